#!/usr/bin/python3
"""Bonded block crossing a rank boundary: 2 ranks must reproduce 1 rank's
particle states and bond histories (round-off only), with every bond kept, and
the block must really have crossed into the second rank."""
import sys


def load(path):
    header, rows = None, {}
    for line in open(path):
        if line.startswith("#"):
            header = line.split()
            continue
        kind, key, *values = line.split()
        rows[(kind, key)] = [float(v) for v in values]
    return dict(zip(header[1::2], map(int, header[2::2]))), rows


(h1, one), (h2, two) = load(sys.argv[1]), load(sys.argv[2])
assert h1["ranks"] == 1 and h2["ranks"] == 2
assert h1["bonds"] == h2["bonds"] > 100, (h1["bonds"], h2["bonds"])
assert h2["atomsOnLastRank"] > 0, "the block never reached the second rank"
assert one.keys() == two.keys(), "different particles or bonds"
worst = 0.0
for key, a in one.items():
    b = two[key]
    scale = max(max(abs(v) for v in a), 1e-12)
    worst = max(worst, max(abs(x - y) for x, y in zip(a, b)) / scale)
print(f"{h1['bonds']} bonds; {h2['atomsOnLastRank']} atoms on rank 1 at the end; "
      f"largest relative difference {worst:.3e}")
assert worst < 1e-8, "bond histories or particle states differ between 1 and 2 ranks"
print("1 passed, 0 failed")
