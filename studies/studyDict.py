"""The study dictionary of studies/runStudy.py: an OpenFOAM-style file read strictly.

Syntax (a subset of OpenFOAM's, as the applications' reader accepts it): `keyword value;`,
`keyword ( item item ... );`, `keyword { ... }`, `// comment` and `/* comment */`, strings in
double quotes. A keyword written twice in one block, an unknown keyword, a missing entry or a
value of the wrong kind is refused with an error naming the file, the line and the entry's dotted
path (StudyDictError); runStudy.py prints it and exits with status 1.

What the entries mean is documented in studies/README.md; `read_study` returns a plain Study
object with every value checked, the `default` values resolved from the case and ladders expanded.
"""
import csv
import difflib
import math
import os
import re
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "postProcessing"))
import iceCases  # noqa: E402

TOP = iceCases.TOP
SHARED = iceCases.SHARED


class StudyDictError(Exception):
    """An error in a study dictionary: `file:line: entry: what`."""

    def __init__(self, path, line, entry, text):
        self.path, self.line, self.entry = path, line, entry
        where = f"{path}:{line}" if line else path
        super().__init__(f"{where}: {entry}: {text}" if entry else f"{where}: {text}")


# ---------------------------------------------------------------------------- parsing
_TOKEN = re.compile(r'\s+|//[^\n]*|/\*.*?\*/|"(?:[^"\\\n]|\\.)*"|[{}();]|[^\s{}();"]+', re.S)


class Entry:
    """One entry: its keyword, line, dotted path and value (a list of tokens, a list of items, or a Dict)."""

    def __init__(self, key, line, path, value, kind):
        self.key, self.line, self.path, self.value, self.kind = key, line, path, value, kind


class Dict:
    def __init__(self, file, path, line):
        self.file, self.path, self.line, self.entries = file, path, line, {}

    def error(self, key, text, line=None):
        entry = self.entries.get(key)
        return StudyDictError(self.file, line or (entry.line if entry else self.line),
                              f"{self.path}.{key}" if self.path else key, text)

    def check_keys(self, allowed):
        for key, entry in self.entries.items():
            if key not in allowed:
                close = difflib.get_close_matches(key, allowed, 1)
                hint = f"; did you mean '{close[0]}'?" if close else ""
                raise self.error(key, f"unknown keyword{hint} (allowed: {', '.join(sorted(allowed))})")

    def found(self, key):
        return key in self.entries

    def _get(self, key):
        if key not in self.entries:
            where = f"'{self.path}'" if self.path else "the top level"
            raise StudyDictError(self.file, self.line, f"{self.path}.{key}" if self.path else key,
                                 f"missing entry (needed in {where})")
        return self.entries[key]

    def subdict(self, key):
        e = self._get(key)
        if e.kind != "dict":
            raise self.error(key, "needs a sub-dictionary { ... }")
        return e.value

    def word(self, key, default=None, allowed=None):
        if default is not None and key not in self.entries:
            return default
        e = self._get(key)
        if e.kind != "tokens" or len(e.value) != 1:
            raise self.error(key, "needs one word or number followed by ';'")
        text = e.value[0]
        if text.startswith('"'):
            text = text[1:-1]
        if allowed is not None and text not in allowed:
            raise self.error(key, f"'{text}' is not one of: {', '.join(allowed)}")
        return text

    def number(self, key, default=None, positive=False, whole=False):
        if default is not None and key not in self.entries:
            return default
        text = self.word(key)
        value = _number(text)
        if value is None or (whole and value != int(value)):
            raise self.error(key, f"needs {'a whole number' if whole else 'a number'}, got '{text}'")
        if positive and not value > 0:
            raise self.error(key, f"needs a number > 0, got '{text}'")
        return int(value) if whole else value

    def items(self, key):
        """A list `( a b c )` as the item texts (quotes removed)."""
        e = self._get(key)
        if e.kind != "list":
            raise self.error(key, "needs a list ( ... );")
        return [t[1:-1] if t.startswith('"') else t for t in e.value]

    def keys(self):
        return list(self.entries)


def _number(text):
    try:
        value = float(text)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def parse(path, text=None):
    """The top-level Dict of a study dictionary file."""
    if text is None:
        try:
            text = open(path).read()
        except OSError as e:
            raise StudyDictError(path, 0, None, f"cannot read: {e.strerror}")
    tokens, line, pos = [], 1, 0
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if m is None:   # an unterminated string or comment
            what = "string" if text[pos] == '"' else "comment"
            raise StudyDictError(path, line, None, f"unterminated {what}")
        t = m.group(0)
        if not (t.isspace() or t.startswith("//") or t.startswith("/*")):
            tokens.append((t, line))
        line += t.count("\n")
        pos = m.end()
    if text[pos:].strip():
        raise StudyDictError(path, line, None, "unexpected end")
    top = Dict(path, "", 1)
    k = _parse_block(path, tokens, 0, top, closing=False)
    assert k == len(tokens)
    return top


def _parse_block(path, tokens, k, block, closing):
    while k < len(tokens):
        t, line = tokens[k]
        if t == "}":
            if not closing:
                raise StudyDictError(path, line, block.path or None, "'}' without its '{'")
            return k + 1
        if t in "{}();" or t.startswith("#") or t.startswith("$"):
            what = "directives (#include, $name) are not read in a study dictionary" if t[0] in "#$" else \
                f"expected a keyword, got '{t}'"
            raise StudyDictError(path, line, block.path or None, what)
        key = t[1:-1] if t.startswith('"') else t
        dotted = f"{block.path}.{key}" if block.path else key
        if key in block.entries:
            raise StudyDictError(path, line, dotted,
                                 f"written twice in one block (first on line {block.entries[key].line})")
        k += 1
        if k >= len(tokens):
            raise StudyDictError(path, line, dotted, "no value (expected a value and ';', '(' or '{')")
        t2, line2 = tokens[k]
        if t2 == "{":
            sub = Dict(path, dotted, line)
            k = _parse_block(path, tokens, k + 1, sub, closing=True)
            block.entries[key] = Entry(key, line, dotted, sub, "dict")
        elif t2 == "(":
            items, k = [], k + 1
            while k < len(tokens) and tokens[k][0] != ")":
                if tokens[k][0] in "{}(;":
                    raise StudyDictError(path, tokens[k][1], dotted, f"unexpected '{tokens[k][0]}' in a list")
                items.append(tokens[k][0])
                k += 1
            if k + 1 >= len(tokens) or tokens[k + 1][0] != ";":
                raise StudyDictError(path, line, dotted, "a list needs ')' and ';'")
            block.entries[key] = Entry(key, line, dotted, items, "list")
            k += 2
        else:
            values = []
            while k < len(tokens) and tokens[k][0] not in ";{}()":
                values.append(tokens[k][0])
                k += 1
            if k >= len(tokens) or tokens[k][0] != ";":
                raise StudyDictError(path, line, dotted, "missing ';' after the value")
            if not values:
                raise StudyDictError(path, line, dotted, "no value before ';'")
            block.entries[key] = Entry(key, line, dotted, values, "tokens")
            k += 1
    if closing:
        raise StudyDictError(path, block.line, block.path, "'{' without its '}'")
    return k


# ---------------------------------------------------------------------------- the study
class Knob:
    """One knob: where it goes (`entry` file:dotted or an application `option`), its values."""

    def __init__(self, name):
        self.name = name
        self.file = self.dotted = self.option = None
        self.create = False
        self.values = []        # texts, `default` resolved
        self.quick = None
        self.case_value = None  # the case's own value (text), or None
        self.finer = None       # 'larger' | 'smaller' | [values, coarse to fine] | None
        self.template = None    # the entry's value made from the knobs' values ("${name}"), or None
        self.with_entries = {}  # value -> [(file, dotted, value, create)] set beside that value

    def where(self):
        return f"{self.file}:{self.dotted}" if self.file else self.option


class Study:
    pass


# the table's own columns: no knob or figure may take these names
RESERVED = {"point", "status", "reference", "is_reference", "is_case_default", "is_scatter", "wall_s",
            "particle_steps_per_s",
            "n_particles", "n_steps", "ranks", "peak_rss_MiB", "load_average", "git_revision", "finished_at", "error"}


def _check_name(d, name, what, taken):
    if name in RESERVED or name.endswith(("_error", "_scatter", "_within_scatter")) or name in taken:
        raise StudyDictError(d.file, d.entries[name].line, f"{d.path}.{name}",
                             f"a {what} cannot be named '{name}' (a column of the table: "
                             f"{', '.join(sorted(RESERVED | set(taken)))}, or *_error, *_scatter)")
    if not re.fullmatch(r"[A-Za-z]\w*", name):
        raise StudyDictError(d.file, d.entries[name].line, f"{d.path}.{name}",
                             f"a {what}'s name is a word of letters, digits and '_'")


def _split_entry(d, key, spec):
    if ":" not in spec:
        raise d.error(key, f"needs 'file:dotted.entry' (e.g. system/controlDict:writeInterval), got '{spec}'")
    file, dotted = spec.split(":", 1)
    if os.path.isabs(file) or ".." in file.split("/") or not dotted or not re.fullmatch(r"[\w.]+", dotted):
        raise d.error(key, f"needs a file inside the case and a dotted entry, got '{spec}'")
    return file, dotted


def _fixed_entries(sd, s):
    """The entries of a `set` block (or a knob's `with` block): [(file, dotted, value, create)]."""
    fixed = []
    for key in sd.keys():
        if key.endswith(":#include"):   # "file:#include" "../../common/chain/x": an #include appended to file
            file = key[:-len(":#include")]
            included = os.path.normpath(os.path.join(s.case, os.path.dirname(file), sd.word(key)))
            if not os.path.isfile(os.path.join(s.case, file)):
                raise sd.error(key, f"the case has no file {file}")
            # a generated dictionary may not be there yet (the runner refuses to start without it)
            s.includes.append((sd, key, included))
            fixed.append((file, "#include", sd.word(key), False))
            continue
        file, dotted = _split_entry(sd, key, key)
        e = sd.entries[key]
        if e.kind == "dict":
            sub = e.value
            sub.check_keys({"value", "create"})
            value, create = sub.word("value"), sub.word("create", default="no", allowed=("yes", "no")) == "yes"
        else:
            value, create = sd.word(key), False
        if not os.path.isfile(os.path.join(s.case, file)):
            raise sd.error(key, f"the case has no file {file}")
        if _case_value(s.case, file, dotted) is None and not create:
            raise sd.error(key, f"{dotted} is not in {s.case_name}/{file} (write "
                                f"'\"{key}\" {{ value {value}; create yes; }}' if it may be added)")
        fixed.append((file, dotted, value, create))
    return fixed


def _case_value(case, file, dotted):
    try:
        return iceCases.get_entry(os.path.join(case, file), dotted).strip()
    except (KeyError, OSError):
        return None


def _ladder(d, key):
    """`ladder { from 0.4; factor 0.5; count 4; }` -> texts 0.4 0.2 0.1 0.05 (%.6g)."""
    lad = d.subdict(key)
    lad.check_keys({"from", "factor", "count"})
    start, factor = lad.number("from"), lad.number("factor", positive=True)
    count = lad.number("count", whole=True, positive=True)
    return ["%.6g" % (start * factor ** i) for i in range(count)]


def _read_knob(d, name, s, path):
    """One knob of `knobs` (or the knob of `scatter`): where it goes and its values."""
    d.check_keys({"entry", "option", "caseEntry", "caseValue", "values", "ladder", "quick", "finer", "create",
                  "template", "with"})
    knob = Knob(name)
    if d.found("entry") == d.found("option"):
        raise StudyDictError(path, d.line, d.path, "needs one of 'entry file:dotted.path;' or 'option -name;'")
    if d.found("entry"):
        knob.file, knob.dotted = _split_entry(d, "entry", d.word("entry"))
        knob.create = d.word("create", default="no", allowed=("yes", "no")) == "yes"
        knob.case_value = _case_value(s.case, knob.file, knob.dotted)
        if not os.path.isfile(os.path.join(s.case, knob.file)):
            raise d.error("entry", f"the case has no file {knob.file} ({s.case})")
        if knob.case_value is None and not knob.create:
            raise d.error("entry", f"{knob.dotted} is not in {s.case_name}/{knob.file} nor in the files it "
                                   "includes (write 'create yes;' if the point may add it)")
    else:
        knob.option = d.word("option")
        if not re.fullmatch(r"-\w+", knob.option):
            raise d.error("option", f"needs an option such as -particles, got '{knob.option}'")
        if d.found("create"):
            raise d.error("create", "only for an 'entry' knob")
        if d.found("template"):
            raise d.error("template", "only for an 'entry' knob")
    if d.found("template"):
        knob.template = d.word("template")
    if d.found("caseValue"):   # an option's value where the Allrun is not given it (-resolution: default)
        if not knob.option or d.found("caseEntry"):
            raise d.error("caseValue", "only for an 'option' knob without 'caseEntry' (an entry's own value "
                                       "is read from the case)")
        knob.case_value = d.word("caseValue")
    if d.found("caseEntry"):
        file, dotted = _split_entry(d, "caseEntry", d.word("caseEntry"))
        knob.case_value = _case_value(s.case, file, dotted)
        if knob.case_value is None:
            raise d.error("caseEntry", f"{dotted} is not in {s.case_name}/{file}")
    if d.found("values") == d.found("ladder"):
        raise StudyDictError(path, d.line, d.path, "needs one of 'values ( ... );' or 'ladder { ... }'")
    raw = d.items("values") if d.found("values") else _ladder(d, "ladder")
    if not raw:
        raise d.error("values", "needs at least one value")

    def resolve(texts, key):
        out = []
        for t in texts:
            if t == "default":
                if knob.case_value is None:
                    raise d.error(key, "'default' needs the case's own value: the entry is not in the case"
                                       + ("" if knob.file else " (name it with 'caseEntry file:dotted;')"))
                t = knob.case_value
            if t in out:
                raise d.error(key, f"value '{t}' twice")
            if not re.fullmatch(r"[\w.+/-]+", t) or ".." in t.split("/"):
                raise d.error(key, f"'{t}': a value is one word, number or relative path")
            out.append(t)
        return out
    knob.values = resolve(raw, "values" if d.found("values") else "ladder")
    if d.found("quick"):
        knob.quick = resolve(d.items("quick"), "quick")
        extra = [q for q in knob.quick if q not in knob.values]
        if extra:
            raise d.error("quick", f"{', '.join(extra)} not among the values")
    if d.found("finer") and d.entries["finer"].kind == "list":   # words in order: (quick default)
        knob.finer = d.items("finer")
        if sorted(knob.finer) != sorted(knob.values):
            raise d.error("finer", f"needs the values ({', '.join(knob.values)}) each once, from the coarsest to "
                                   f"the finest, got ({' '.join(knob.finer)})")
    elif d.found("finer"):
        knob.finer = d.word("finer", allowed=("larger", "smaller"))
        bad = [v for v in knob.values if _number(v) is None]
        if bad:
            raise d.error("finer", f"needs numeric values (or the values in order: finer ( coarse ... fine );), "
                                   f"got {', '.join(bad)}")
    if d.found("with"):
        wd = d.subdict("with")
        for value in wd.keys():
            if value not in knob.values:
                raise wd.error(value, f"'{value}' is not among the values ({', '.join(knob.values)})")
            knob.with_entries[value] = _fixed_entries(wd.subdict(value), s)
    return knob


def read_study(path):
    """The Study of the study dictionary at path (a file, or a folder holding `studyDict`)."""
    if os.path.isdir(path):
        path = os.path.join(path, "studyDict")
    path = os.path.abspath(path)
    top = parse(path)
    top.check_keys({"study", "knobs", "set", "figures", "reference", "scatter"})
    s = Study()
    s.dict_path = path
    s.folder = os.path.dirname(path)

    st = top.subdict("study")
    st.check_keys({"case", "application", "allrun", "summary", "siblings", "stages", "cores", "ranks", "arguments",
                   "description", "postProcess"})
    case = st.word("case")
    candidates = [os.path.join(s.folder, case), os.path.join(TOP, "cases", case)] if not os.path.isabs(case) else [case]
    found = [c for c in candidates if os.path.isfile(os.path.join(c, "Allrun"))]
    if not found:
        raise st.error("case", f"no case '{case}' (looked for an Allrun in {', '.join(candidates)})")
    s.case = os.path.realpath(found[0])
    s.case_name = os.path.basename(s.case)
    if st.found("application") == st.found("allrun"):
        raise StudyDictError(path, st.line, "study", "needs one of 'application NAME;' (build/demModels/NAME "
                                                     "-case POINT) or 'allrun ( options );' (the case's ./Allrun)")
    s.allrun = st.items("allrun") if st.found("allrun") else None
    if s.allrun is not None:
        s.application = "Allrun"
        s.app = os.path.join(s.case, "Allrun")
        if st.found("ranks") or st.found("arguments"):
            raise st.error("ranks" if st.found("ranks") else "arguments",
                           "not with 'allrun': write the Allrun's own options in its list (-np 1)")
    else:
        s.application = st.word("application")
        s.app = os.path.join(iceCases.BUILD, "demModels", s.application)
        if not re.fullmatch(r"\w+", s.application):
            raise st.error("application", f"needs the name of an application in build/demModels, got "
                                          f"'{s.application}'")
        for key in ("summary", "siblings", "stages"):
            if st.found(key):
                raise st.error(key, "only with 'allrun' (an application writes postProcessing/summary.json)")
    # the summary: one path, or `summary { by KNOB; VALUE "path"; ... }` where it depends on a knob's
    # value (the floating block's water level writes cfd/postProcessing/summary.json)
    s.summary, s.summary_by = "postProcessing/summary.json", None
    if st.found("summary") and st.entries["summary"].kind == "dict":
        sd = st.subdict("summary")
        s.summary_by = (sd.word("by"), {v: sd.word(v) for v in sd.keys() if v != "by"})
        paths = list(s.summary_by[1].values())
    else:
        s.summary = st.word("summary", default=s.summary)
        paths = [s.summary]
    for path_ in paths:
        if os.path.isabs(path_) or ".." in path_.split("/") or not path_.endswith(".json"):
            raise st.error("summary", f"needs a .json file inside the case, got '{path_}'")
    s.siblings = st.items("siblings") if st.found("siblings") else []
    s.stages = st.items("stages") if st.found("stages") else []
    for stage in s.stages:
        if os.path.isabs(stage) or ".." in stage.split("/") or not stage.startswith("cases/"):
            raise st.error("stages", f"needs folders under cases/ of this checkout (cases/ridgeFlexure/keels/keel0.5), "
                                     f"got '{stage}'")
    for sibling in s.siblings:
        if not os.path.isdir(os.path.join(TOP, "cases", sibling)):
            raise st.error("siblings", f"no case cases/{sibling}")
    s.ranks = st.number("ranks", default=1, whole=True, positive=True)
    s.arguments = st.items("arguments") if st.found("arguments") else []
    s.description = st.word("description", default="")
    s.post_process = st.items("postProcess") if st.found("postProcess") else []
    if s.allrun is None and st.found("cores"):
        raise st.error("cores", "only with 'allrun' (an application point takes its ranks)")
    s.cores = s.ranks if s.allrun is None else st.number("cores", default=_allrun_cores(s.allrun), whole=True,
                                                         positive=True)
    if s.post_process:
        script = os.path.join(TOP, s.post_process[0])
        if not os.path.isfile(script) or os.path.isabs(s.post_process[0]):
            raise st.error("postProcess", f"needs a script of this checkout first (e.g. postProcessing/"
                                          f"failureAnalysis.py), got '{s.post_process[0]}'")

    kd = top.subdict("knobs")
    if not kd.keys():
        raise StudyDictError(path, kd.line, "knobs", "needs at least one knob")
    s.knobs = []
    s.includes = []   # (block, key, path) of every "file:#include" entry: checked by missing_includes
    for name in kd.keys():
        _check_name(kd, name, "knob", [k.name for k in s.knobs])
        s.knobs.append(_read_knob(kd.subdict(name), name, s, path))

    names = [k.name for k in s.knobs]
    for knob in s.knobs:
        if knob.template is not None:
            for ref in re.findall(r"\$\{([^}]*)\}", knob.template):
                if ref not in names and ref != "STUDY":
                    raise kd.subdict(knob.name).error(
                        "template", f"'${{{ref}}}' names no knob (knobs: {', '.join(names)}; or STUDY, this "
                                    "study's folder)")
            if "$" in re.sub(r"\$\{[^}]*\}", "", knob.template):
                raise kd.subdict(knob.name).error("template", "a '$' only as ${knob} or ${STUDY}")

    s.scatter, s.scatter_at = (None, None) if not top.found("scatter") else _read_scatter(top.subdict("scatter"), s, path)
    if s.summary_by:
        by, table = s.summary_by
        knob = next((k for k in s.knobs + ([s.scatter] if s.scatter else []) if k.name == by), None)
        if knob is None:
            raise st.subdict("summary").error("by", f"'{by}' names no knob ({', '.join(k.name for k in s.knobs)})")
        needed = knob.values
        if knob is s.scatter:   # the other seeds, and the case's own for every other point
            if knob.case_value is None:
                raise st.subdict("summary").error("by", f"the scatter knob '{by}' needs the case's own value "
                                                        "(name it with 'caseEntry file:dotted;')")
            needed = [knob.case_value] + knob.values
        missing = [v for v in needed if v not in table]
        if missing:
            raise StudyDictError(path, st.subdict("summary").line, "study.summary",
                                 f"no path for {by} {', '.join(missing)}")
    elif "$" in s.summary:   # "runs/${resolution}-speed${speed}/...": the point's values of the knobs
        names = {k.name for k in s.knobs}
        for ref in re.findall(r"\$\{([^}]*)\}", s.summary):
            if ref not in names:
                raise st.error("summary", f"'${{{ref}}}' names no knob ({', '.join(sorted(names))})")
        if "$" in re.sub(r"\$\{[^}]*\}", "", s.summary):
            raise st.error("summary", "a '$' only as ${knob}")
    s.fixed = _fixed_entries(top.subdict("set"), s) if top.found("set") else []
    # the knobs' `with` blocks were read before `set`: their includes are in s.includes too

    fd = top.subdict("figures")
    if not fd.keys():
        raise StudyDictError(path, fd.line, "figures", "needs at least one figure")
    s.figures = []   # (name, dotted key in summary.json)
    for name in fd.keys():
        _check_name(fd, name, "figure", [k.name for k in s.knobs] + [n for n, _ in s.figures]
                    + ([s.scatter.name] if s.scatter else []))
        e = fd.entries[name]
        if e.kind == "dict":
            e.value.check_keys({"key"})
            key = e.value.word("key")
        else:
            key = fd.word(name)
        if not re.fullmatch(r"([\w./]+\.json:)?[\w.\[\]]+", key) or \
                os.path.normpath(os.path.join(os.path.dirname(s.summary), key.split(":")[0])).startswith(".."):
            raise fd.error(name, f"needs a dotted key of the summary (runs[0].x for a list's item), or "
                                 f"file.json:dotted.key of another file of the point's case, its path from the "
                                 f"summary's folder, got '{key}'")
        s.figures.append((name, key))

    rd = top.subdict("reference")
    s.reference_type = rd.word("type", allowed=("measured", "finest", "summary", "none"))
    if s.reference_type == "measured":
        rd.check_keys({"type", "values", "file", "quantities", "source"})
        s.reference_source = rd.word("source", default="")
        s.reference = {}
        if rd.found("file"):
            ref_file = rd.word("file").replace("$SHARED", SHARED)
            ref_file = os.path.normpath(os.path.join(s.folder, ref_file))
            if not os.path.isfile(ref_file):
                raise rd.error("file", f"no file {ref_file}")
            table = {}
            with open(ref_file) as f:
                for row in csv.DictReader(line for line in f if not line.startswith("#")):
                    table[row.get("quantity")] = row.get("value")
            qd = rd.subdict("quantities")
            for name in qd.keys():
                q = qd.word(name)
                if q not in table or _number(table[q]) is None:
                    raise qd.error(name, f"no numeric quantity '{q}' in {ref_file}")
                s.reference[name] = _number(table[q])
            s.reference_source = s.reference_source or os.path.relpath(ref_file, TOP)
        if rd.found("values"):
            vd = rd.subdict("values")
            for name in vd.keys():
                s.reference[name] = vd.number(name)
        names = [n for n, _ in s.figures]
        for name in s.reference:
            if name not in names:
                raise StudyDictError(path, rd.line, "reference", f"'{name}' is no figure (figures: {', '.join(names)})")
        if not s.reference:
            raise StudyDictError(path, rd.line, "reference", "a measured reference needs 'values { ... }' or 'file'")
    elif s.reference_type == "summary":   # an analytic answer the point computes itself (Archimedes, the ODE)
        rd.check_keys({"type", "keys", "source"})
        kd = rd.subdict("keys")
        names = [n for n, _ in s.figures]
        s.reference_keys = {}
        for name in kd.keys():
            if name not in names:
                raise kd.error(name, f"'{name}' is no figure (figures: {', '.join(names)})")
            s.reference_keys[name] = kd.word(name)
        if not s.reference_keys:
            raise StudyDictError(path, kd.line, "reference.keys", "needs at least one figure's key")
        s.reference_source = rd.word("source", default="the point's own summary")
    elif s.reference_type == "none":   # a map, not a convergence study: no error columns to fill
        rd.check_keys({"type"})
    else:
        rd.check_keys({"type"})
        if not any(k.finer for k in s.knobs):
            raise rd.error("type", "'finest' needs at least one knob with 'finer larger;' or 'finer smaller;'")
    return s


def _allrun_cores(options):
    """The cores an Allrun point takes: its -np (or -jobs), 1 without."""
    for flag in ("-np", "-jobs"):
        if flag in options[:-1]:
            n = _number(options[options.index(flag) + 1])
            if n is not None and n >= 1:
                return int(n)
    return 1


def _read_scatter(sd, s, path):
    """`scatter { <knob> { entry ...; values (...); } at { knob value; ... } }`: the packings (or
    other seeds) run at the chosen point `at` beside its own, to measure the scatter of its figures."""
    names = [n for n in sd.keys() if n != "at"]
    if len(names) != 1:
        raise StudyDictError(path, sd.line, "scatter", "needs one knob (the seed: entry or option, values) "
                                                       "and 'at { knob value; }'")
    name = names[0]
    _check_name(sd, name, "scatter knob", [k.name for k in s.knobs])
    knob = _read_knob(sd.subdict(name), name, s, path)
    for key in ("finer", "with", "template"):
        if sd.subdict(name).found(key):
            raise sd.subdict(name).error(key, "not for the scatter's knob")
    if knob.case_value in knob.values:
        raise sd.subdict(name).error("values", f"'{knob.case_value}' is the case's own value, which the point "
                                               "`at` runs already: list the other seeds")
    at = sd.subdict("at")
    at.check_keys({k.name for k in s.knobs})
    values = {}
    for k in s.knobs:
        v = at.word(k.name)
        if v == "default":
            v = k.case_value
        if v not in k.values:
            raise at.error(k.name, f"'{v}' is not among the knob's values ({', '.join(k.values)})")
        values[k.name] = v
    return knob, values


def missing_includes(study):
    """StudyDictErrors of the #include entries whose file is not there, and of the saved stages
    (study.stages) not built yet."""
    stages = [StudyDictError(study.dict_path, 0, "study.stages", f"no saved stage {stage} in this checkout: run the "
                             f"Allrun of the case that builds it first (e.g. cases/keelBond/Allrun builds "
                             f"cases/ridgeFlexure/keels/keel0.5)")
              for stage in study.stages if not os.path.isdir(os.path.join(TOP, stage))]
    return stages + [block.error(key, f"no file {path} (the path is relative to the case file's folder, as the case's own "
                             "#include lines; a generated dictionary is written by the step that makes it)")
            for block, key, path in study.includes if not os.path.isfile(path)]


if __name__ == "__main__":
    try:
        study = read_study(sys.argv[1])
    except StudyDictError as e:
        sys.exit(str(e))
    for k in study.knobs:
        print(k.name, k.where(), k.values, "quick", k.quick, "case", k.case_value, "finer", k.finer)
