#!/usr/bin/python3
"""Runs a parametric study of a case: every combination of the knobs of a study dictionary, each
point in its own copy of the case, side by side (-jobs N); one table (CSV + HDF5) and one PNG.

usage: runStudy.py STUDY [-jobs N] [-quick] [-resume] [-retry-failed] [-out FOLDER] [-list] [-plot] [-bin FOLDER]

  STUDY          a study dictionary, or a folder holding one named `studyDict` (studies/README.md)
  -jobs N        points run side by side (default 1; each takes `ranks` cores)
  -quick         only each knob's `quick` values (tables in FOLDER/quick instead of FOLDER/results)
  -resume        a point killed after a checkpoint continues from it (the application's -resume)
                 instead of starting again
  -retry-failed  run again the points recorded as failed (otherwise kept as failed)
  -out FOLDER    where the point runs (FOLDER/runs) and the tables go; default: the study's folder
  -list          print the points and their state; run nothing
  -plot          rewrite the table and the PNG from the points run so far; run nothing
  -bin FOLDER    where the applications are (default: build/demModels of this checkout)

A point is skipped when its folder holds a finished run made from the same inputs (`madeFrom`:
knob values, command, the case's input files and what they include of cases/common); a changed input reruns it. The
table and the PNG are rewritten (atomically) after every point. Exit status: 0 when every point
finished, 3 when some failed (recorded in the table with the application's message), 1 on an
error of the study dictionary or another runner on the same folder, 2 on a bad command line,
143 when stopped by SIGTERM/SIGINT (the running points are recorded as killed; -resume continues them).
"""
import argparse
import concurrent.futures
import csv
import datetime
import fcntl
import hashlib
import io
import itertools
import json
import os
import re
import shutil
import signal
import statistics
import subprocess
import sys
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import studyDict  # noqa: E402
from studyDict import iceCases  # noqa: E402

MiB = 1024.0 * 1024.0


# ---------------------------------------------------------------------------- points
class Point:
    def __init__(self, study, values, seed=None):
        self.values = values   # {knob name: text}
        self.seed = seed       # the scatter knob's value of a scatter point (the chosen point, another seed)
        label = "_".join(f"{k.name}-{values[k.name]}" for k in study.knobs)
        if seed is not None:
            label += f"_{study.scatter.name}-{seed}"
        self.label = label.replace("/", "+")
        self.state = {}


def make_points(study, quick):
    lists = [(k.quick if quick and k.quick else k.values) for k in study.knobs]
    points = [Point(study, dict(zip([k.name for k in study.knobs], combo))) for combo in itertools.product(*lists)]
    # the scatter: the chosen point again with each other seed, when this run holds the chosen point
    if study.scatter and any(p.values == study.scatter_at for p in points):
        seeds = study.scatter.quick if quick and study.scatter.quick is not None else study.scatter.values
        points += [Point(study, dict(study.scatter_at), seed) for seed in seeds]
    return points


def _hash_file(path):
    h = hashlib.sha256()
    with open(path, "rb") as f:
        h.update(f.read())
    return h.hexdigest()


_GENERATED = re.compile(r".*\.h5$|.*\.data$|.*\.restart\..*|^checkpoint.*|^variables\.generated$|^platen\.stl$|.*\.tmp$")


def input_files(study):
    """{name: sha256} of the case's inputs (constant/, system/, DEM/ as copy_case copies them) and of
    the files of cases/common that its dictionaries #include (not the calibrations of other cases)."""
    files = {}
    if study.allrun is not None:   # the Allrun and the case's scripts make the point too (not results/ or README)
        import caseMirror
        for case in [study.case_name] + study.siblings:
            # a sibling's results/ may be read (the punch reads the rubble beam's summary); the case's own not
            skipped = ("results", "README.md", "studies") if case == study.case_name else ("README.md",)
            for rel in caseMirror.case_files(iceCases.TOP, os.path.join("cases", case)):
                inner = os.path.relpath(rel, os.path.join("cases", case)).split(os.sep)[0]
                if inner not in skipped:
                    files[rel] = _hash_file(os.path.join(iceCases.TOP, rel))
        for stage in study.stages:   # the saved stages (HDF5) a point reuses instead of building them
            for folder, dirs, names in os.walk(os.path.join(iceCases.TOP, stage)):
                dirs.sort()
                for name in sorted(n for n in names if n.endswith(".h5")):
                    path = os.path.join(folder, name)
                    files["stage:" + os.path.relpath(path, iceCases.TOP)] = _hash_file(path)
        return files
    for sub in ("constant", "system", "DEM"):
        for folder, dirs, names in os.walk(os.path.join(study.case, sub)):
            rel = os.path.relpath(folder, study.case)
            if sub == "DEM":
                dirs[:] = [d for d in dirs if not _GENERATED.match(d)]
                names = [n for n in names if not _GENERATED.match(n)]
            dirs.sort()
            for name in sorted(names):
                files[os.path.join("case", rel, name)] = _hash_file(os.path.join(folder, name))
    for path in iceCases.input_files([os.path.join(study.case, "constant"), os.path.join(study.case, "system")]):
        if os.path.relpath(path, study.case).startswith(os.pardir):
            files[os.path.relpath(path, os.path.dirname(study.case))] = _hash_file(path)
    return files


def _knobs_of(study, point):
    """(knob, value) of every knob a point sets: the study's, and the scatter's for a scatter point."""
    out = [(k, point.values[k.name]) for k in study.knobs]
    if point.seed is not None:
        out.append((study.scatter, point.seed))
    return out


def command(study, point):
    args = list(study.allrun if study.allrun is not None else study.arguments)
    for k, value in _knobs_of(study, point):
        if k.option:
            args += [k.option, value]
    if study.allrun is not None:
        return ["./Allrun"] + args
    return [study.application, "-np", str(study.ranks)] + args


def expand(study, knob, values):
    """The value a knob writes into its entry: its template with ${knob} and ${STUDY} filled in
    (an absolute path where it starts with ${STUDY}), or the knob's value itself."""
    if knob.template is None:
        return values[knob.name]
    return re.sub(r"\$\{(\w+)\}", lambda m: study.folder if m.group(1) == "STUDY" else values[m.group(1)],
                  knob.template)


_UPSTREAM_HASHES = {}


def upstream_files(study, point):
    """{path: sha256} of the saved stages a point reads by a templated path (a keel): a changed
    file makes the point again. A file that is not there yet is recorded as missing."""
    out = {}
    for k in study.knobs:
        if k.template is not None and "${STUDY}" in k.template:
            path = expand(study, k, point.values)
            rel = os.path.relpath(path, study.folder)
            if path not in _UPSTREAM_HASHES:
                _UPSTREAM_HASHES[path] = _hash_file(path) if os.path.isfile(path) else "missing"
            out[rel] = _UPSTREAM_HASHES[path]
    return out


def with_entries(study, point):
    """The entries the knobs' `with` blocks set beside the point's values."""
    return [e for k in study.knobs for e in k.with_entries.get(point.values[k.name], [])]


def made_from(study, point, inputs):
    """The fingerprint of what makes a point: knob values, command, fixed entries, the case's inputs,
    the post-processing and the files the point reads by a templated path."""
    entries = study.fixed + with_entries(study, point)
    record = {"knobs": point.values, "command": command(study, point),
              "set": [list(map(str, f)) for f in entries], "inputs": inputs}
    if point.seed is not None:
        record["scatter"] = {study.scatter.name: point.seed}
    if study.post_process:
        record["postProcess"] = study.post_process
    upstream = upstream_files(study, point)
    for file, dotted, value, _ in entries:
        if dotted == "#include":   # the generated dictionary a point includes: its content
            path = os.path.normpath(os.path.join(study.case, os.path.dirname(file), value))
            upstream[os.path.relpath(path, iceCases.TOP)] = _hash_file(path) if os.path.isfile(path) else "missing"
    if upstream:
        record["upstream"] = upstream
    return hashlib.sha256(json.dumps(record, sort_keys=True).encode()).hexdigest()


def write_json_atomically(path, data):
    iceCases.write_atomically(path, json.dumps(data, indent=1, sort_keys=True) + "\n")


def _mpirun_line(line):
    s = line.strip()
    return (not s or set(s) <= set("-=*") or "mpirun" in s or "Primary job" in s or "MPI_ABORT" in s
            or "MPI_COMM_WORLD" in s or "process returned" in s or "non-zero exit" in s
            or "abort" in s.lower() and "mpi" in s.lower() or s.startswith("Per user-direction")
            or "with errorcode" in s or "NOTE: invoking" in s or "You may or may not see output" in s
            or "exited on signal" in s or "Process name:" in s or "Exit code:" in s
            or "the job to be terminated" in s)


def error_tail(log, lines=3):
    """The application's own message: the last lines of its log, MPI's banner left out."""
    try:
        text = open(log, errors="replace").read().splitlines()
    except OSError:
        return "no log"
    keep = [l.strip() for l in text if not _mpirun_line(l)]
    marks = [i for i, l in enumerate(keep) if "FATAL" in l or "ERROR" in l or "Error" in l]
    if marks:   # the application's error block: from its heading on
        keep = keep[marks[-1]:]
    return " | ".join(keep[-lines:]) if keep else "no message in the log"


def _dig(data, dotted):
    """data's item at a dotted key; `runs[3]` is a list's item."""
    for part in re.findall(r"[^.\[\]]+|\[\d+\]", dotted):
        if part.startswith("["):
            index = int(part[1:-1])
            if not isinstance(data, list) or index >= len(data):
                return None
            data = data[index]
        elif not isinstance(data, dict) or part not in data:
            return None
        else:
            data = data[part]
    return data


# ---------------------------------------------------------------------------- the runner
class Runner:
    def __init__(self, study, args):
        self.study, self.args = study, args
        self.out = os.path.abspath(args.out or study.folder)
        self.runs = os.path.join(self.out, "runs")
        self.tables = os.path.join(self.out, "quick" if args.quick else "results")
        self.points = make_points(study, args.quick)
        self.inputs = input_files(study)
        self.lock = threading.Lock()
        self.running = {}   # label -> Popen
        self.stopping = False
        self.revision = iceCases.git_revision()
        self.run_walls = []
        self.lock_fd = None

    # -- state of one point
    def folder(self, p):
        return os.path.join(self.runs, p.label)

    def load_state(self, p):
        path = os.path.join(self.folder(p), "point.json")
        try:
            p.state = json.load(open(path))
        except (OSError, ValueError):
            p.state = {}
        p.fingerprint = made_from(self.study, p, self.inputs)
        return p.state

    def case(self, p):
        """The point's case: its copy, or for an Allrun study the case in the point's mirror of the project
        (POINT/mirror/cases/CASE, so that the Allrun's ../.. finds build/ and postProcessing/)."""
        if self.study.allrun is not None:
            return os.path.join(self.folder(p), "mirror", "cases", self.study.case_name)
        return os.path.join(self.folder(p), self.study.case_name)

    def summary_file(self, p):
        if self.study.summary_by:   # the path that the point's value of a knob names
            by, table = self.study.summary_by
            if by in p.values:
                return os.path.join(self.case(p), table[p.values[by]])
            # the scatter knob: a scatter point's seed, the case's own seed on every other point
            return os.path.join(self.case(p), table[p.seed if p.seed is not None else self.study.scatter.case_value])
        path = re.sub(r"\$\{(\w+)\}", lambda m: p.values[m.group(1)], self.study.summary)   # a templated path
        return os.path.join(self.case(p), path)

    def finished(self, p):
        """Whether the point's case holds a finished summary (not one marked "complete": false)."""
        try:
            return json.load(open(self.summary_file(p))).get("complete", True) is not False
        except (OSError, ValueError, AttributeError):
            return False

    def save_state(self, p):
        write_json_atomically(os.path.join(self.folder(p), "point.json"), p.state)

    def verdict(self, p):
        """What to do with a point: 'done', 'failed' (kept), 'resume', 'run'."""
        s = p.state
        if s.get("madeFrom") != p.fingerprint:
            return "run"
        case = self.case(p)
        if s.get("status") == "done" and self.finished(p):
            return "done"
        if s.get("status") == "failed" and not self.args.retry_failed:
            return "failed"
        checkpoint = os.path.join(case, "DEM", "checkpoint")
        # 'running': the runner itself was killed (SIGKILL, a reboot); the lock says no runner holds it now
        if self.args.resume and self.study.allrun is None and s.get("status") in ("killed", "running") and os.path.isdir(checkpoint) \
                and os.listdir(checkpoint):
            return "resume"
        return "run"

    # -- running one point
    def prepare(self, p):
        if self.study.allrun is not None:
            import caseMirror
            case, _ = caseMirror.make_mirror(iceCases.TOP, getattr(self.study, "build", iceCases.BUILD),
                                             self.folder(p), self.study.case_name, name="mirror", skip=("results",))
            for sibling in self.study.siblings:   # whole: their results/ may be read
                caseMirror.copy_folder(iceCases.TOP, os.path.join("cases", sibling),
                                       os.path.join(self.folder(p), "mirror"))
            for stage in self.study.stages:   # a keel built once, reused by every point (its Allrun checks it)
                shutil.copytree(os.path.join(iceCases.TOP, stage), os.path.join(self.folder(p), "mirror", stage),
                                dirs_exist_ok=True)
        else:
            case = iceCases.copy_case(self.study.case, self.case(p))
        for file, dotted, value, create in self.study.fixed + with_entries(self.study, p):
            self._set(case, file, dotted, value, create)
        for k, value in _knobs_of(self.study, p):
            if k.file:   # a path (keels/keel0.5/DEM/compacted.h5) is written as a string
                value = expand(self.study, k, dict(p.values, **{k.name: value}))
                if os.path.isabs(value):   # ${STUDY}/...: relative to the point's case, as a case's own paths
                    value = os.path.relpath(value, case)
                self._set(case, k.file, k.dotted, f'"{value}"' if "/" in value else value, k.create)
        return case

    @staticmethod
    def _set(case, file, dotted, value, create):
        path = os.path.join(case, file)
        if dotted == "#include":   # after the file's own entries: what it includes overrides them
            text = open(path).read()
            iceCases.write_atomically(path, text.rstrip("\n") + f'\n\n#include "{value}"\n')
            return
        try:
            iceCases.set_entry(path, dotted, value)
        except KeyError:
            if not create:
                raise
            iceCases.add_entry(path, dotted, value)

    def run_point(self, p, how):
        if self.stopping:   # stopped before this point began: it stays as it was
            p.skipped_by_stop = True
            return p
        case = self.case(p)
        if how == "run":
            os.makedirs(self.folder(p), exist_ok=True)
            p.state = {"madeFrom": p.fingerprint, "knobs": p.values, "status": "preparing", "wall_s": 0.0}
            self.save_state(p)
            case = self.prepare(p)
        # The peak RSS comes from /usr/bin/time (its wait4 on mpirun, which has reaped the ranks): a
        # process forked from this runner would count the runner's own memory (Linux keeps the larger
        # of the forked copy's and the program's high-water mark in ru_maxrss).
        rss_file = os.path.join(self.folder(p), "rss.txt")
        timer = ["/usr/bin/time", "-f", "%M", "-o", rss_file] if os.access("/usr/bin/time", os.X_OK) else []
        if os.path.exists(rss_file):
            os.remove(rss_file)
        if self.study.allrun is not None:
            cmd = timer + ["bash"] + command(self.study, p)
        else:
            cmd = timer + ["mpirun", "-np", str(self.study.ranks), "--oversubscribe", self.study.app, "-case", case]
            cmd += command(self.study, p)[3:] + (["-resume"] if how == "resume" else [])
        env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
                   OMPI_MCA_mpi_yield_when_idle="1")
        log = os.path.join(self.folder(p), "log.run")
        err = os.path.join(self.folder(p), "log.err")   # stderr apart: the error message in its order
        p.state.update(status="running", command=" ".join(cmd), started=_now())
        self.save_state(p)
        start = time.time()
        mode = "a" if how == "resume" else "w"
        with open(log, mode) as out, open(err, mode) as errors:
            with self.lock:
                if self.stopping:
                    p.state["status"] = "killed"
                    self.save_state(p)
                    return p
                # the point holds the study's lock too (an inherited descriptor of the locked file):
                # if this runner is killed outright, no other runner starts while the point still runs
                proc = subprocess.Popen(cmd, stdout=out, stderr=errors, env=env, start_new_session=True,
                                        cwd=case if self.study.allrun is not None else None,
                                        pass_fds=(self.lock_fd,) if self.lock_fd is not None else ())
                self.running[p.label] = proc
            _, status, usage = os.wait4(proc.pid, 0)
            proc.returncode = os.waitstatus_to_exitcode(status)
            # and what is left of its process group (ranks finishing after a stop) has gone too
            for _ in range(600):
                try:
                    os.killpg(proc.pid, 0)
                except (ProcessLookupError, PermissionError):
                    break
                time.sleep(0.1)
            with self.lock:
                del self.running[p.label]
        wall = time.time() - start
        p.state["wall_s"] = p.state.get("wall_s", 0.0) + wall
        try:
            rss_kB = float(open(rss_file).read().split()[-1])
            p.state["rss_from"] = "/usr/bin/time"
        except (OSError, ValueError, IndexError):   # no /usr/bin/time, or it was killed
            rss_kB = usage.ru_maxrss
            p.state["rss_from"] = "wait4 (counts the runner's memory)"
        p.state["peak_rss_MiB"] = max(p.state.get("peak_rss_MiB", 0.0), rss_kB * 1024 / MiB)
        p.state["load_average"] = round(os.getloadavg()[0], 2)
        p.state["git_revision"] = self.revision
        p.state["finished_at"] = _now()
        p.state.pop("error", None)
        post_error = None
        if proc.returncode == 0 and self.finished(p) and self.study.post_process and not self.stopping:
            post_error = self.post_process(p, case)
            p.state["wall_s"] = time.time() - start + p.state["wall_s"] - wall
        if proc.returncode == 0 and self.finished(p) and post_error is None:
            p.state["status"] = "done"
            with self.lock:
                self.run_walls.append(p.state["wall_s"])
        elif post_error is not None and not self.stopping:
            p.state["status"] = "failed"
            p.state["error"] = post_error
        elif self.stopping:
            p.state["status"] = "killed"
        else:
            p.state["status"] = "failed"
            message = error_tail(err)
            if message == "no message in the log":
                message = error_tail(log)
            if self.study.allrun is not None:   # the application's own error, from the run's log the Allrun names
                cause = self.allrun_cause(case)
                if cause:
                    message = cause + " | " + message
            p.state["error"] = f"exit {proc.returncode}: " + message.replace(self.runs + os.sep, "runs/")
        self.save_state(p)
        return p

    @staticmethod
    def allrun_cause(case):
        """The first application error (a FATAL block) among the logs an Allrun left in its case."""
        for folder, _, names in sorted(os.walk(case)):
            for name in sorted(names):
                if name.startswith("log."):
                    path = os.path.join(folder, name)
                    with open(path, errors="replace") as f:
                        if "FATAL" in f.read():
                            return f"{os.path.relpath(path, case)}: " + error_tail(path, lines=2)
        return None

    def post_process(self, p, case):
        """Runs the study's postProcess on the finished point; None, or the failure's message."""
        script, *extra = self.study.post_process
        log = os.path.join(self.folder(p), "log.postProcess")
        with open(log, "w") as out:
            result = subprocess.run([sys.executable, os.path.join(iceCases.TOP, script)] + extra + [case],
                                    stdout=out, stderr=subprocess.STDOUT)
        if result.returncode == 0:
            return None
        return f"postProcess {script} exit {result.returncode}: " + error_tail(log)

    # -- the table
    def figures(self, p):
        if p.state.get("status") != "done":
            return {}
        try:
            summary = json.load(open(self.summary_file(p)))
        except (OSError, ValueError):
            return {}
        p.summary = summary
        others = {}
        out = {}
        for name, key in self.study.figures:
            data = summary
            if ":" in key:   # file.json:dotted, another file of the point's case, from the summary's folder
                file, key = key.split(":", 1)
                if file not in others:
                    try:
                        others[file] = json.load(open(os.path.join(os.path.dirname(self.summary_file(p)), file)))
                    except (OSError, ValueError):
                        others[file] = {}
                data = others[file]
            v = _dig(data, key)
            if isinstance(v, str):   # a text figure (a failure mode): kept as it is, no error
                out[name] = v
            else:
                out[name] = float(v) if isinstance(v, (int, float)) and not isinstance(v, bool) else float("nan")
        return out

    def reference_point(self, p):
        """The point whose figures are p's reference (reference 'finest'): each knob with `finer` at
        its finest value among the points of this run, the other knobs as p's."""
        values = dict(p.values)
        for k in self.study.knobs:
            if isinstance(k.finer, list):   # words from the coarsest to the finest
                values[k.name] = max({q.values[k.name] for q in self.points}, key=k.finer.index)
            elif k.finer:
                run_values = sorted({q.values[k.name] for q in self.points}, key=float)
                values[k.name] = run_values[-1] if k.finer == "larger" else run_values[0]
        return next(q for q in self.points if q.values == values and q.seed is None)

    def is_case_default(self, p):
        if p.seed is not None:
            return False
        for k in self.study.knobs:
            if k.case_value is None:
                return False
            a, b = p.values[k.name], k.case_value
            fa, fb = studyDict._number(a), studyDict._number(b)
            if not (a == b or (fa is not None and fb is not None and fa == fb)):
                return False
        return True

    def rows(self):
        figs = {p.label: self.figures(p) for p in self.points}
        rows = []
        scatter = self.scatter(figs)
        for p in self.points:
            row = {"point": p.label}
            row.update(p.values)
            if self.study.scatter:
                row[self.study.scatter.name] = p.seed if p.seed is not None else (self.study.scatter.case_value or "")
                row["is_scatter"] = int(p.seed is not None)
            row["status"] = p.state.get("status", "pending") if p.state.get("madeFrom") == p.fingerprint else "pending"
            if self.study.reference_type == "measured":
                ref, ref_label = self.study.reference, "measured: " + self.study.reference_source
            elif self.study.reference_type == "summary":
                own = getattr(p, "summary", {}) if p.state.get("status") == "done" else {}
                ref = {n: _dig(own, key) for n, key in self.study.reference_keys.items()}
                ref = {n: float(v) for n, v in ref.items() if isinstance(v, (int, float)) and not isinstance(v, bool)}
                ref_label = self.study.reference_source
            elif self.study.reference_type == "none":
                ref, ref_label = {}, "none"
            else:
                rp = self.reference_point(p)
                ref, ref_label = figs[rp.label], rp.label
            for name, _ in self.study.figures:
                v = figs[p.label].get(name, float("nan"))
                r = ref.get(name, float("nan"))
                row[name] = v
                numeric = isinstance(v, float) and isinstance(r, float)
                row[name + "_error"] = (v - r) / r if numeric and r == r and r != 0 and v == v else float("nan")
                if self.study.scatter and name in scatter:
                    sd = scatter[name]
                    row[name + "_scatter"] = sd
                    err = row[name + "_error"]
                    row[name + "_within_scatter"] = int(abs(err) <= 2 * sd) if err == err and sd == sd else ""
            row["reference"] = ref_label
            row["is_reference"] = int(self.study.reference_type == "finest" and self.reference_point(p) is p)
            row["is_case_default"] = int(self.is_case_default(p))
            done = row["status"] == "done"
            s = getattr(p, "summary", {}) if done else {}
            row["wall_s"] = p.state.get("wall_s", float("nan")) if row["status"] in ("done", "failed") else float("nan")
            pss = s.get("particle_steps_per_s")
            if pss is None and s.get("particles") and s.get("steps") and row["wall_s"] == row["wall_s"]:
                pss = s["particles"] * s["steps"] / row["wall_s"]
            row["particle_steps_per_s"] = float(pss) if pss is not None else float("nan")
            row["n_particles"] = s.get("particles", "")
            row["n_steps"] = s.get("steps", "")
            row["ranks"] = self.study.cores
            row["peak_rss_MiB"] = p.state.get("peak_rss_MiB", float("nan")) if row["status"] != "pending" else float("nan")
            row["load_average"] = p.state.get("load_average", float("nan")) if row["status"] != "pending" else float("nan")
            row["git_revision"] = p.state.get("git_revision", "") if row["status"] != "pending" else ""
            row["finished_at"] = p.state.get("finished_at", "") if row["status"] != "pending" else ""
            row["error"] = p.state.get("error", "") if row["status"] == "failed" else ""
            rows.append(row)
        return rows

    def scatter(self, figs):
        """{figure: relative sample standard deviation} over the chosen point and its scatter points
        (NaN until two of them are done): the packing's (seed's) share of any error."""
        if not self.study.scatter:
            return {}
        group = [q for q in self.points if q.values == self.study.scatter_at
                 and q.state.get("madeFrom") == q.fingerprint and q.state.get("status") == "done"]
        out = {}
        for name, _ in self.study.figures:
            values = [figs[q.label].get(name) for q in group]
            values = [v for v in values if isinstance(v, float) and v == v]
            if len(values) < 2:
                out[name] = float("nan")
                continue
            mean = statistics.mean(values)
            out[name] = statistics.stdev(values) / abs(mean) if mean else float("nan")
        return out

    def write_tables(self):
        os.makedirs(self.tables, exist_ok=True)
        rows = self.rows()
        columns = list(rows[0])
        text = io.StringIO()
        w = csv.DictWriter(text, columns, lineterminator="\n")
        w.writeheader()
        for r in rows:
            w.writerow({c: ("%.6g" % v if isinstance(v, float) else v) for c, v in r.items()})
        iceCases.write_atomically(os.path.join(self.tables, "table.csv"), text.getvalue())
        self.write_h5(rows, columns)
        try:
            import studyPlot
            studyPlot.plot(self, rows, os.path.join(self.tables, "study.png"))
        except Exception as e:   # a plot is no reason to lose a study
            print(f"runStudy: the plot was not written: {type(e).__name__}: {e}", file=sys.stderr)
        return rows

    def write_h5(self, rows, columns):
        import h5py
        import numpy as np
        path = os.path.join(self.tables, "table.h5")
        tmp = path + ".tmp"
        with h5py.File(tmp, "w") as f:
            g = f.create_group("points")
            for c in columns:
                vals = [r[c] for r in rows]
                if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in vals):
                    g.create_dataset(c, data=np.array(vals, dtype=float))
                else:
                    g.create_dataset(c, data=np.array([str(v) for v in vals], dtype=h5py.string_dtype()))
            f.attrs["study"] = os.path.relpath(self.study.dict_path, iceCases.TOP)
            f.attrs["case"] = self.study.case_name
            f.attrs["reference"] = self.study.reference_type
            f.attrs["figures"] = json.dumps(dict(self.study.figures))
            f.attrs["knobs"] = json.dumps({k.name: k.where() for k in self.study.knobs})
            f.attrs["git_revision"] = self.revision
            f.attrs["written"] = _now()
        os.replace(tmp, path)

    # -- the whole study
    def list_points(self):
        for p in self.points:
            self.load_state(p)
            v = self.verdict(p)
            extra = f" ({p.state.get('error')})" if v == "failed" else ""
            print(f"{p.label:50s} {v}{extra}")

    def stop(self, signum, frame):
        with self.lock:
            self.stopping = True
            for proc in self.running.values():
                if self.study.allrun is not None:   # the Allrun's whole group: its mpirun and ranks
                    try:
                        os.killpg(proc.pid, signal.SIGTERM)
                    except ProcessLookupError:
                        pass
                    continue
                # mpirun (the child of /usr/bin/time, which would die at once and leave it running)
                # forwards the signal to its ranks and ends after them
                try:
                    children = open(f"/proc/{proc.pid}/task/{proc.pid}/children").read().split()
                except OSError:
                    children = []
                try:
                    for child in children:
                        os.kill(int(child), signal.SIGTERM)
                    if not children:
                        os.killpg(proc.pid, signal.SIGTERM)
                except ProcessLookupError:
                    pass

    def run(self):
        todo, kept = [], 0
        for p in self.points:
            self.load_state(p)
            v = self.verdict(p)
            if v in ("done", "failed"):
                kept += 1
            else:
                todo.append((p, v))
        total = len(self.points)
        print(f"runStudy: {self.study.case_name}, {total} points ({kept} finished before, {len(todo)} to run), "
              f"-jobs {self.args.jobs}, {self.study.cores} core(s) each; runs in {self.runs}")
        self.write_tables()
        done = kept
        with concurrent.futures.ThreadPoolExecutor(self.args.jobs) as pool:
            futures = {pool.submit(self.run_point, p, how): p for p, how in todo}
            pending = set(futures)
            while pending:
                finished, pending = concurrent.futures.wait(pending, timeout=1.0,
                                                            return_when=concurrent.futures.FIRST_COMPLETED)
                if self.stopping:
                    for f in pending:
                        f.cancel()
                for f in finished:
                    p = futures[f]
                    if f.cancelled() or getattr(p, "skipped_by_stop", False):
                        continue
                    try:
                        f.result()
                    except Exception as e:   # the runner's own failure on this point (a copy, a bad entry)
                        p.state.update(status="failed", error=f"{type(e).__name__}: {e}")
                        self.save_state(p)
                    done += 1
                    self.write_tables()
                    self.progress(p, done, total, len(pending))
        rows = self.write_tables()
        failed = [r for r in rows if r["status"] == "failed"]
        killed = [r for r in rows if r["status"] in ("killed", "running", "pending", "preparing")]
        print(f"runStudy: table {os.path.join(self.tables, 'table.csv')} (+ table.h5, study.png): "
              f"{total - len(failed) - len(killed)} done, {len(failed)} failed, {len(killed)} not finished")
        if self.stopping:
            return 143
        return 3 if failed or killed else 0

    def estimate_wall(self, p):
        """A point's expected wall time: log(wall) fitted linearly in log(value) of the numeric knobs
        over the points run so far (the mean of their walls until there are enough of them)."""
        import numpy as np
        ran = [q for q in self.points if q.state.get("status") == "done" and q.state.get("wall_s")]
        # a knob the finished points do not vary yet says nothing about the others' walls
        knobs = [k for k in self.study.knobs if all(studyDict._number(v) and studyDict._number(v) > 0
                                                     for v in k.values)
                 and len({q.values[k.name] for q in ran}) > 1]
        if len(ran) < len(knobs) + 2:
            return sum(self.run_walls) / len(self.run_walls)

        def row(q):
            return [1.0] + [np.log(float(q.values[k.name])) for k in knobs]
        coef = np.linalg.lstsq(np.array([row(q) for q in ran]),
                               np.log([q.state["wall_s"] for q in ran]), rcond=None)[0]
        return float(np.exp(np.dot(row(p), coef)))

    def progress(self, p, done, total, left):
        s = p.state.get("status")
        figs = ""
        if s == "done":
            f = self.figures(p)
            figs = ", ".join(f"{n} {f[n]:.4g}" if isinstance(f[n], float) else f"{n} {f[n]}"
                             for n, _ in self.study.figures)
        elif s == "failed":
            figs = p.state.get("error", "")
        walls = self.run_walls
        if left and walls:
            eta = sum(self.estimate_wall(q) for q in self.points if q.state.get("status") in
                      ("pending", "preparing", "running", None) or q.state.get("madeFrom") != q.fingerprint)
            eta /= min(self.args.jobs, left)
            eta_text = f"about {eta / 60:.1f} min left" if eta >= 120 else f"about {eta:.0f} s left"
        else:
            eta_text = "estimate after the first point" if left else "finished"
        print(f"[{done}/{total} done, {left} left] {p.label}: {s} in {p.state.get('wall_s', 0):.0f} s"
              f"{': ' + figs if figs else ''}; {eta_text}", flush=True)


def _now():
    return datetime.datetime.now().strftime("%Y-%m-%d %H:%M:%S")


def main(argv):
    parser = argparse.ArgumentParser(prog="runStudy.py", description=__doc__.split("\n\n")[0])
    parser.add_argument("study")
    parser.add_argument("-jobs", type=iceCases.whole_number(1, 64), default=1)
    parser.add_argument("-quick", action="store_true")
    parser.add_argument("-resume", action="store_true")
    parser.add_argument("-retry-failed", dest="retry_failed", action="store_true")
    parser.add_argument("-out")
    parser.add_argument("-list", action="store_true")
    parser.add_argument("-plot", action="store_true")
    parser.add_argument("-bin", help="the folder of the applications (default build/demModels)")
    args = parser.parse_args(argv)
    try:
        study = studyDict.read_study(args.study)
    except studyDict.StudyDictError as e:
        print(f"runStudy: {e}", file=sys.stderr)
        return 1
    missing = studyDict.missing_includes(study)
    if missing and not (args.list or args.plot):
        for e in missing:
            print(f"runStudy: {e}", file=sys.stderr)
        return 1
    if args.bin and study.allrun is not None:   # the Allrun finds the applications through the mirror's build/
        study.build = os.path.dirname(os.path.abspath(args.bin))
    elif args.bin:
        study.app = os.path.join(os.path.abspath(args.bin), study.application)
    if not os.access(study.app, os.X_OK):
        print(f"runStudy: {study.app} is not built; run bin/build", file=sys.stderr)
        return 1
    runner = Runner(study, args)
    if args.list:
        runner.list_points()
        return 0
    os.makedirs(runner.runs, exist_ok=True)
    lock_path = os.path.join(runner.runs, ".lock")
    lock = open(lock_path, "a+")
    try:
        fcntl.flock(lock, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError:
        lock.seek(0)
        holder = lock.read().strip() or "unknown"
        print(f"runStudy: another runner (pid {holder}) is running this study ({lock_path}), or a point it "
              "started still runs; wait for it to finish or stop it", file=sys.stderr)
        return 1
    lock.seek(0)
    lock.truncate()
    lock.write(str(os.getpid()))
    lock.flush()
    runner.lock_fd = lock.fileno()
    if args.plot:
        for p in runner.points:
            runner.load_state(p)
        runner.write_tables()
        print(f"runStudy: {os.path.join(runner.tables, 'table.csv')} and study.png rewritten")
        return 0
    signal.signal(signal.SIGTERM, runner.stop)
    signal.signal(signal.SIGINT, runner.stop)
    return runner.run()


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
