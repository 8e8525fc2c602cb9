#!/usr/bin/python3
"""postProcessing/iceCases.py's dictionary reading and editing (get_entry, set_entry), which every
study, test and script uses to set a case's entry: a keyword or brace written in a comment is never
taken for the entry, a string keeps its '//', and an entry from an #include is overridden after it."""
import os
import sys
import tempfile
import unittest

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))),
                                "postProcessing"))
import iceCases  # noqa: E402

DICT = """// the fluid's deltaT must
// divide couplingInterval * demTimeStep.
couplingInterval    10;     // DEM steps { per exchange }
/* a block comment naming speed 3; and loading { speed 4; } */
demScript           "DEM/in.x // not a comment";
loading
{
    // speed 1; in a comment
    speed           0.005;  // m/s
}
"""


class DictionaryEditTest(unittest.TestCase):
    def setUp(self):
        self.folder = tempfile.mkdtemp()
        self.path = os.path.join(self.folder, "dict")
        with open(self.path, "w") as f:
            f.write(DICT)

    def test_comments_are_not_entries(self):
        self.assertEqual(iceCases.get_entry(self.path, "couplingInterval"), "10")
        self.assertEqual(iceCases.get_entry(self.path, "loading.speed"), "0.005")
        with self.assertRaises(KeyError):
            iceCases.get_entry(self.path, "speed")   # only in the comments at the top level

    def test_string_keeps_its_slashes(self):
        self.assertEqual(iceCases.get_entry(self.path, "demScript"), '"DEM/in.x // not a comment"')

    def test_set_changes_the_entry_only(self):
        iceCases.set_entry(self.path, "loading.speed", 0.02)
        iceCases.set_entry(self.path, "couplingInterval", 20)
        text = open(self.path).read()
        self.assertEqual(text, DICT.replace("0.005;", "0.02;").replace("10;     //", "20;     //"))

    def test_override_after_include(self):
        with open(os.path.join(self.folder, "common"), "w") as f:
            f.write("timeStep\n{\n    factor 0.25;   // timeStep { factor 9; }\n}\n")
        case = os.path.join(self.folder, "case")
        with open(case, "w") as f:
            f.write('// the common timeStep {, shared by every case\n#include "common"\n')
        self.assertEqual(iceCases.get_entry(case, "timeStep.factor"), "0.25")
        iceCases.set_entry(case, "timeStep.factor", 0.125)
        self.assertEqual(iceCases.get_entry(case, "timeStep.factor"), "0.125")
        self.assertIn("0.25", open(os.path.join(self.folder, "common")).read())


if __name__ == "__main__":
    unittest.main()
