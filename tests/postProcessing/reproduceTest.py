#!/usr/bin/python3
"""bin/reproduce on a project of tiny cases: entries run by separate bin/reproduce processes side by
side are reported together, with each run's wall time and exit status, by one -dry over all (long
entries included, which a plain call skips); a figure outside its tolerance is STALE and makes the
exit status 1; -dry for an entry never run is a failure, not a fresh figure; an entry that another
bin/reproduce is running is not run again beside it (which would remove its scratch copy)."""
import csv
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import unittest

TOP = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# The case's run writes its summary; how long it takes and what it writes come from its arguments.
ALLRUN = """#!/bin/sh
touch started
sleep "$1"
mkdir -p postProcessing
echo "{\\"force_N\\": $2}" > postProcessing/summary.json
exit "$3"
"""


def entry(case, seconds, value, status, committed_value, rel):
    return {"case": case, "command": ["./Allrun", str(seconds), str(value), str(status)], "long": False,
            "wall_s": 1, "wall_note": "test", "tolerance_why": "test",
            "summaries": [{"fresh": "postProcessing/summary.json", "committed": "results/summary.json",
                           "figures": [{"name": "force [N]", "key": "force_N", "rel": rel}]}],
            "_committed": committed_value}


class ReproduceTest(unittest.TestCase):
    def setUp(self):
        self.top = tempfile.mkdtemp(prefix="reproduceTest")
        os.makedirs(os.path.join(self.top, "bin"))
        os.makedirs(os.path.join(self.top, "postProcessing"))
        shutil.copy2(os.path.join(TOP, "bin", "reproduce"), os.path.join(self.top, "bin"))
        shutil.copy2(os.path.join(TOP, "postProcessing", "caseMirror.py"), os.path.join(self.top, "postProcessing"))
        entries = {"fresh": entry("caseA", 1, 100.0, 0, 100.0, 1e-6),
                   "stale": dict(entry("caseB", 1, 103.0, 0, 100.0, 0.02), long=True),
                   "failed": entry("caseC", 0, 100.0, 3, 100.0, 1e-6),
                   "neverRun": entry("caseD", 0, 100.0, 0, 100.0, 1e-6),
                   "slow": entry("caseE", 3, 100.0, 0, 100.0, 1e-6),
                   "caseAOther": entry("caseA", 0, 100.0, 0, 100.0, 1e-6)}
        for e in entries.values():
            case = os.path.join(self.top, "cases", e["case"])
            os.makedirs(os.path.join(case, "results"), exist_ok=True)
            with open(os.path.join(case, "Allrun"), "w") as f:
                f.write(ALLRUN)
            os.chmod(os.path.join(case, "Allrun"), 0o755)
            with open(os.path.join(case, "results", "summary.json"), "w") as f:
                json.dump({"force_N": e.pop("_committed")}, f)
        with open(os.path.join(self.top, "bin", "reproduce.json"), "w") as f:
            json.dump({"entries": entries}, f)
        self.work = os.path.join(self.top, "build", "reproduce")

    def tearDown(self):
        shutil.rmtree(self.top, ignore_errors=True)

    def reproduce(self, *args):
        return subprocess.Popen([sys.executable, os.path.join(self.top, "bin", "reproduce"), *args],
                                stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)

    def report_rows(self):
        with open(os.path.join(self.work, "report.csv"), newline="") as f:
            return {r["entry"]: r for r in csv.DictReader(f)}

    def test_side_by_side_then_one_dry_report(self):
        runs = [self.reproduce(*names) for names in (["fresh"], ["-long", "stale"], ["failed"])]
        for run in runs:
            run.communicate(timeout=60)
        self.assertEqual([r.returncode for r in runs], [0, 1, 1])

        dry = self.reproduce("-dry", "fresh", "stale", "failed", "neverRun")   # the long one too
        out, _ = dry.communicate(timeout=60)
        self.assertEqual(dry.returncode, 1, out)
        rows = self.report_rows()
        self.assertEqual({k: r["verdict"] for k, r in rows.items()},
                         {"fresh": "fresh", "stale": "STALE", "failed": "FAILED", "neverRun": "FAILED"})
        # each run's own wall time (it slept 1 s), not the dry pass's
        self.assertGreaterEqual(float(rows["fresh"]["wall_s"]), 1.0)
        self.assertLess(float(rows["fresh"]["wall_s"]), 30.0)
        self.assertAlmostEqual(float(rows["stale"]["relative"]), 0.03, places=12)
        self.assertIn("exited 3", rows["failed"]["note"])
        self.assertIn("no earlier run", rows["neverRun"]["note"])
        self.assertEqual(rows["neverRun"]["wall_s"], "")
        with open(os.path.join(self.work, "report.md")) as f:
            report = f.read()
        self.assertIn("| caseA | fresh | `./Allrun 1 100.0 0` | 1 (1) | 1 / 0 / 0 |", report)
        self.assertIn("| caseB | stale | `./Allrun 1 103.0 0` | 1 (1) | 0 / 1 / 0 |", report)

    def test_an_entry_running_elsewhere_is_not_run_beside_it(self):
        first = self.reproduce("slow")
        marker = os.path.join(self.work, "slow", "cases", "caseE", "started")
        for _ in range(200):                 # until the first has made its copy and started the case
            if os.path.exists(marker):
                break
            time.sleep(0.05)
        second = self.reproduce("slow")
        out2, _ = second.communicate(timeout=60)
        out1, _ = first.communicate(timeout=60)
        self.assertEqual(first.returncode, 0, out1)
        self.assertEqual(second.returncode, 1, out2)
        self.assertIn("another bin/reproduce is running it", out2)
        self.assertTrue(os.path.exists(os.path.join(self.work, "slow", "cases", "caseE", "postProcessing",
                                                    "summary.json")))

    def test_long_entry_is_skipped_without_long(self):
        run = self.reproduce("stale")
        out, _ = run.communicate(timeout=60)
        self.assertEqual(run.returncode, 0, out)
        self.assertIn("skipped, long", out)
        self.assertFalse(os.path.exists(os.path.join(self.work, "stale")))

    def test_exact_selects_the_entry_not_its_case(self):
        for args, expected in ((["-list", "caseA"], ["fresh", "caseAOther"]), (["-list", "-exact", "fresh"], ["fresh"]),
                               (["-list", "fresh"], ["fresh"])):
            run = self.reproduce(*args)
            out, _ = run.communicate(timeout=60)
            self.assertEqual(run.returncode, 0, out)
            listed = [line.split(":")[0] for line in out.splitlines() if line and not line.startswith(" ")]
            self.assertEqual(listed, expected, args)
        run = self.reproduce("-exact", "caseA")          # a case's name is no entry's
        out, _ = run.communicate(timeout=60)
        self.assertEqual(run.returncode, 2, out)
        self.assertIn("caseA: no such entry in", out)

    def test_unknown_entry_is_a_usage_error(self):
        run = self.reproduce("noSuchEntry")
        out, _ = run.communicate(timeout=60)
        self.assertEqual(run.returncode, 2)
        self.assertIn("noSuchEntry: no such entry or case", out)


if __name__ == "__main__":
    unittest.main()
