#!/usr/bin/python3
"""Tests of cases/ridgeFlexure/studies/forceCurves.py on a made-up ridgeFlexure case: the stop
rule replayed (at 0.5 it must give back each run's own stop, at a higher fraction it stops where
the rule says and counts the peaks it would miss), the spike test, the running means, the README
blocks, and a clear exit where the replay does not match a run or no run is finished."""
import csv
import json
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "..", "cases", "ridgeFlexure", "studies", "forceCurves.py")
SAMPLE = 0.00021    # m of travel between samples (not a divisor of the rule's 5 mm: no ties)
AFTER = 24          # samples from the first below the fraction to the stop: the first past 5 mm
LAST = 476          # the last sample of a run that went to maxTravel (0.1 m)
SPEED = 0.05        # m/s


def rise_and_fall(peak_at, peak, fall_to, samples, spike_at=None, spike=None):
    """A force curve rising linearly to `peak` at sample `peak_at`, then falling linearly to
    `fall_to` x peak at the last sample; optionally one sample replaced by `spike`."""
    force = []
    for i in range(samples):
        if i <= peak_at:
            force.append(peak * i / peak_at)
        else:
            force.append(peak * (1.0 - (1.0 - fall_to) * (i - peak_at) / (samples - 1 - peak_at)))
    if spike_at is not None:
        force[spike_at] = spike
    return force


class ForceCurvesTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.case = self.tmp.name
        os.makedirs(os.path.join(self.case, "results"))
        with open(os.path.join(self.case, "README.md"), "w") as f:
            f.write("# ridge\n\n<!-- ridge force spikes -->\n<!-- end ridge force spikes -->\n\n"
                    "<!-- ridge early stop -->\n<!-- end ridge early stop -->\n")

    def tearDown(self):
        self.tmp.cleanup()

    def add_run(self, folder, name, force, finished=True, kinetic=None):
        path = os.path.join(self.case, "runs", folder, name, "postProcessing")
        os.makedirs(path)
        with open(os.path.join(path, "platenForce.csv"), "w", newline="") as f:
            writer = csv.writer(f)
            writer.writerow(["time", "travel", "force", "brokenBonds", "kineticEnergy"])
            for i, value in enumerate(force):
                writer.writerow([0.2 + i * SAMPLE / SPEED, i * SAMPLE, value, 2 * i,
                                 (kinetic or {}).get(i, 1.0)])
        with open(os.path.join(path, "summary.json"), "w") as f:
            json.dump({"complete": finished}, f)
        # the stop rule's entries, as the case's (the script reads each run's own)
        os.makedirs(os.path.join(path, "..", "system"))
        with open(os.path.join(path, "..", "system", "controlDict"), "w") as f:
            f.write(f"maxTravel 0.1;\nminTravel 0.03;  // m\ntravelAfterHalfLoad 0.005;\nsampleInterval {SAMPLE};\n")

    def stopped_run(self, name, peak_at, fall_samples):
        """A run the half-load rule stopped: rising to its peak, falling below half within
        `fall_samples`, ending on the first sample more than 5 mm after the first below half."""
        force = [1000.0 * i / peak_at for i in range(peak_at + 1)]
        force += [1000.0 * (1.0 - 0.6 * k / fall_samples) for k in range(1, fall_samples + 1)]
        first_below = next(i for i in range(peak_at, len(force)) if force[i] < 500.0)
        force += [400.0] * (first_below + AFTER + 1 - len(force))
        self.add_run("default-iceStiff", name, force)
        return force

    def run_tool(self, *args):
        return subprocess.run([sys.executable, TOOL, "--case", self.case, "--publish", *args],
                              capture_output=True, text=True)

    def rows(self, stem):
        with open(os.path.join(self.case, "results", stem + ".csv"), newline="") as f:
            return list(csv.DictReader(f))

    def test_replays_the_stop_rule_and_finds_the_spike(self):
        self.stopped_run_force = self.stopped_run("run01_keel0.5_2min_CL0", peak_at=200, fall_samples=40)
        # ran to maxTravel, its load never below half: the rule never fired
        self.add_run("default-iceStiff", "run02_keel0.5_2min_CL10", rise_and_fall(300, 2000.0, 0.6, LAST + 1))
        # two peaks: 1000 N at sample 200, a dip to 900 N, then 1100 N at 300; to maxTravel
        twin = [1000.0 * i / 200 for i in range(201)] + [1000.0 - 100.0 * k / 30 for k in range(1, 31)]
        twin += [900.0] * 30 + [900.0 + 200.0 * k / 40 for k in range(1, 41)]
        twin += [1100.0 * (1.0 - 0.1 * k / (LAST - 300)) for k in range(1, LAST - 300 + 1)]
        self.add_run("default-iceStiff", "run04_keel0.5_2min_CL20", twin)
        # the layer alone, with a one-sample spike near its top and the kinetic energy jumping there
        layer = rise_and_fall(200, 1000.0, 0.9, LAST + 1, spike_at=210, spike=1600.0)
        self.add_run("default", "layerAlone_CL10", layer, kinetic={210: 4.0})
        self.add_run("default-iceStiff", "run03_keel0.5_2min_CL15", [1.0, 2.0], finished=False)   # not finished: left out
        result = self.run_tool("--fractions", "0.5,0.7,0.95")
        self.assertEqual(result.returncode, 0, result.stderr)

        stops = {r["fraction_of_peak"]: r for r in self.rows("earlyStop")}
        self.assertEqual(stops["0.5"]["runs"], "4")
        self.assertEqual(float(stops["0.5"]["loading_time_kept"]), 1.0)
        self.assertEqual(float(stops["0.5"]["broken_bonds_counted"]), 1.0)
        self.assertEqual(stops["0.5"]["runs_stopped_before_their_peak"], "none")
        # at 0.7 run01 stops 24 samples after falling below 700 N (21 samples past its peak),
        # the layer 24 after its spike, run02 24 after falling below 1400 N, run04 goes on
        run01 = 200 + 21 + AFTER
        run02 = 300 + next(k for k in range(LAST) if 2000.0 * (1.0 - 0.4 * k / (LAST - 300)) < 1400.0) + AFTER
        kept = (run01 + (210 + 1 + AFTER) + run02 + LAST) / (len(self.stopped_run_force) - 1 + 3 * LAST)
        self.assertAlmostEqual(float(stops["0.7"]["loading_time_kept"]), round(kept, 3))
        self.assertEqual(stops["0.7"]["runs_stopped_before_their_peak"], "none")
        # at 0.95 run04 stops in its dip, before its second, higher peak: 1000 against 1100 N
        self.assertEqual(stops["0.95"]["runs_stopped_before_their_peak"], "run04 -9.1%")

        spikes = {r["run"]: r for r in self.rows("forceSpikes")}
        self.assertEqual(spikes["layerAlone_CL10"]["spike"], "yes")
        self.assertAlmostEqual(float(spikes["layerAlone_CL10"]["peak_kN"]), 1.6)
        self.assertAlmostEqual(float(spikes["layerAlone_CL10"]["kinetic_at_peak_over_median"]), 4.0)
        self.assertEqual(spikes["run02"]["spike"], "no")
        # the 3-sample mean around the spike: (1600 + its two neighbours) / 3
        neighbours = layer[209] + layer[211]
        self.assertAlmostEqual(float(spikes["layerAlone_CL10"]["running_mean_3_kN"]),
                               round((1600.0 + neighbours) / 3 * 1e-3, 3))
        self.assertAlmostEqual(float(spikes["run02"]["running_mean_3_kN"]), 2.0, places=2)

        readme = open(os.path.join(self.case, "README.md")).read()
        self.assertIn("| layerAlone_CL10 | 1.6 at", readme)
        self.assertIn("| 0.95 | 4 |", readme)

    def test_a_stop_the_replay_does_not_give_back_is_refused(self):
        force = self.stopped_run("run01_keel0.5_2min_CL0", peak_at=200, fall_samples=40)
        # the same curve cut two samples before its stop: the rule would not have stopped it there
        self.add_run("default-iceStiff", "run02_keel0.5_2min_CL10", force[:-2])
        result = self.run_tool()
        self.assertEqual(result.returncode, 1)
        self.assertIn("run02_keel0.5_2min_CL10", result.stderr)
        self.assertNotIn("Traceback", result.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.case, "results", "earlyStop.csv")))

    def test_another_speed_reads_its_own_runs_and_is_not_published(self):
        self.add_run("default-speed0.025-iceStiff", "run01_keel0.5_2min_CL0", rise_and_fall(300, 2000.0, 0.6, LAST + 1))
        result = self.run_tool("--speed", "0.025")
        self.assertEqual(result.returncode, 2)
        self.assertIn("--speed: without --publish", result.stderr)
        result = subprocess.run([sys.executable, TOOL, "--case", self.case, "--speed", "0.025"],
                                capture_output=True, text=True)
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(os.path.join(self.case, "runs", "forceCurves-speed0.025", "forceSpikes.csv"), newline="") as f:
            self.assertEqual([r["run"] for r in csv.DictReader(f)], ["run01"])
        self.assertFalse(os.path.exists(os.path.join(self.case, "results", "forceSpikes.csv")))

    def test_no_finished_run(self):
        self.add_run("default-iceStiff", "run01_keel0.5_2min_CL0", [1.0, 2.0], finished=False)
        result = self.run_tool()
        self.assertEqual(result.returncode, 1)
        self.assertIn("no finished run", result.stderr)


if __name__ == "__main__":
    unittest.main()
