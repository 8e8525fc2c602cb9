#!/usr/bin/python3
"""Tests of postProcessing/failureAnalysis.py on synthetic breakage records.

    failureAnalysisTest.py CLASS   (ClassifierTest, CountsTest, MomentsTest, OutputsTest,
                                    BadInputTest), as ctest runs them."""
import importlib.util
import json
import os
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, "..", "..", "postProcessing", "failureAnalysis.py")
sys.path.insert(0, os.path.dirname(TOOL))
sys.path.insert(0, HERE)

import failureAnalysis as fa  # noqa: E402
import syntheticRecords as syn  # noqa: E402
from breakageRecord import read_geometry  # noqa: E402


def load_json(path):
    with open(path) as f:
        return json.load(f)


def run_tool(*args):
    return subprocess.run([sys.executable, TOOL, *args], capture_output=True, text=True)


class Folder(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.dir = self.tmp.name

    def tearDown(self):
        self.tmp.cleanup()

    def ridge_geometry(self):
        path = os.path.join(self.dir, "ridge.json")
        with open(path, "w") as f:
            json.dump(syn.RIDGE, f)
        return read_geometry(path)


class ClassifierTest(Folder):
    def classify(self, name, seed=1):
        return fa.classifyRidgeFailure(syn.scenario(name, seed), self.ridge_geometry())

    def test_each_mode_is_recognised(self):
        for name in ("CL flexure", "keel V-crack from the bottom", "mixed", "plug shear"):
            for seed in (1, 2, 3):
                with self.subTest(mode=name, seed=seed):
                    self.assertEqual(self.classify(name, seed)["mode"], name)

    def test_rubble_punch_has_a_keel_only(self):
        path = os.path.join(self.dir, "keel.json")
        with open(path, "w") as f:
            json.dump(dict(syn.RIDGE, layers=syn.RIDGE["layers"][:1]), f)
        for name in ("keel V-crack from the bottom", "plug shear"):
            with self.subTest(mode=name):
                result = fa.classifyRidgeFailure(syn.scenario(name), read_geometry(path))
                self.assertEqual(result["mode"], name)
                self.assertEqual(result["evidence"]["share_cl"], 0.0)

    def test_a_clamped_layer_hinging_at_its_ends_is_cl_flexure(self):
        result = self.classify("clamped CL flexure")
        ev = result["evidence"]
        self.assertEqual(ev["first_share_cl"], 0.0)         # the keel's freeze-bonds went first
        self.assertLess(ev["cl_share_mid_span"], 0.6)        # a third at each end
        self.assertGreater(ev["cl_share_hinges"], 0.95)
        self.assertEqual(ev["first_ice_share_cl"], 1.0)
        self.assertEqual(result["mode"], "CL flexure")

    def test_cl_breaks_scattered_along_the_span_are_not_cl_flexure(self):
        result = self.classify("scattered CL")
        self.assertEqual(result["mode"], "undetermined")
        self.assertLess(result["evidence"]["cl_share_mid_span"], 0.6)
        self.assertLess(result["evidence"]["cl_share_hinges"], 0.6)

    def test_a_keel_crack_that_does_not_grow_upward_is_no_v_crack(self):
        result = self.classify("keel bottom band growing downward")
        self.assertEqual(result["evidence"]["first_share_keel_bottom_mid_span"], 1.0)
        self.assertLess(result["evidence"]["keel_late_median_height_m"],
                        result["evidence"]["keel_first_median_height_m"])
        self.assertEqual(result["mode"], "undetermined")

    def test_one_shear_band_is_no_plug(self):
        result = self.classify("one shear band")
        self.assertEqual(result["evidence"]["plug_bands"]["side_shares"], [1.0, 0.0])
        self.assertEqual(result["mode"], "undetermined")

    def test_coarse_particles_in_a_thin_cl(self):
        # A 0.10 m CL of 27.5 mm spheres: bond centres only between 27.5 and 72.5 mm up.
        record = syn.scenario("CL flexure")
        in_cl = record["z"] > 0.5
        record["z"][in_cl] = 0.5275 + (record["z"][in_cl] - 0.51) / 0.13 * 0.045
        thin = dict(syn.RIDGE, layers=[syn.RIDGE["layers"][0],
                                       {"name": "consolidatedLayer", "zBottom": 0.5,
                                        "zTop": 0.6}])
        path = os.path.join(self.dir, "thin.json")
        for radius, mode in ((0.0, "undetermined"), (0.0275, "CL flexure")):
            with open(path, "w") as f:
                json.dump(dict(thin, particleRadius=radius), f)
            result = fa.classifyRidgeFailure(record, read_geometry(path))
            with self.subTest(particleRadius=radius):
                self.assertEqual(result["mode"], mode)
                # each face moved in by the radius, at most a quarter of the thickness
                expected = (record["z"][in_cl].max() - record["z"][in_cl].min()) \
                    / (0.1 - 2 * min(radius, 0.025))
                self.assertAlmostEqual(result["evidence"]["cl_thickness_cover_mid_span"],
                                       expected, places=12)

    def test_evidence_says_where_and_in_what_order(self):
        result = self.classify("keel V-crack from the bottom")
        ev = result["evidence"]
        self.assertEqual(ev["first_breaks"], 17)  # 10 % of 165, rounded up
        self.assertEqual(ev["first_share_keel_bottom_mid_span"], 1.0)
        self.assertLess(ev["first_break_s"]["keel"], ev["first_break_s"]["consolidatedLayer"])
        self.assertGreater(ev["keel_top_third_mean_abs_dx_m"],
                           2 * ev["keel_bottom_third_mean_abs_dx_m"])  # opens upward: a V
        self.assertTrue(any(line.startswith("first 10% of breaks (17") for line in result["text"]))

    def test_window_end_leaves_out_later_breaks(self):
        # The CL scenario's keel breaks start at t = 1.5 s; up to 1.4 s only the CL broke.
        record = syn.scenario("CL flexure")
        result = fa.classifyRidgeFailure(record, self.ridge_geometry(), windowEnd=1.4)
        self.assertEqual(result["evidence"]["window_breaks"], int((record["time"] <= 1.4).sum()))
        self.assertEqual(result["evidence"]["share_keel"], 0.0)

    def test_thresholds_are_parameters(self):
        strict = fa.RidgeFailureRules(dominantFraction=0.95)
        result = fa.classifyRidgeFailure(syn.scenario("CL flexure"), self.ridge_geometry(),
                                         rules=strict)
        self.assertEqual(result["mode"], "undetermined")  # the CL holds 88 %, not 95 %


def known_events():
    """3 ice tension at 0.1-0.3 s, 2 freeze shear at 0.5 s and 1.2 s, 1 freeze tension at
    0.6 s, 1 ice bending at 1.5 s, 1 ice twist at 1.8 s; z and x put them in known regions."""
    return {"time": [0.1, 0.2, 0.3, 0.5, 0.6, 1.2, 1.5, 1.8],
            "x": [1.5, 1.55, 1.6, 0.3, 1.5, 2.9, 1.52, 0.1],
            "y": [0.5] * 8,
            "z": [0.6, 0.52, 0.62, 0.2, 0.51, 0.3, 0.58, 0.1],
            "family": [0, 0, 0, 1, 1, 1, 0, 0],
            "mode": [1, 1, 1, 2, 1, 2, 4, 3]}


class CountsTest(Folder):
    def test_counts_by_mode_family_region(self):
        case = syn.make_case(os.path.join(self.dir, "case"), known_events(), syn.RIDGE)
        out = os.path.join(self.dir, "out")
        self.assertEqual(run_tool(case, "--out", out).returncode, 0)
        summary = load_json(os.path.join(out, "summary.json"))
        counts = summary["counts"]
        self.assertEqual(counts["total"], 8)
        self.assertEqual(counts["mode"], {"tension": 4, "shear": 2, "twist": 1, "bending": 1})
        self.assertEqual(counts["family"], {"ice": 5, "freeze": 3})
        self.assertEqual(counts["family_mode"]["freeze"],
                         {"tension": 1, "shear": 2, "twist": 0, "bending": 0})
        # keel: z 0.2, 0.3, 0.1; CL: the rest; centre |x - 1.525| <= 0.25: five;
        # interface: the freeze-bond at z 0.51 (CL bottom 0.5, tolerance 0.05), not the ice
        # bond at z 0.52.
        self.assertEqual(counts["region"], {"keel": 3, "consolidatedLayer": 5, "centre": 5,
                                            "ends": 3, "interface": 1})
        self.assertAlmostEqual(summary["freeze_bonds_broken_in_tension_fraction"], 1 / 3)
        self.assertEqual(summary["bonds_in_case"], {})  # the case has no summary.json

    def test_until_leaves_out_later_breaks_and_samples(self):
        # A run stopped by a blow-up: the breaks after 1.0 s (freeze shear at 1.2 s, ice bending at
        # 1.5 s, ice twist at 1.8 s) are the blow-up's and are not counted.
        case = syn.make_case(os.path.join(self.dir, "case"), known_events(), syn.RIDGE)
        out = os.path.join(self.dir, "out")
        self.assertEqual(run_tool(case, "--out", out, "--until", "1.0").returncode, 0)
        summary = load_json(os.path.join(out, "summary.json"))
        self.assertEqual(summary["until_s"], 1.0)
        self.assertEqual(summary["counts"]["total"], 5)
        self.assertEqual(summary["counts"]["mode"], {"tension": 4, "shear": 1, "twist": 0, "bending": 0})
        with open(os.path.join(out, "counts.csv")) as f:
            times = [float(line.split(",")[0]) for line in f.read().splitlines()[1:]]
        self.assertLessEqual(max(times), 1.0)
        refused = run_tool(case, "--until", "-1", "--out", os.path.join(self.dir, "o2"))
        self.assertNotEqual(refused.returncode, 0)
        self.assertIn("--until", refused.stderr)
        self.assertIn("positive time", refused.stderr)
        early = run_tool(case, "--until", "1e-9", "--out", os.path.join(self.dir, "o3"))
        self.assertNotEqual(early.returncode, 0)
        self.assertIn("needs at least two", early.stderr)

    def test_shares_of_the_bonds_the_case_had(self):
        case = syn.make_case(os.path.join(self.dir, "case"), known_events())
        with open(os.path.join(case, "postProcessing", "summary.json"), "w") as f:
            json.dump({"ice_bonds": 50, "freeze_bonds": 12}, f)
        out = os.path.join(self.dir, "out")
        self.assertEqual(run_tool(case, "--out", out, "-at", "0.55").returncode, 0)
        summary = load_json(os.path.join(out, "summary.json"))
        self.assertEqual(summary["broken_share_of_ice_bonds"], 5 / 50)
        self.assertEqual(summary["broken_share_of_freeze_bonds"], 3 / 12)
        self.assertEqual(summary["freeze_bonds_broken_in_tension_share_of_all_freeze_bonds"],
                         1 / 12)
        at = [m for m in summary["moments"] if m["name"] == "t0.55"][0]
        self.assertEqual(at["broken_share_of_ice_bonds"], 3 / 50)
        self.assertEqual(at["broken_share_of_freeze_bonds"], 1 / 12)

    def test_cumulative_counts_at_curve_samples(self):
        case = syn.make_case(os.path.join(self.dir, "case"), known_events())
        out = os.path.join(self.dir, "out")
        self.assertEqual(run_tool(case, "--out", out).returncode, 0)
        rows = np.genfromtxt(os.path.join(out, "counts.csv"), delimiter=",", names=True)
        self.assertEqual(len(rows), 201)  # every sample of the 0-2 s curve
        at = {round(t, 2): r for t, r in zip(rows["time"], rows)}
        self.assertEqual(at[0.5]["broken"], 4)  # the break at 0.5 s counts at 0.5 s
        self.assertEqual(at[0.55]["broken"], 4)
        self.assertEqual(at[0.55]["tension"], 3)
        self.assertEqual(at[0.55]["freeze_shear"], 1)
        self.assertEqual(at[2.0]["broken"], 8)
        self.assertEqual(at[2.0]["region_all"], 8)  # no geometry: one region
        self.assertEqual(at[0.05]["broken"], 0)


class MomentsTest(Folder):
    def test_moments_of_a_curve_with_known_peak(self):
        time, force = syn.triangle_curve(peak_time=1.0, peak_force=1e5, fall=80e3)
        moments, missing = fa.find_moments(time, 0.005 * time, force, extra_times=[0.25])
        by_name = {m["name"]: m for m in moments}
        self.assertEqual(missing, {})
        self.assertAlmostEqual(by_name["peak"]["time"], 1.0, places=12)
        self.assertAlmostEqual(by_name["peak"]["force"], 1e5, places=6)
        self.assertAlmostEqual(by_name["halfLoadBeforePeak"]["time"], 0.5, places=9)
        self.assertAlmostEqual(by_name["halfLoadAfterPeak"]["time"], 1.625, places=9)
        self.assertAlmostEqual(by_name["halfLoadAfterPeak"]["travel"], 0.005 * 1.625, places=12)
        self.assertAlmostEqual(by_name["t0.25"]["force"], 0.25e5, places=6)

    def test_the_last_rise_through_half_load_counts(self):
        # A load drop below half before the peak: half load before the peak is on the last rise.
        time = np.array([0.0, 1.0, 2.0, 3.0, 4.0, 5.0])
        force = np.array([0.0, 60.0, 20.0, 80.0, 100.0, 10.0])
        moments, _ = fa.find_moments(time, time, force)
        by_name = {m["name"]: m for m in moments}
        self.assertAlmostEqual(by_name["halfLoadBeforePeak"]["time"], 2.5)
        self.assertAlmostEqual(by_name["halfLoadAfterPeak"]["time"], 4 + 50 / 90)

    def test_half_load_not_reached_is_reported(self):
        time = np.linspace(0.0, 1.0, 11)
        moments, missing = fa.find_moments(time, time, 100.0 * time, extra_times=[0.5, 3.0])
        self.assertEqual([m["name"] for m in moments],
                         ["halfLoadBeforePeak", "peak", "t0.5", "t3"])
        self.assertIn("halfLoadAfterPeak", missing)
        self.assertNotIn("note", moments[2])
        self.assertIn("outside the force curve", moments[3]["note"])
        self.assertEqual(moments[3]["force"], 100.0)


class OutputsTest(Folder):
    def test_vtp_pvd_png_and_summary(self):
        record = syn.scenario("keel V-crack from the bottom")
        case = syn.make_case(os.path.join(self.dir, "case"), record, syn.RIDGE)
        out = os.path.join(self.dir, "out")
        result = run_tool(case, "--out", out, "-at", "1.3")
        self.assertEqual(result.returncode, 0, result.stderr)
        self.assertIn("ridge failure mode: keel V-crack from the bottom", result.stdout)
        summary = load_json(os.path.join(out, "summary.json"))
        self.assertEqual([m["name"] for m in summary["moments"]],
                         ["halfLoadBeforePeak", "peak", "halfLoadAfterPeak", "t1.3"])
        self.assertEqual(summary["ridge_failure"]["mode"], "keel V-crack from the bottom")

        collection = ET.parse(os.path.join(out, "moments.pvd")).getroot()
        files = [d.get("file") for d in collection.iter("DataSet")]
        self.assertEqual(files, [m["vtp"] for m in summary["moments"]])
        for moment in summary["moments"]:
            expected = int((record["time"] <= moment["time"]).sum())
            self.assertEqual(moment["counts"]["total"], expected)
            piece = ET.parse(os.path.join(out, moment["vtp"])).getroot().find("PolyData/Piece")
            self.assertEqual(int(piece.get("NumberOfPoints")), expected)
            self.assertEqual(int(piece.get("NumberOfVerts")), expected)
            arrays = {a.get("Name"): a.text.split() if a.text else []
                      for a in piece.iter("DataArray")}
            for name in ("mode", "family", "time", "layer", "centreBand", "interface"):
                self.assertEqual(len(arrays[name]), expected, name)
            self.assertEqual(len(arrays[None]), 3 * expected)  # the points
            if expected:
                self.assertLessEqual(max(map(float, arrays["time"])), moment["time"])
                self.assertEqual(sorted(set(arrays["family"])), ["1"])  # keel freeze-bonds
            png = os.path.join(out, moment["png"])
            with open(png, "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
            self.assertGreater(os.path.getsize(png), 20000)
        self.assertGreater(os.path.getsize(os.path.join(out, "counts.png")), 50000)
        self.assertFalse([f for f in os.listdir(out) if "tmp" in f])  # atomic writes finished

    @unittest.skipUnless(importlib.util.find_spec("vtk"), "python3-vtk9 not installed")
    def test_vtk_reads_the_moments_as_paraview_does(self):
        import vtk

        record = syn.scenario("plug shear")
        case = syn.make_case(os.path.join(self.dir, "case"), record, syn.RIDGE)
        out = os.path.join(self.dir, "out")
        self.assertEqual(run_tool(case, "--out", out).returncode, 0)
        peak = [m for m in load_json(os.path.join(out, "summary.json"))["moments"]
                if m["name"] == "halfLoadAfterPeak"][0]
        reader = vtk.vtkXMLPolyDataReader()
        reader.SetFileName(os.path.join(out, peak["vtp"]))
        reader.Update()
        self.assertEqual(reader.GetErrorCode(), 0)
        data = reader.GetOutput()
        selected = record["time"] <= peak["time"]
        self.assertEqual(data.GetNumberOfPoints(), int(selected.sum()))
        self.assertEqual(data.GetNumberOfVerts(), int(selected.sum()))
        modes = data.GetPointData().GetArray("mode")
        self.assertEqual([int(modes.GetValue(k)) for k in range(modes.GetNumberOfTuples())],
                         record["mode"][selected].tolist())
        self.assertAlmostEqual(data.GetPoint(3)[2], record["z"][selected][3], places=8)

    def test_order_of_events_is_in_time(self):
        case = syn.make_case(os.path.join(self.dir, "case"), known_events(), syn.RIDGE)
        out = os.path.join(self.dir, "out")
        self.assertEqual(run_tool(case, "--out", out).returncode, 0)
        order = load_json(os.path.join(out, "summary.json"))["order_of_events"]
        times = [e["time_s"] for e in order]
        self.assertEqual(times, sorted(times))
        first = {e["event"]: e["time_s"] for e in order}
        self.assertEqual(first["first break, family freeze"], 0.5)
        self.assertEqual(first["first break, mode twist"], 1.8)
        self.assertEqual(first["first break, region interface"], 0.6)


class BadInputTest(Folder):
    def check_refused(self, args, *fragments):
        result = run_tool(*args)
        self.assertNotEqual(result.returncode, 0)
        self.assertEqual(result.stdout, "")
        for fragment in fragments:
            self.assertIn(fragment, result.stderr)

    def test_missing_and_broken_files(self):
        case = syn.make_case(os.path.join(self.dir, "case"), known_events())
        out = os.path.join(self.dir, "out")
        self.check_refused([os.path.join(self.dir, "nowhere")], "nowhere", "not a directory")
        self.check_refused([case, "--breakage", os.path.join(case, "none.h5"), "--out", out],
                           "none.h5", "cannot open")
        h5 = os.path.join(self.dir, "noMode.h5")
        syn.write_record(h5, known_events(), drop=("mode",))
        self.check_refused([case, "--breakage", h5, "--out", out], "noMode.h5",
                           "'/breakage/mode'", "dataset missing")
        curve = os.path.join(self.dir, "noForce.csv")
        with open(curve, "w") as f:
            f.write("time,travel\n0,0\n1,1\n")
        self.check_refused([case, "--curve", curve, "--out", out], "noForce.csv",
                           "entry 'force'", "column missing")
        self.check_refused([case, "--curve", curve, "--columns", "time,travel,load_N", "--out",
                            out], "noForce.csv", "entry 'load_N'", "needed: time, travel, load_N")
        self.check_refused([case, "--columns", "time,force", "--out", out], "'--columns'",
                           "three column names")
        self.check_refused([case, "--curve", os.path.join(case, "gone.csv"), "--out", out],
                           "gone.csv", "cannot read")

    def test_bad_geometry_and_options(self):
        case = syn.make_case(os.path.join(self.dir, "case"), known_events())
        out = os.path.join(self.dir, "out")
        bad = dict(syn.RIDGE, layers=[{"name": "keel", "zBottom": 0.5, "zTop": 0.2}])
        path = os.path.join(self.dir, "bad.json")
        with open(path, "w") as f:
            json.dump(bad, f)
        self.check_refused([case, "--geometry", path, "--out", out], "bad.json", "layers[0]",
                           "zTop must be above zBottom")
        with open(path, "w") as f:
            json.dump(dict(syn.RIDGE, length="long"), f)
        self.check_refused([case, "--geometry", path, "--out", out], "entry 'length'",
                           "finite number")
        self.check_refused([case, "-at", "0.5,soon", "--out", out], "'-at'", "separated by commas")
        self.check_refused([case, "--centre-half-width", "-1", "--out", out],
                           "--centre-half-width", "positive")
        self.assertFalse(os.path.exists(os.path.join(out, "summary.json")))


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1] + sys.argv[1:], verbosity=2)
