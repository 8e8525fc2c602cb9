"""Helpers for studies that run many variants of a case: copy a case (with the
cases/common it includes), set dictionary entries by their dotted path (as
foamDictionary -entry -set does),
run an application under mpirun, and read the results.

Used by the sweep, speed-study and benchmark scripts with Debian's
/usr/bin/python3."""
import argparse
import csv
import filecmp
import hashlib
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import threading
import time

TOP = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SHARED = os.path.join(os.path.dirname(TOP), "shared")
BUILD = os.path.join(TOP, "build")

# Every mpirun these scripts start, directly or through a case's Allrun, inherits this: Open MPI
# binds each mpirun's ranks to cores from core 0 on, so two 1-rank jobs side by side shared core 0
# (each at 0.44 of its speed alone; studies/sceneSpeed). Unbound, the kernel spreads them.
os.environ.setdefault("OMPI_MCA_hwloc_base_binding_policy", "none")


_COMMENT_OR_STRING = re.compile(r'//[^\n]*|/\*.*?\*/|"(?:[^"\\\n]|\\.)*"', re.S)


def _mask_comments(text):
    """text with its // and /* */ comments blanked (the same length, newlines kept), so that a
    keyword or a brace written in a comment is never taken for an entry."""
    def blank(m):
        return m.group(0) if m.group(0).startswith('"') else re.sub(r"[^\n]", " ", m.group(0))
    return _COMMENT_OR_STRING.sub(blank, text)


def _block_span(text, start, name):
    """(open, close) indices of the braces of sub-dictionary `name` in text[start:close]; text is
    the dictionary with its comments masked (_mask_comments), so that the indices are the file's."""
    pattern = re.compile(r"(^|[\s;{}])" + re.escape(name) + r"(?:\s|//[^\n]*)*\{", re.M)
    depth_ok = None
    for m in pattern.finditer(text, start):
        # accept only matches at brace depth 0 relative to `start`
        depth = text.count("{", start, m.start()) - text.count("}", start, m.start())
        if depth == 0:
            depth_ok = m
            break
    if depth_ok is None:
        raise KeyError(name)
    open_brace = depth_ok.end() - 1
    depth = 0
    for k in range(open_brace, len(text)):
        if text[k] == "{":
            depth += 1
        elif text[k] == "}":
            depth -= 1
            if depth == 0:
                return open_brace, k
    raise ValueError(f"unclosed dictionary {name}")


def _entry_value_span(text, dotted, path):
    text = _mask_comments(text)
    *dicts, key = dotted.split(".")
    start, end = 0, len(text)
    for name in dicts:
        open_brace, close_brace = _block_span(text[:end], start, name)
        start, end = open_brace + 1, close_brace
    pattern = re.compile(r"(^|[\s;{])(" + re.escape(key) + r")(\s+)([^;{}]*);", re.M)
    for m in pattern.finditer(text, start, end):
        depth = text.count("{", start, m.start()) - text.count("}", start, m.start())
        if depth == 0:
            return m.start(4), m.end(4)
    raise KeyError(f"{dotted} not found in {path}")


_INCLUDE = re.compile(r'^[ \t]*#include(?:IfPresent)?[ \t]*"([^"]*)"', re.M)


def included_files(path):
    """The files that path's top-level #include lines name, resolved against its folder."""
    folder = os.path.dirname(path)
    names = (os.path.join(folder, name) for name in _INCLUDE.findall(open(path).read()))
    return [name for name in names if os.path.isfile(name)]


def input_files(paths):
    """The files under `paths` (files or folders) and, recursively, the files their
    dictionaries #include: what a run made from those paths depends on, and nothing else
    (cases/common holds calibrations of other cases too)."""
    found, pending = set(), []
    for path in paths:
        if os.path.isdir(path):
            pending += [os.path.join(folder, n) for folder, _, names in os.walk(path) for n in names]
        elif os.path.isfile(path):
            pending.append(path)
    while pending:
        path = os.path.normpath(pending.pop())
        if path in found or not os.path.isfile(path):
            continue
        found.add(path)
        with open(path, "rb") as f:
            binary = b"\0" in f.read(4096)   # an HDF5 keel, not a dictionary
        if not binary:
            pending += included_files(path)
    return sorted(found)


def get_entry(path, dotted):
    """The value text of `a.b.key value;` in an OpenFOAM dictionary file, or, when the
    file does not write it, in the files it #includes (the last include first), also
    those included inside a sub-dictionary (`a { #include "x" }`: x's `b.key`)."""
    text = open(path).read()
    try:
        begin, end = _entry_value_span(text, dotted, path)
        return text[begin:end]
    except KeyError:
        pass
    text = _mask_comments(text)   # the includes and braces of the file's structure, not of its comments
    parts = dotted.split(".")
    start, end = 0, len(text)
    for depth in range(len(parts)):
        # the #include lines of this block (its own level): they hold the rest of the path
        level = [m for m in _INCLUDE.finditer(text, start, end)
                 if text.count("{", start, m.start()) - text.count("}", start, m.start()) == 0]
        for m in reversed(level):
            included = os.path.join(os.path.dirname(path), m.group(1))
            if os.path.isfile(included):
                try:
                    return get_entry(included, ".".join(parts[depth:]))
                except KeyError:
                    pass
        if depth == len(parts) - 1:
            break
        try:
            open_brace, close_brace = _block_span(text[:end], start, parts[depth])
        except KeyError:
            break
        start, end = open_brace + 1, close_brace
    raise KeyError(f"{dotted} not found in {path} nor in what it includes")


def set_entry(path, dotted, value):
    """Sets `a.b.key value;` in an OpenFOAM dictionary file. The entry must exist, in
    the file or in a file it #includes; in the latter case an override is added to
    the file after the include (inside the sub-dictionaries of the path the file
    already has, so the file writes each keyword once)."""
    text = open(path).read()
    try:
        begin, end = _entry_value_span(text, dotted, path)
        open(path, "w").write(text[:begin] + str(value) + text[end:])
    except KeyError:
        get_entry(path, dotted)   # raises KeyError when no include has it either
        open(path, "w").write(_with_override(text, dotted, value))


def keel_file(keel):
    """The saved stage of the rubble case `keel` that a ridge reads as its keel
    (keel.settledRubble): DEM/compacted.h5 where it compacts, else DEM/settled.h5.
    The same as keel_file in bin/caseCommon.sh."""
    method = get_entry(os.path.join(keel, "constant", "rubbleProperties"), "compaction.method").strip()
    return os.path.join(keel, "DEM", "compacted.h5" if method == "plates" else "settled.h5")


def add_entry(path, dotted, value):
    """Adds `a.b.key value;`, which the file must not have, to an OpenFOAM dictionary file."""
    text = open(path).read()
    try:
        _entry_value_span(text, dotted, path)
    except KeyError:
        open(path, "w").write(_with_override(text, dotted, value))
        return
    raise KeyError(f"{dotted} is in {path} already")


def uncompacted(path, porosity):
    """A rubbleProperties (path) bonded where the heap settled, no compaction, with the ice of
    a blocks.rubbleThickness layer at `porosity` rained in."""
    set_entry(path, "compaction.method", "none")
    add_entry(path, "blocks.expectedPorosity", porosity)


def softened_compaction(path):
    """A rubbleProperties (path) compacted with the contacts and the blocks' bonds at the
    settling's softened modulus (compaction.youngsModulus = settling.youngsModulus), as the rubble
    cases were before 2026-11-28. For reduced heaps that test the stages: two or three blocks thick,
    ice-stiff blocks jam near porosity 0.60 (cases/rubblePunch/README.md, "Compaction at the ice's
    stiffness"), softened ones reach their target. A ridge or punch on such a keel must start its
    assembly at the same modulus (ridgeProperties assembly.youngsModulus)."""
    modulus = get_entry(path, "settling.youngsModulus").strip()
    try:
        set_entry(path, "compaction.youngsModulus", modulus)
    except KeyError:
        add_entry(path, "compaction.youngsModulus", modulus)


def _with_override(text, dotted, value):
    """text with `a { b { key value; } }` added: into the deepest of a, a.b, ... that
    it has, otherwise before its closing `// ****` line (or at its end)."""
    *dicts, key = dotted.split(".")
    masked = _mask_comments(text)
    start, insert_at, depth = 0, None, 0
    for name in dicts:
        try:
            open_brace, close_brace = _block_span(masked[:insert_at or len(masked)], start, name)
        except KeyError:
            break
        start, insert_at, depth = open_brace + 1, close_brace, depth + 1
    missing = dicts[depth:]
    indent = "    " * depth
    lines = [indent + "    " * i + name + "\n" + indent + "    " * i + "{" for i, name in enumerate(missing)]
    lines.append(indent + "    " * len(missing) + f"{key} {value};")
    lines += [indent + "    " * i + "}" for i in reversed(range(len(missing)))]
    block = "\n".join(lines) + "\n"
    if insert_at is not None:
        line_start = text.rfind("\n", 0, insert_at) + 1
        if not text[line_start:insert_at].strip():
            insert_at = line_start   # the closing brace stands on its own line
        elif text[insert_at - 1] != "\n":
            block = "\n" + block
        return text[:insert_at] + block + text[insert_at:]
    footer = text.rfind("\n// ****")
    at = footer + 1 if footer >= 0 else len(text)
    return text[:at] + block + "\n" + text[at:]


def copy_common(case_copy):
    """cases/common copied to <case_copy>/../common, where the `#include
    "../../common/..."` of a copied case's dictionaries looks (see cases/common/README.md)."""
    source = os.path.join(TOP, "cases", "common")
    target = os.path.join(os.path.dirname(os.path.abspath(case_copy)), "common")
    if os.path.realpath(target) == os.path.realpath(source):
        return
    # file by file, each replaced whole and only when it differs: runs made side by side
    # share the copy, and one of them may be reading it
    for folder, _, names in os.walk(source):
        into = os.path.join(target, os.path.relpath(folder, source))
        os.makedirs(into, exist_ok=True)
        for name in names:
            src, dst = os.path.join(folder, name), os.path.join(into, name)
            if not (os.path.exists(dst) and filecmp.cmp(src, dst, shallow=False)):
                tmp = "%s.tmp%d.%d" % (dst, os.getpid(), threading.get_ident())
                shutil.copyfile(src, tmp)
                os.replace(tmp, dst)


def copy_case(source, target):
    shutil.rmtree(target, ignore_errors=True)
    os.makedirs(target)
    # the case's inputs only: what a run of the source wrote into DEM/ (saved stages,
    # checkpoints, LIGGGHTS restarts and data files) stays behind
    generated = shutil.ignore_patterns("*.h5", "*.data", "*.restart.*", "checkpoint*", "variables.generated",
                                       "platen.stl", "*.tmp")
    for sub in ("constant", "system", "DEM"):
        if os.path.isdir(os.path.join(source, sub)):
            shutil.copytree(os.path.join(source, sub), os.path.join(target, sub),
                            ignore=generated if sub == "DEM" else None)
    copy_common(target)
    return target


def small_rubble_case(source, path, length, width, thickness, max_time, tilt, entries=None):
    """A reduced copy of a rubble case (cases/rubbleBeam): a shorter box, a
    thinner layer, a shorter settling, compacted at the settling's softened
    contacts (softened_compaction: a heap this thin of ice-stiff blocks jams);
    `entries` sets further dotted entries of its rubbleProperties (among them,
    compaction.youngsModulus again)."""
    copy_case(source, path)
    props = os.path.join(path, "constant", "rubbleProperties")
    softened_compaction(props)
    set_entry(props, "box.length", length)
    set_entry(props, "box.width", width)
    set_entry(props, "blocks.rubbleThickness", thickness)
    set_entry(props, "settling.maxTime", max_time)
    set_entry(props, "settling.maxTilt", tilt)
    for entry, value in (entries or {}).items():
        set_entry(props, entry, value)
    return path


# The smoke tests' keel: ridgeFlexure's quick keel cut to a 1.6 x 0.4 m box and 0.25 m of rubble,
# settled for at most 0.5 s and compacted loosely and fast (ridgeFlexure -smoke, ridgeDesignMap -smoke).
SMOKE_KEEL = (("box.length", 1.6), ("box.width", 0.4), ("blocks.rubbleThickness", 0.25),
              ("settling.maxTime", 0.5), ("settling.minTime", 0.1), ("settling.maxTilt", 30),
              ("compaction.targetPorosity", 0.45), ("compaction.speed", 0.1), ("compaction.holdTime", 0.2),
              ("compaction.releaseTime", 0.2))


def smoke_keel(rubble_properties):
    """Sets SMOKE_KEEL in a keel's constant/rubbleProperties."""
    for entry, value in SMOKE_KEEL:
        set_entry(rubble_properties, entry, value)


def fatal_message(text):
    """The application's own message in a failed run's output (the line after its FATAL banner),
    or the output's first line when it has no banner."""
    lines = str(text).splitlines()
    return next((lines[i + 1].strip() for i, line in enumerate(lines[:-1]) if "FATAL" in line),
                lines[0] if lines else "failed")


def run_app(app, case, ranks=1, args=(), log_name="log.run"):
    """Runs an application on a case; returns the wall time in s. Raises on failure."""
    # yield_when_idle: ranks that wait do not busy-spin a shared core (2 ranks on 2 busy cores).
    # execute_quiet: an input error reads as the application's message alone (bin/caseCommon.sh)
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
               OMPI_MCA_mpi_yield_when_idle="1", OMPI_MCA_orte_execute_quiet="1")
    exe = os.path.join(BUILD, "demModels", app) if not os.path.isabs(app) else app
    cmd = ["mpirun", "-np", str(ranks), "--oversubscribe", exe, "-case", case, *map(str, args)]
    start = time.time()
    with open(os.path.join(case, log_name), "w") as log:
        result = subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, env=env)
    if result.returncode != 0:
        tail = open(os.path.join(case, log_name)).read()[-2000:]
        raise RuntimeError(f"{' '.join(cmd)} failed:\n{tail}")
    return time.time() - start


def kill_after_new_checkpoint(app, case, args, checkpoint, log_name, delay=0.0):
    """Runs app on one rank (no mpirun) and SIGKILLs it `delay` s after `checkpoint` has been written
    anew (a newer file than at the start); a fault test's kill. Returns when the process is gone."""
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    before = os.path.getmtime(checkpoint) if os.path.exists(checkpoint) else None
    with open(os.path.join(case, log_name), "w") as log:
        run = subprocess.Popen([app, "-case", case, *map(str, args)], stdout=log, stderr=subprocess.STDOUT, env=env)
        while run.poll() is None and (not os.path.exists(checkpoint) or os.path.getmtime(checkpoint) == before):
            time.sleep(0.005)
        time.sleep(delay)
        run.kill()
        run.wait()


def folder_fingerprint(folder, settings=(), upstream=()):
    """A digest of what a freshly prepared run folder is made from: every file in it (its
    dictionaries: nothing has run there yet) and the files they #include, by path relative to the
    folder and content; its settings (the application's arguments, JSON); and the upstream files
    it reads by name (a keel)."""
    digest = hashlib.sha256(json.dumps(list(settings), sort_keys=True).encode())
    own = input_files([folder])
    named = [(os.path.relpath(p, folder), p) for p in own] + [(os.path.abspath(p), p) for p in upstream]
    for name, path in named:
        digest.update(name.encode())
        with open(path, "rb") as f:
            digest.update(f.read())
    return digest.hexdigest()[:16]


def prepared_run(target, prepare, settings=(), upstream=()):
    """The run folder `target` as prepare(folder) makes it (a case copied, entries set), reused
    only when it was made from the same inputs (folder_fingerprint, recorded in target/madeFrom).
    One made from other inputs, or with no record, is removed and made again, so a study skips a
    finished run, and resumes a checkpoint, only for the inputs that made it."""
    scratch = target.rstrip(os.sep) + ".preparing"
    shutil.rmtree(scratch, ignore_errors=True)
    prepare(scratch)
    made_from = folder_fingerprint(scratch, settings, upstream)
    stamp = os.path.join(target, "madeFrom")
    if os.path.isdir(target):
        if os.path.exists(stamp) and open(stamp).read().strip() == made_from:
            shutil.rmtree(scratch)
            return target
        print(f"{target} was made from other inputs (its dictionaries, what they include, its settings "
              "or its upstream files changed, or it has no madeFrom record): made again", flush=True)
        shutil.rmtree(target)
    write_atomically(os.path.join(scratch, "madeFrom"), made_from + "\n")
    os.replace(scratch, target)
    return target


def finished(case):
    """Whether the case holds a finished run's result set: a summary.json that does not say
    "complete": false (a run in the making, killed or stopped by an error)."""
    path = os.path.join(case, "postProcessing", "summary.json")
    if not os.path.exists(path):
        return False
    try:
        return json.load(open(path)).get("complete", True) is not False
    except ValueError:
        return False


def summary(case):
    """The case's summary.json; refuses an incomplete result set (a run in the making, killed or
    stopped by an error: its summary says "complete": false and why)."""
    path = os.path.join(case, "postProcessing", "summary.json")
    s = json.load(open(path))
    if s.get("complete") is False:
        raise RuntimeError(f"{path}: the result set is incomplete: {s.get('reason', 'no reason given')}")
    return s


def curve(case):
    with open(os.path.join(case, "postProcessing", "platenForce.csv")) as f:
        rows = list(csv.DictReader(f))
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def fluid_force_figures(curve, window_mm=None):
    """At the cfd level, what the resolved water adds beyond still-water buoyancy, over the
    loading or a travel window (lo, hi) in mm of a force curve (columns as iceCases.curve gives
    them): the mean drag on the ice, and the pressure force less that buoyancy (mean, standard
    deviation). None at another level (no dragZ column) or for an empty window."""
    if "dragZ" not in curve:
        return None
    rows = [k for k, t in enumerate(curve["travel"]) if window_mm is None or window_mm[0] <= t * 1e3 <= window_mm[1]]
    if not rows:
        return None
    dynamic = [curve["pressureForceZ"][k] - curve["buoyancy"][k] for k in rows]
    return {"drag_mean_N": statistics.fmean(curve["dragZ"][k] for k in rows),
            "dynamic_pressure_mean_N": statistics.fmean(dynamic),
            "dynamic_pressure_std_N": statistics.pstdev(dynamic)}


def residual_strength(case, window=0.03):
    """Mean force over `window` m of travel after the peak, as a fraction of the peak."""
    c, s = curve(case), summary(case)
    d0 = s["travel_at_peak_m"]
    values = [f for d, f in zip(c["displacement"], c["force"]) if d0 < d <= d0 + window]
    return sum(values) / len(values) / s["peak_force_N"] if values else float("nan")


def write_atomically(path, text):
    tmp = path + ".tmp"
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, path)


def save_figure(fig, path, dpi=110):
    """A matplotlib figure laid out and written to path (a PNG) whole or not at all."""
    fig.tight_layout()
    tmp = path + ".tmp.png"
    fig.savefig(tmp, dpi=dpi)
    os.replace(tmp, path)


def git_revision():
    """The short revision of the checkout with a '+' if it has uncommitted changes ('unknown' outside git)."""
    try:
        rev = subprocess.run(["git", "-C", TOP, "rev-parse", "--short", "HEAD"], capture_output=True,
                             text=True, check=True).stdout.strip()
        dirty = subprocess.run(["git", "-C", TOP, "status", "--porcelain", "--untracked-files=no"],
                               capture_output=True, text=True, check=True).stdout.strip()
        return rev + ("+" if dirty else "")
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def write_readme_section(readme, name, text):
    """Replaces the generated block `<!-- NAME -->` ... `<!-- end NAME -->` of a README with text,
    so that the figures a reader sees are those of the published results, never typed.
    Exits naming the README and the markers if the block is missing."""
    start, end = f"<!-- {name} -->", f"<!-- end {name} -->"
    content = open(readme).read()
    if content.count(start) != 1 or content.count(end) != 1:
        sys.exit(f"{readme}: needs one '{start}' ... '{end}' block for the generated {name}")
    head, rest = content.split(start, 1)
    _, tail = rest.split(end, 1)
    write_atomically(readme, head + start + "\n" + text.rstrip("\n") + "\n" + end + tail)
    print(f"{readme}: {name} written from the published results")


def write_readme_table(readme, name, command, source, table, dated=False):
    """write_readme_section with the header every published table carries: the command that
    published it, the revision (and, dated, when), and the file the table is generated from."""
    when = time.strftime(" on %Y-%m-%d %H:%M UTC", time.gmtime()) if dated else ""
    write_readme_section(readme, name, f"Published by `{command}` at revision `{git_revision()}`{when}; "
                                       f"generated from `{source}`.\n\n{table}")


def publish_files(sources, folder, names=None):
    """A study's --publish: copies its output files (text or images) into the committed folder,
    each atomically (under names[i] when given, else its own name); exits naming the missing
    ones, having copied none, unless all exist."""
    missing = [src for src in sources if not os.path.isfile(src)]
    if missing or not sources:
        sys.exit("not published: missing (run the study first): " + (", ".join(missing) or "every output"))
    os.makedirs(folder, exist_ok=True)
    for i, src in enumerate(sources):
        target = os.path.join(folder, names[i] if names else os.path.basename(src))
        shutil.copyfile(src, target + ".tmp")
        os.replace(target + ".tmp", target)
        print("published", target)


def write_study_outputs(out, stem, texts):
    """A study's outputs, out/<stem>.<extension> for each {extension: text}, each written whole."""
    os.makedirs(out, exist_ok=True)
    for extension, text in texts.items():
        write_atomically(os.path.join(out, f"{stem}.{extension}"), text)


def publish_study(study, out, stem, extensions, table_name, source_extension):
    """The --publish of the script studies/<name>/<stem>.py: out/<stem>.<ext> copied into the
    study's results/, and results/<stem>.md written as the generated table `table_name` of its
    README.md."""
    results = os.path.join(study, "results")
    publish_files([os.path.join(out, f"{stem}.{ext}") for ext in extensions], results)
    folder = os.path.relpath(study, TOP)
    write_readme_table(os.path.join(study, "README.md"), table_name, f"{folder}/{stem}.py --publish",
                       f"{folder}/results/{stem}.{source_extension}", open(os.path.join(results, f"{stem}.md")).read())


# argparse types for the studies' options, strict as the applications' command
# lines: the whole string is read, and a count, a speed or a length of 0 or
# less is refused (argparse then prints the usage and exits with status 2).
_NUMBER = re.compile(r"\+?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?")


def whole_number(minimum=1, maximum=None):
    """A type: a whole number from minimum (to maximum), as an int (-jobs, -ranks)."""
    def read(text):
        if not re.fullmatch(r"\d+", text) or int(text) < minimum or (maximum is not None and int(text) > maximum):
            bound = f"from {minimum} to {maximum}" if maximum is not None else f"of at least {minimum}"
            raise argparse.ArgumentTypeError(f"needs a whole number {bound}, got '{text}'")
        return int(text)
    read.__name__ = "whole number"
    return read


def whole_text(minimum=1, maximum=None):
    """As whole_number, but the text itself (for a study that hands it to an application)."""
    check = whole_number(minimum, maximum)

    def read(text):
        check(text)
        return text
    read.__name__ = "whole number"
    return read


def positive_text(text):
    """A type: a decimal number > 0 (0.2, 5e-3), the text itself."""
    m = _NUMBER.fullmatch(text)
    if not m or not re.search(r"[1-9]", m.group(1)):
        raise argparse.ArgumentTypeError(f"needs a positive number, got '{text}'")
    return text


def positive_number(text):
    """A type: a decimal number > 0, as a float (a platen speed, a length, a time)."""
    return float(positive_text(text))


def choice(allowed):
    """A type: one of the names `allowed` (a water level, a keel)."""
    def read(text):
        if text not in allowed:
            raise argparse.ArgumentTypeError(f"needs one of {'|'.join(allowed)}, got '{text}'")
        return text
    read.__name__ = "choice"
    return read


def comma_list(item):
    """A type: comma-separated items, each read by the type `item` (--speeds 0.2,0.1)."""
    def read(text):
        parts = text.split(",")
        try:
            return [item(p) for p in parts]
        except argparse.ArgumentTypeError as e:
            raise argparse.ArgumentTypeError(f"a comma-separated list, each item: {e}")
    read.__name__ = "list"
    return read
