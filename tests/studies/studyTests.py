#!/usr/bin/python3
"""Tests of the parametric-study runner (studies/runStudy.py) on small level-ice beams.

usage: studyTests.py TEST WORKDIR BINDIR
  TEST: dictionaries | skip | rerun | resume | failed | atomic | badDict | lock | ranks | scatter | allrun
  WORKDIR: an empty folder of the build tree (removed first)
  BINDIR: the folder of iceBeamDEM

Each test prints what it checks ('ok' / 'FAIL') and exits 1 on a failure."""
import csv
import json
import os
import shutil
import signal
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
TOP = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(TOP, "postProcessing"))
import iceCases  # noqa: E402
sys.path.insert(0, os.path.dirname(HERE))
from checkList import CheckList  # noqa: E402

RUNNER = os.path.join(TOP, "studies", "runStudy.py")
test, work, bindir = sys.argv[1], os.path.abspath(sys.argv[2]), sys.argv[3]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
check = CheckList()


def study_dict(name, knobs, case="levelIceBeam", arguments="-particles 200", ranks=1, extra_set="",
               figures="slope elastic_slope_N_per_m; firstPeak first_peak_force_N;",
               reference="type measured; values { slope 6.25e6; firstPeak 120e3; }", extra=""):
    folder = os.path.join(work, name)
    os.makedirs(folder, exist_ok=True)
    path = os.path.join(folder, "studyDict")
    with open(path, "w") as f:
        f.write(f"""study {{ case {case}; application iceBeamDEM; ranks {ranks}; arguments ({arguments}); }}
knobs
{{
{knobs}
}}
set {{ "system/controlDict:writeInterval" 10; {extra_set} }}
figures {{ {figures} }}
reference {{ {reference} }}
{extra}
""")
    return folder


def run(folder, *options, wait=True):
    cmd = ["/usr/bin/python3", RUNNER, folder, "-bin", bindir] + list(options)
    if not wait:
        return subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    r = subprocess.run(cmd, capture_output=True, text=True)
    print(f"  $ runStudy.py {os.path.basename(folder)} {' '.join(options)} -> exit {r.returncode}")
    return r


def table(folder, name="results"):
    with open(os.path.join(folder, name, "table.csv")) as f:
        return {r["point"]: r for r in csv.DictReader(f)}


def state(folder, point):
    return json.load(open(os.path.join(folder, "runs", point, "point.json")))


SPEEDS = "platenSpeed { entry constant/beamProperties:platen.speed; values (0.4 0.2); }"


# ---------------------------------------------------------------------------- tests
def test_skip():
    """A second run with nothing changed runs nothing; the table keeps the same figures."""
    s = study_dict("skip", SPEEDS)
    r1 = run(s, "-jobs", "2")
    t1 = table(s)
    check(r1.returncode == 0 and all(r["status"] == "done" for r in t1.values()) and len(t1) == 2,
          f"first run: 2 points done with -jobs 2 ({[r['status'] for r in t1.values()]})")
    logs = {p: os.path.getmtime(os.path.join(s, "runs", p, "log.run")) for p in t1}
    r2 = run(s, "-jobs", "2")
    t2 = table(s)
    check("(2 finished before, 0 to run)" in r2.stdout, "second run: 2 finished before, 0 to run")
    check(all(os.path.getmtime(os.path.join(s, "runs", p, "log.run")) == logs[p] for p in t1),
          "no point's log rewritten")
    check(all(t1[p]["slope"] == t2[p]["slope"] and t1[p]["firstPeak"] == t2[p]["firstPeak"]
              and t1[p]["wall_s"] == t2[p]["wall_s"] for p in t1), "the table's figures and wall times unchanged")
    slopes = [float(t1[p]["slope"]) for p in sorted(t1)]
    check(slopes[0] != slopes[1] and all(x > 1e6 for x in slopes),
          f"the two speeds give different slopes ({slopes})")
    # the reference changed to the finest point ('finer smaller' on the speed): nothing reruns, the
    # reference is the 0.2 m/s point and the 0.4 m/s point's error is against it
    with open(os.path.join(s, "studyDict")) as f:
        text = f.read()
    with open(os.path.join(s, "studyDict"), "w") as f:
        f.write(text.replace("values (0.4 0.2);", "values (0.4 0.2); finer smaller;")
                .replace("type measured; values { slope 6.25e6; firstPeak 120e3; }", "type finest;"))
    r3 = run(s)
    t3 = table(s)
    ref = t3["platenSpeed-0.2"]
    err = float(t3["platenSpeed-0.4"]["slope_error"])
    want = float(t3["platenSpeed-0.4"]["slope"]) / float(ref["slope"]) - 1
    check("0 to run" in r3.stdout and ref["is_reference"] == "1" and abs(err - want) < 1e-5 and abs(err) > 1e-3,
          f"'finer' added: nothing rerun, error against the 0.2 m/s point {err:.5f} (= {want:.5f})")


def test_rerun():
    """A changed input of the case reruns every point; a new knob value runs only its point."""
    case = iceCases.copy_case(os.path.join(TOP, "cases", "levelIceBeam"), os.path.join(work, "cases", "myBeam"))
    shutil.copy(os.path.join(TOP, "cases", "levelIceBeam", "Allrun"), case)
    s = study_dict("rerun", SPEEDS, case=case)
    run(s)
    t1 = table(s)
    made1 = {p: state(s, p)["madeFrom"] for p in t1}
    iceCases.set_entry(os.path.join(case, "constant", "beamProperties"), "packing.seed", 2)
    r2 = run(s)
    t2 = table(s)
    check("(0 finished before, 2 to run)" in r2.stdout, "packing.seed changed in the case: both points rerun")
    check(all(state(s, p)["madeFrom"] != made1[p] for p in t1), "their madeFrom changed")
    check(all(t1[p]["slope"] != t2[p]["slope"] for p in t1),
          f"another packing, other slopes ({[t1[p]['slope'] for p in t1]} -> {[t2[p]['slope'] for p in t2]})")
    with open(os.path.join(s, "studyDict")) as f:
        text = f.read()
    with open(os.path.join(s, "studyDict"), "w") as f:
        f.write(text.replace("values (0.4 0.2);", "values (0.4 0.2 0.3);"))
    r3 = run(s)
    t3 = table(s)
    check("(2 finished before, 1 to run)" in r3.stdout and t3["platenSpeed-0.3"]["status"] == "done"
          and all(t3[p]["slope"] == t2[p]["slope"] for p in t2), "a third speed: only its point runs")


def test_resume():
    """A runner stopped by SIGTERM after a point's checkpoint records the point as killed; -resume
    continues it from the checkpoint to the uninterrupted run's figures exactly."""
    knobs = "platenSpeed { entry constant/beamProperties:platen.speed; values (0.05); }"
    extra = '"system/controlDict:checkpointInterval" 0.004;'
    whole = study_dict("whole", knobs, arguments="-particles 400", extra_set=extra)
    stopped = study_dict("stopped", knobs, arguments="-particles 400", extra_set=extra)
    run(whole)
    point = "platenSpeed-0.05"
    proc = run(stopped, wait=False)
    checkpoint = os.path.join(stopped, "runs", point, "levelIceBeam", "DEM", "checkpoint", "iceBeamDEM.checkpoint")
    start = time.time()
    while not os.path.exists(checkpoint) and proc.poll() is None and time.time() - start < 120:
        time.sleep(0.02)
    time.sleep(0.3)
    proc.send_signal(signal.SIGTERM)
    out = proc.communicate()[0]
    print("  " + out.strip().replace("\n", "\n  "))
    check(proc.returncode == 143 and state(stopped, point)["status"] == "killed",
          f"SIGTERM: exit {proc.returncode} (143), point {state(stopped, point)['status']} (killed)")
    check(table(stopped)[point]["status"] == "killed", "the table says killed")
    left = []
    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            if stopped.encode() in open(f"/proc/{pid}/cmdline", "rb").read():
                left.append(pid)
        except OSError:
            pass
    check(not left, f"the runner returned after the point's processes had ended (left: {left})")
    r = run(stopped, "-resume")
    log = open(os.path.join(stopped, "runs", point, "log.run")).read()
    check(r.returncode == 0 and "Resumed from the checkpoint at step" in log,
          "-resume: resumed from the checkpoint" + ("" if r.returncode == 0 else ": " + r.stderr.strip()))
    a = json.load(open(os.path.join(whole, "runs", point, "levelIceBeam", "postProcessing", "summary.json")))
    b = json.load(open(os.path.join(stopped, "runs", point, "levelIceBeam", "postProcessing", "summary.json")))
    keys = ["elastic_slope_N_per_m", "first_peak_force_N", "peak_force_N", "steps"]
    check(all(a[k] == b[k] for k in keys), "figures equal to the uninterrupted run's to the last bit: " +
          ", ".join(f"{k} {a[k]} / {b[k]}" for k in keys))
    # the travel is the platen's position, summed in another order after a resume: a few ulp
    t = "travel_at_peak_m"
    check(abs(a[t] - b[t]) <= 1e-14 * abs(a[t]), f"{t} {a[t]} / {b[t]} (1e-14)")
    ta, tb = table(whole)[point], table(stopped)[point]
    check(ta["slope"] == tb["slope"] and ta["firstPeak"] == tb["firstPeak"] and tb["status"] == "done",
          "the tables agree")


def test_failed():
    """A point the program refuses is recorded as failed with the program's message and kept;
    -retry-failed runs it again."""
    knobs = ("timeStepFactor { entry constant/iceProperties:timeStep.factor; values (0.25 0.6); finer smaller; }")
    s = study_dict("failed", knobs)
    r = run(s)
    t = table(s)
    bad = t["timeStepFactor-0.6"]
    check(r.returncode == 3, f"exit 3 when a point failed (got {r.returncode})")
    check(bad["status"] == "failed" and "timeStep.factor" in bad["error"] and "unsafe" in bad["error"]
          and "Primary job" not in bad["error"], f"failed with the program's message: {bad['error'][:160]}")
    check(t["timeStepFactor-0.25"]["status"] == "done" and float(t["timeStepFactor-0.25"]["slope"]) > 1e6,
          "the other point done")
    when = state(s, "timeStepFactor-0.6")["finished_at"]
    mtime = os.path.getmtime(os.path.join(s, "runs", "timeStepFactor-0.6", "log.run"))
    r2 = run(s)
    check("(2 finished before, 0 to run)" in r2.stdout and r2.returncode == 3 and
          os.path.getmtime(os.path.join(s, "runs", "timeStepFactor-0.6", "log.run")) == mtime,
          "not rerun without -retry-failed (still reported, exit 3)")
    time.sleep(1.1)
    r3 = run(s, "-retry-failed")
    check("(1 finished before, 1 to run)" in r3.stdout and state(s, "timeStepFactor-0.6")["finished_at"] != when
          and table(s)["timeStepFactor-0.6"]["status"] == "failed", "-retry-failed reruns it (fails again)")


def test_atomic():
    """The table is rewritten after every point, atomically: a reader polling it all the time sees
    only whole tables (every point a row, every row every column) and the done count never falls;
    the HDF5 table holds the CSV's numbers."""
    s = study_dict("atomic", "platenSpeed { entry constant/beamProperties:platen.speed; values (0.4 0.3 0.2); }")
    proc = run(s, wait=False)
    path = os.path.join(s, "results", "table.csv")
    reads, broken, counts = 0, 0, []
    while proc.poll() is None:
        time.sleep(0.002)   # about 500 reads a second, leaving the core to the runs
        try:
            with open(path) as f:
                text = f.read()
        except FileNotFoundError:
            continue
        reads += 1
        rows = list(csv.DictReader(text.splitlines()))
        if len(rows) != 3 or any(None in r or None in r.values() for r in rows) or not text.endswith("\n"):
            broken += 1
        else:
            counts.append(sum(r["status"] == "done" for r in rows))
    proc.communicate()
    check(reads > 100 and broken == 0, f"{reads} reads while it ran, {broken} broken tables")
    check(counts == sorted(counts) and counts[-1] == 3 and len(set(counts)) >= 3,
          f"done counts seen: {sorted(set(counts))} (rising to 3, at least 3 distinct)")
    left = [n for n in os.listdir(os.path.join(s, "results")) if "tmp" in n]
    check(not left, f"no temporary files left ({left})")
    import h5py
    t = table(s)
    with h5py.File(os.path.join(s, "results", "table.h5")) as f:
        points = [p.decode() if isinstance(p, bytes) else p for p in f["points/point"][()]]
        ok = all(abs(f["points/slope"][i] - float(t[p]["slope"])) <= 1e-5 * abs(float(t[p]["slope"]))
                 and f["points/peak_rss_MiB"][i] > 10 and f["points/particle_steps_per_s"][i] > 1e4
                 for i, p in enumerate(points))
        check(ok and len(points) == 3 and f.attrs["case"] == "levelIceBeam",
              "table.h5: the CSV's slopes, peak RSS > 10 MiB, particle-steps/s > 1e4")
    png = os.path.join(s, "results", "study.png")
    check(os.path.isfile(png) and 5e3 < os.path.getsize(png) < 300e3, "study.png written, 5-300 kB")


def test_bad_dict():
    """Bad study dictionaries and command lines: exit 1 (2 for the command line), the file, line and
    entry named, nothing run."""
    good = study_dict("bad", SPEEDS)
    path = os.path.join(good, "studyDict")
    text = open(path).read()
    cases = [
        ("unknown keyword", text.replace("ranks 1;", "rank 1;"), "1", "study.rank", "did you mean 'ranks'"),
        ("keyword twice", text.replace("ranks 1;", "ranks 1; ranks 2;"), "1", "study.ranks", "written twice"),
        ("missing ';'", text.replace("values (0.4 0.2); }", "values (0.4 0.2) }"), "4", "knobs.platenSpeed.values",
         "')' and ';'"),
        ("missing figures", text.replace("figures {", "figurez {"), "7", "figurez", "unknown keyword"),
        ("entry not in the case", text.replace("platen.speed", "platen.sped"), "4", "knobs.platenSpeed.entry",
         "platen.sped is not in levelIceBeam/constant/beamProperties"),
        ("no such case", text.replace("case levelIceBeam", "case levelIceBeem"), "1", "study.case", "no case"),
        ("default of an option", text.replace(SPEEDS, "particles { option -particles; values (default 200); }"),
         "4", "knobs.particles.values", "'default' needs the case's own value"),
        ("quick not among values", text.replace("values (0.4 0.2);", "values (0.4 0.2); quick (0.1);"), "4",
         "knobs.platenSpeed.quick", "0.1 not among the values"),
        ("finest without finer", text.replace("type measured; values { slope 6.25e6; firstPeak 120e3; }",
                                              "type finest;"), "8", "reference.type",
         "needs at least one knob with 'finer"),
        ("figure named like a column", text.replace("slope elastic", "wall_s elastic"), "7", "figures.wall_s",
         "cannot be named"),
        ("a directive", text.replace("set {", "#include \"x\"\nset {"), "6", None, "directives"),
        ("missing entry", text.replace("figures { slope elastic_slope_N_per_m; firstPeak first_peak_force_N; }", ""),
         "1", "figures", "missing entry"),
        ("ladder count", text.replace("values (0.4 0.2);", "ladder { from 0.4; factor 0.5; count 0; }"), "4",
         "knobs.platenSpeed.ladder.count", "needs a number > 0"),
        ("finer order missing a value", text.replace("values (0.4 0.2);", "values (0.4 0.2); finer (0.4);"), "4",
         "knobs.platenSpeed.finer", "needs the values (0.4, 0.2) each once"),
        ("caseValue of an entry", text.replace("values (0.4 0.2);", "values (0.4 0.2); caseValue 0.4;"), "4",
         "knobs.platenSpeed.caseValue", "only for an 'option' knob"),
    ]
    for what, bad_text, line, entry, words in cases:
        folder = os.path.join(work, "bad_" + what.replace(" ", "_").replace("'", "").replace(";", ""))
        os.makedirs(folder)
        with open(os.path.join(folder, "studyDict"), "w") as f:
            f.write(bad_text)
        r = run(folder)
        msg = r.stderr.strip()
        where = f"{os.path.join(folder, 'studyDict')}:{line}:"
        ok = r.returncode == 1 and where in msg and (entry is None or entry in msg) and words in msg \
            and "Traceback" not in msg and not os.path.exists(os.path.join(folder, "runs"))
        check(ok, f"{what}: {msg}")
    r = run(good, "-jobs", "0")
    check(r.returncode == 2 and "-jobs" in r.stderr and "whole number" in r.stderr, "-jobs 0: exit 2, named")
    r = run(os.path.join(work, "nothing"))
    check(r.returncode == 1 and "cannot read" in r.stderr, "no study dictionary: exit 1, 'cannot read'")


def test_lock():
    """A second runner on the same study folder is refused while the first runs."""
    s = study_dict("lock", "platenSpeed { entry constant/beamProperties:platen.speed; values (0.1); }",
                   arguments="-particles 400")
    first = run(s, wait=False)
    lock = os.path.join(s, "runs", ".lock")
    start = time.time()
    while not (os.path.exists(lock) and open(lock).read().strip()) and time.time() - start < 30:
        time.sleep(0.02)
    second = run(s)
    running = first.poll() is None
    first.communicate()
    check(running and second.returncode == 1 and "another runner" in second.stderr
          and str(first.pid) in second.stderr and lock in second.stderr,
          f"second runner refused while the first ran: {second.stderr.strip()}")
    check(first.returncode == 0 and table(s)["platenSpeed-0.1"]["status"] == "done", "the first finished")
    third = run(s)
    check(third.returncode == 0 and "0 to run" in third.stdout, "after it, a runner may start (lock released)")
    # a runner killed outright (SIGKILL) leaves its point running: the point keeps the lock
    shutil.rmtree(os.path.join(s, "runs", "platenSpeed-0.1"))
    first = run(s, wait=False)
    log = os.path.join(s, "runs", "platenSpeed-0.1", "log.run")
    start = time.time()
    while not (os.path.exists(log) and "iceBeamDEM:" in open(log).read()) and time.time() - start < 60:
        time.sleep(0.02)
    first.kill()
    first.communicate()
    second = run(s)
    point_ran_on = "End:" not in open(log).read()
    check(point_ran_on and second.returncode == 1 and "a point it started still runs" in second.stderr,
          f"runner SIGKILLed: its orphaned point holds the lock, a new runner is refused (point still ran: "
          f"{point_ran_on}; second runner: exit {second.returncode} {second.stderr.strip()})")
    start = time.time()
    while "End:" not in open(log).read() and time.time() - start < 120:
        time.sleep(0.1)
    time.sleep(1)
    fourth = run(s)
    check(fourth.returncode == 0 and table(s)["platenSpeed-0.1"]["status"] == "done",
          "once the orphaned point ended, a runner starts and finishes the point")


def test_ranks():
    """The same 200-particle beam study on 1 and 2 ranks: the same figures (the force is identical
    before the first break), the table's columns right, the errors against the measured field
    reference computed from the file's values."""
    figures = "slope elastic_slope_N_per_m; firstPeak first_peak_force_N;"
    reference = ('type measured; file "$SHARED/data/levelIceBeamField.csv"; '
                 "quantities { slope elastic_slope; firstPeak peak_load; }")
    tables = {}
    for np_ in (1, 2):
        s = study_dict(f"ranks{np_}", SPEEDS, ranks=np_, figures=figures, reference=reference)
        r = run(s, "-jobs", "1")
        check(r.returncode == 0, f"{np_} rank(s): exit {r.returncode}")
        tables[np_] = table(s)
    # the peak RSS is the point's own: the same run measured directly (GNU time on mpirun) agrees
    # within 25 %, well below the runner's own memory (numpy, h5py, matplotlib loaded: > 60 MiB more)
    direct = iceCases.copy_case(os.path.join(TOP, "cases", "levelIceBeam"), os.path.join(work, "direct", "beam"))
    iceCases.set_entry(os.path.join(direct, "system", "controlDict"), "writeInterval", 10)
    rss = os.path.join(work, "direct", "rss")
    subprocess.run(["/usr/bin/time", "-f", "%M", "-o", rss, "mpirun", "--allow-run-as-root", "-np", "1",
                    os.path.join(bindir, "iceBeamDEM"), "-case", direct, "-particles", "200", "-platenSpeed", "0.4"],
                   capture_output=True, check=True)
    direct_mib = float(open(rss).read().split()[-1]) / 1024
    table_mib = float(tables[1]["platenSpeed-0.4"]["peak_rss_MiB"])
    check(abs(table_mib / direct_mib - 1) < 0.25, f"peak RSS {table_mib:.1f} MiB, measured directly {direct_mib:.1f} MiB")
    for p in tables[1]:
        a, b = tables[1][p], tables[2][p]
        ds = abs(float(a["slope"]) / float(b["slope"]) - 1)
        dp = abs(float(a["firstPeak"]) / float(b["firstPeak"]) - 1)
        check(ds < 1e-3 and dp < 0.02, f"{p}: slope 1 vs 2 ranks {ds:.2e} (< 1e-3), first peak {dp:.2e} (< 0.02)")
        check(a["ranks"] == "1" and b["ranks"] == "2" and int(a["n_particles"]) == 200 and int(a["n_steps"]) > 1000,
              f"{p}: ranks 1/2, 200 particles, {a['n_steps']} steps")
        for t in (a, b):
            want = float(t["slope"]) / 6.25e6 - 1
            check(abs(float(t["slope_error"]) - want) < 1e-5 and abs(float(t["firstPeak_error"])
                  - (float(t["firstPeak"]) / 120e3 - 1)) < 1e-5,
                  f"errors against the field: slope {t['slope_error']} (= {want:.6f})")
            check(float(t["wall_s"]) > 0 and float(t["peak_rss_MiB"]) > 10 and t["git_revision"]
                  and float(t["load_average"]) >= 0, f"wall {t['wall_s']} s, peak RSS {t['peak_rss_MiB']} MiB")


def test_scatter():
    """The seed scatter at the chosen point: its other packings run beside it, each figure's relative
    standard deviation over the three is on every row (computed here again from the rows), an
    error within two of them is flagged, the scatter points are no reference and no case default;
    the case's own seed among the scatter's values is refused."""
    scatter = ("scatter { seed { entry constant/beamProperties:packing.seed; values (2 3); } "
               "at { platenSpeed 0.2; } }")
    s = study_dict("scatter", SPEEDS, extra=scatter)
    r = run(s, "-jobs", "2")
    t = table(s)
    check(r.returncode == 0 and len(t) == 4 and all(x["status"] == "done" for x in t.values()),
          f"4 points done (2 speeds, seeds 2 and 3 at 0.2 m/s): {sorted(t)}")
    group = [t["platenSpeed-0.2"], t["platenSpeed-0.2_seed-2"], t["platenSpeed-0.2_seed-3"]]
    check([x["is_scatter"] for x in group] == ["0", "1", "1"] and [x["seed"] for x in group] == ["1", "2", "3"]
          and t["platenSpeed-0.4"]["seed"] == "1", "the seed column: the case's 1, then 2 and 3")
    for name in ("slope", "firstPeak"):
        values = [float(x[name]) for x in group]
        mean = sum(values) / 3
        sd = (sum((v - mean) ** 2 for v in values) / 2) ** 0.5 / abs(mean)
        check(len(set(values)) == 3, f"{name}: the three packings differ ({values})")
        for x in t.values():
            got = float(x[name + "_scatter"])
            flag = int(abs(float(x[name + "_error"])) <= 2 * sd)
            check(abs(got / sd - 1) < 1e-4 and x[name + "_within_scatter"] == str(flag),
                  f"{x['point']}: {name} scatter {got:.4g} (= {sd:.4g}), within 2 sd: {x[name + '_within_scatter']}")
    check(all(x["is_case_default"] == "0" for x in group[1:]), "a scatter point is no case default")
    own = study_dict("scatterOwnSeed", SPEEDS, extra=scatter.replace("(2 3)", "(1 2)"))
    r = run(own, "-list")
    check(r.returncode == 1 and "scatter.seed.values" in r.stderr and "the case's own value" in r.stderr,
          f"the case's own seed among the scatter's values refused: {r.stderr.strip()}")


def test_allrun():
    """A study of a case's ./Allrun (freezeBondTension -smoke: two tests) in a mirror of the project:
    figures from list items of its summary, errors against the measured values that the same
    summary carries (reference `summary`), a point the Allrun refuses recorded with its message."""
    folder = os.path.join(work, "allrun")
    os.makedirs(folder)
    with open(os.path.join(folder, "studyDict"), "w") as f:
        f.write("""study { case freezeBondTension; allrun (-smoke); cores 2; }
knobs { particleDiameter { entry constant/tensionTestProperties:specimen.particleDiameter; values (0.0225 0.02); } }
figures { first runs[0].simulated_kPa; second runs[1].simulated_kPa; slope fits_by_submersion_min.30.simulated.slope; }
reference { type summary; keys { first runs[0].mean_kPa; second runs[1].mean_kPa; } }
""")
    r = run(folder, "-jobs", "1")
    t = table(folder)
    check(r.returncode == 0 and len(t) == 2 and all(x["status"] == "done" for x in t.values()),
          f"2 Allrun points done: {[x['status'] for x in t.values()]} {r.stdout[-300:]}")
    for label, x in t.items():
        case = os.path.join(folder, "runs", label, "mirror", "cases", "freezeBondTension")
        summary = json.load(open(os.path.join(case, "postProcessing", "summary.json")))
        runs = summary["runs"]
        for i, name in enumerate(("first", "second")):
            want = runs[i]["simulated_kPa"] / runs[i]["mean_kPa"] - 1
            check(abs(float(x[name]) / runs[i]["simulated_kPa"] - 1) < 1e-5
                  and abs(float(x[name + "_error"]) - want) < 1e-5,
                  f"{label}: {name} {x[name]} kPa, error {x[name + '_error']} (= {want:.6f} against the measured mean)")
        check(x["slope_error"] == "nan" and float(x["slope"]) > 0 and x["ranks"] == "2",
              f"{label}: a figure without reference has no error; 2 cores")
        d = iceCases.get_entry(os.path.join(case, "constant", "tensionTestProperties"), "specimen.particleDiameter")
        check(d.strip() == x["particleDiameter"], f"{label}: the mirror's case runs diameter {d.strip()}")
    stage = os.path.join(work, "allrunStage")
    os.makedirs(stage)
    with open(os.path.join(stage, "studyDict"), "w") as f:
        f.write("""study { case freezeBondTension; allrun (-smoke); stages ("cases/freezeBondTension/keels/none"); }
knobs { np { option -np; values (1); } }
figures { first runs[0].simulated_kPa; }
reference { type none; }
""")
    r = run(stage)
    check(r.returncode == 1 and "no saved stage cases/freezeBondTension/keels/none" in r.stderr
          and not os.path.isdir(os.path.join(stage, "runs", "np-1")),
          f"a saved stage that is not built refused before any point runs: {r.stderr.strip()[:160]}")
    template = os.path.join(work, "allrunTemplate")
    os.makedirs(template)
    with open(os.path.join(template, "studyDict"), "w") as f:
        f.write("""study { case freezeBondTension; allrun (-smoke); summary "runs/${speed}/summary.json"; }
knobs { np { option -np; values (1); } }
figures { first runs[0].simulated_kPa; }
reference { type none; }
""")
    r = run(template)
    check(r.returncode == 1 and "study.summary" in r.stderr and "'${speed}' names no knob (np)" in r.stderr
          and not os.path.isdir(os.path.join(template, "runs")),
          f"a templated summary path naming no knob refused: {r.stderr.strip()[:160]}")
    bad = os.path.join(work, "allrunBad")
    os.makedirs(bad)
    with open(os.path.join(bad, "studyDict"), "w") as f:
        f.write("""study { case freezeBondTension; allrun (-smoke); }
knobs { np { option -np; values (0); } }
figures { first runs[0].simulated_kPa; }
reference { type none; }
""")
    r = run(bad)
    t = table(bad)
    check(r.returncode == 3 and t["np-0"]["status"] == "failed" and "-np" in t["np-0"]["error"],
          f"-np 0 refused by the Allrun, the point failed with its message: {t['np-0']['error']}")


def test_dictionaries():
    """Every committed study dictionary still reads against its case (an entry the case renamed, a
    value no longer valid), and its committed table has a column for each knob and figure."""
    import glob
    sys.path.insert(0, os.path.join(TOP, "studies"))
    import studyDict
    paths = glob.glob(os.path.join(TOP, "studies", "*", "studyDict"))
    # a case's studies at any depth, but not the points' copies under runs/ (their mirrors hold the
    # whole project, links included: a recursive glob would walk them all)
    for folder, dirs, names in os.walk(os.path.join(TOP, "cases")):
        dirs[:] = [d for d in dirs if d != "runs"]
        paths += [os.path.join(folder, n) for n in names if n == "studyDict"]
    paths = sorted(paths)
    check(len(paths) >= 8, f"{len(paths)} study dictionaries found")
    for path in paths:
        rel = os.path.relpath(path, TOP)
        try:
            study = studyDict.read_study(path)
        except studyDict.StudyDictError as e:
            check(False, f"{rel}: {e}")
            continue
        table = os.path.join(os.path.dirname(path), "results", "table.csv")
        if not os.path.isfile(table):
            print(f"  {rel}: reads; no committed table")
            continue
        with open(table) as f:
            columns = next(csv.reader(f))
        wanted = [k.name for k in study.knobs] + [n for n, _ in study.figures]
        if study.scatter:
            wanted += [study.scatter.name, "is_scatter"]
        missing = [w for w in wanted if w not in columns]
        check(not missing, f"{rel}: reads; its table has every knob and figure{' (missing ' + ', '.join(missing) + ')' if missing else ''}")


tests = {"dictionaries": test_dictionaries, "skip": test_skip, "rerun": test_rerun, "resume": test_resume, "failed": test_failed,
         "atomic": test_atomic, "badDict": test_bad_dict, "lock": test_lock, "ranks": test_ranks,
         "scatter": test_scatter, "allrun": test_allrun}
tests[test]()
check.finish()
