#!/usr/bin/python3
"""Checks that a coupled run on several ranks exchanged only the particles near each rank's part
of the fluid mesh (coupling/README.md, "Parallel"): iceFoam's closing line
"particles near each rank's part of the mesh at the end: LOW to HIGH of TOTAL" must show every
rank holding some particles, none holding them all, and together at least all of them.

usage: checkLocalExchange.py LOG [--most-per-rank FRACTION]"""
import argparse
import re
import sys


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("log")
    parser.add_argument("--most-per-rank", type=float, default=0.75,
                        help="the largest share of all particles one rank may hold")
    args = parser.parse_args()
    text = open(args.log).read()
    found = re.search(r"particles near each rank's part of the mesh at the end: (\d+) to (\d+) of (\d+)", text)
    if not found:
        sys.exit(f"{args.log}: no line 'particles near each rank's part of the mesh' (iceFoam's end)")
    low, high, total = (int(g) for g in found.groups())
    print(f"particles held per rank: {low} to {high} of {total}")
    failures = []
    if low == 0:
        failures.append("a rank held no particle")
    if high > args.most_per_rank * total:
        failures.append(f"a rank held {high} of {total} particles, above {args.most_per_rank:g} of them")
    if 2 * high < total:
        failures.append(f"two ranks of at most {high} cannot hold all {total} particles")
    if failures:
        sys.exit("; ".join(failures))


if __name__ == "__main__":
    main()
