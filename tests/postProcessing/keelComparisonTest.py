#!/usr/bin/python3
"""Tests of cases/ridgeFlexure/studies/keelComparison.py on a made-up ridgeFlexure case: the two
published matrices joined run by run, the assembly read from the runs' assembly.json or logs (both
spellings of a layer that sank), the README block written, and a clear exit when nothing is published in both."""
import csv
import json
import os
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "..", "cases", "ridgeFlexure", "studies", "keelComparison.py")

COLUMNS = ("run,keel_m,bond_set,CL_cm,depth_m,failure_force_kN,layer_alone_kN,keel_contribution_kN,"
           "failure_mode").split(",")


def assembly_log(floor_pa, freeze, layer_keel, mean_kpa, max_kpa, layer_line=None):
    lines = [f"Compacted keel held between plates at z = 0.358102 and 1.62949 m: {floor_pa} Pa on the floor plate, "
             "0 Pa on the lid, 28 spheres touching them, when the bonds are made",
             f"Bonds: 29895 ice bonds (blocks and layer), {freeze} freeze-bonds ({layer_keel} between layer and keel); "
             f"confinement {mean_kpa} kPa mean, {max_kpa} kPa max on the real area; effective tensile 5.3 kPa"]
    if layer_line:
        lines.insert(0, "Layer balanced on the stiffening keel (assembly.layerHold balanced): " + layer_line
                     + ", net force -4.5 N, speed -0.005 m/s at the end")
    return "\n".join(lines) + "\n"


class KeelComparisonTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.case = self.tmp.name
        os.makedirs(os.path.join(self.case, "results"))
        with open(os.path.join(self.case, "README.md"), "w") as f:
            f.write("# ridge\n\n<!-- ridgeMatrix keel comparison -->\n(not yet published)\n"
                    "<!-- end ridgeMatrix keel comparison -->\n\nafter\n")

    def tearDown(self):
        self.tmp.cleanup()

    def publish(self, table, rows):
        with open(os.path.join(self.case, "results", table), "w", newline="") as f:
            writer = csv.DictWriter(f, COLUMNS)
            writer.writeheader()
            for row in rows:
                writer.writerow(dict(zip(COLUMNS, row)))

    def log(self, folder, run, text):
        path = os.path.join(self.case, "runs", folder, run)
        os.makedirs(path)
        with open(os.path.join(path, "log.ridgeDEM"), "w") as f:
            f.write(text)

    def run_tool(self):
        return subprocess.run([sys.executable, TOOL, "--case", self.case], capture_output=True, text=True)

    def test_joins_the_matrices_and_reads_the_assembly(self):
        self.publish("ridgeMatrix_default_softened.csv", [
            (1, 0.5, "2min", 0, 0.55, 1.926, 0.0, 1.926, "undetermined"),
            (2, 0.5, "2min", 10, 0.62, 7.261, 4.936, 2.325, "mixed; CL 66%"),
            (3, 0.5, "2min", 15, 0.66, 14.18, 12.0, 2.18, "CL flexure")])
        self.publish("ridgeMatrix_default_iceStiff.csv", [
            (1, 0.5, "2min", 0, 0.60, 1.87, 0.0, 1.87, "undetermined"),
            (2, 0.5, "2min", 10, 0.69, 7.53, 4.936, 2.594, "mixed")])
        self.log("default", "run01_keel0.5_2min_CL0", assembly_log(2200.5, 840, 0, 286.4, 9000))
        self.log("default", "run02_keel0.5_2min_CL10", assembly_log(13300, 900, 120, 1520, 44600))
        self.log("default-iceStiff", "run01_keel0.5_2min_CL0", assembly_log(260, 700, 0, 18.04, 600))
        self.log("default-iceStiff", "run02_keel0.5_2min_CL10",
                 assembly_log(319.708, 743, 71, 28.9162, 1128.27, "moved -1.40797 mm up"))
        result = self.run_tool()
        self.assertEqual(result.returncode, 0, result.stderr)
        with open(os.path.join(self.case, "results", "ridgeMatrix_keelComparison.csv"), newline="") as f:
            rows = list(csv.DictReader(f))
        self.assertEqual([r["run"] for r in rows], ["1", "2"])  # run 3 is published in one matrix only
        first, second = rows
        self.assertEqual(first["floor_plate_kPa_softened"], "2.2")
        self.assertEqual(first["floor_plate_kPa_iceStiff"], "0.26")
        self.assertEqual(second["freeze_bonds_iceStiff"], "743")
        self.assertEqual(second["layer_keel_bonds_iceStiff"], "71")
        self.assertEqual(second["confinement_mean_kPa_iceStiff"], "28.9")
        self.assertEqual(second["layer_rise_mm_iceStiff"], "-1.41")
        self.assertEqual(second["layer_rise_mm_softened"], "0.0")  # pressed: the layer did not move
        self.assertEqual(second["failure_force_kN_iceStiff"], "7.53")
        self.assertEqual(second["failure_mode_softened"], "mixed")
        with open(os.path.join(self.case, "README.md")) as f:
            readme = f.read()
        self.assertNotIn("(not yet published)", readme)
        self.assertIn("| 2 | 0.5 | 2min | 10 | 13.3 / 0.32 |", readme)
        self.assertTrue(readme.endswith("<!-- end ridgeMatrix keel comparison -->\n\nafter\n"))

    def test_a_layer_that_sank_reads_alike_in_both_spellings(self):
        rows = [(1, 0.5, "2min", 10, 0.6, 7.0, 4.9, 2.1, "mixed")]
        self.publish("ridgeMatrix_default_softened.csv", rows)
        self.publish("ridgeMatrix_default_iceStiff.csv", rows)
        self.log("default", "run01_keel0.5_2min_CL10", assembly_log(300, 700, 70, 20, 500, "moved 2.5 mm down"))
        self.log("default-iceStiff", "run01_keel0.5_2min_CL10", assembly_log(300, 700, 70, 20, 500, "moved 0.75 mm up"))
        self.assertEqual(self.run_tool().returncode, 0)
        with open(os.path.join(self.case, "results", "ridgeMatrix_keelComparison.csv"), newline="") as f:
            row = next(csv.DictReader(f))
        self.assertEqual((row["layer_rise_mm_softened"], row["layer_rise_mm_iceStiff"]), ("-2.5", "0.75"))

    def test_a_resumed_run_reads_its_assembly_json(self):
        rows = [(1, 1.0, "ultimate", 10, 1.25, 16.22, 4.936, 11.284, "mixed")]
        self.publish("ridgeMatrix_default_softened.csv", rows)
        self.publish("ridgeMatrix_default_iceStiff.csv", rows)
        self.log("default", "run01_keel1.0_ultimate_CL10", assembly_log(18172, 1412, 67, 1517.2, 44000))
        resumed = "run01_keel1.0_ultimate_CL10"
        self.log("default-iceStiff", resumed, "Loading: 16427 particles (13825 keel, 2602 layer)\n")
        os.makedirs(os.path.join(self.case, "runs", "default-iceStiff", resumed, "postProcessing"))
        with open(os.path.join(self.case, "runs", "default-iceStiff", resumed, "postProcessing", "assembly.json"), "w") as f:
            json.dump({"layer_hold": "balanced", "layer_rise_during_stiffening_m": -0.000973, "floor_plate_Pa": 258.2,
                       "lid_Pa": 0.0, "freeze_bonds": 2157, "freeze_bonds_layer_keel": 70,
                       "confinement_mean_Pa": 18104.0, "confinement_max_Pa": 912345.0}, f)
        self.assertEqual(self.run_tool().returncode, 0)
        with open(os.path.join(self.case, "results", "ridgeMatrix_keelComparison.csv"), newline="") as f:
            row = next(csv.DictReader(f))
        self.assertEqual([row[k + "_iceStiff"] for k in ("floor_plate_kPa", "freeze_bonds", "layer_keel_bonds",
                                                         "confinement_mean_kPa", "layer_rise_mm")],
                         ["0.258", "2157", "70", "18.1", "-0.97"])
        self.assertEqual(row["floor_plate_kPa_softened"], "18.172")  # the log, where there is no assembly.json

    def test_nothing_published_in_both_stops_with_a_message(self):
        self.publish("ridgeMatrix_default_softened.csv", [(1, 0.5, "2min", 0, 0.55, 1.9, 0.0, 1.9, "x")])
        self.publish("ridgeMatrix_default_iceStiff.csv", [(2, 0.5, "2min", 10, 0.6, 7.5, 4.9, 2.6, "x")])
        result = self.run_tool()
        self.assertNotEqual(result.returncode, 0)
        self.assertIn("no run published in both", result.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.case, "results", "ridgeMatrix_keelComparison.csv")))


if __name__ == "__main__":
    unittest.main()
