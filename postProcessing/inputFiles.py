#!/usr/bin/python3
"""Prints, one per line, the files under each PATH (files or folders) and, recursively, the
files their dictionaries #include (iceCases.input_files): what bin/caseCommon.sh's
inputs_fingerprint hashes.

usage: inputFiles.py PATH..."""
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from iceCases import input_files  # noqa: E402

if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    print("\n".join(input_files(sys.argv[1:])))
