#!/usr/bin/python3
"""Compares the outputs two builds' test runs left in their build/tests folders, for refactors
that must not change behaviour: every CSV byte for byte, every HDF5 file dataset by dataset and
attribute by attribute (HDF5 files differ in bytes between runs: object timestamps). Attributes
that name the checkout's path are reported apart, as they differ whenever the folders do.

Usage: tests/compareOutputs.py BEFORE/build/tests AFTER/build/tests
Exit status 0 when every file of BEFORE is in AFTER and equal, 1 otherwise.
"""
import os
import sys

import h5py
import numpy as np


def files(root):
    for folder, _, names in os.walk(root):
        if "CMakeFiles" in folder:
            continue
        for name in names:
            if name.endswith((".csv", ".h5")):
                yield os.path.relpath(os.path.join(folder, name), root)


def hdf5_contents(path):
    contents = {"/": dict(h5py.File(path, "r").attrs)}
    with h5py.File(path, "r") as f:
        def visit(name, obj):
            contents["attrs " + name] = dict(obj.attrs)
            if isinstance(obj, h5py.Dataset):
                contents[name] = obj[()]
        f.visititems(visit)
    return contents


def equal(x, y):
    if isinstance(x, dict):
        return x.keys() == y.keys() and all(equal(x[k], y[k]) for k in x)
    return np.array_equal(np.asarray(x), np.asarray(y))


def differing_entries(before, after, roots):
    """(datasets or groups that differ, attribute sets that differ only by the checkout's path,
    attribute names present or different on one side only: metadata, not data)."""
    a, b = hdf5_contents(before), hdf5_contents(after)
    if a.keys() != b.keys():
        return sorted(set(a) ^ set(b)), [], []
    differing, path_only, metadata = [], [], []
    for key in a:
        if equal(a[key], b[key]):
            continue
        if isinstance(a[key], dict):
            x = {k: str(v).replace(roots[0], "ROOT") for k, v in a[key].items()}
            y = {k: str(v).replace(roots[1], "ROOT") for k, v in b[key].items()}
            changed = sorted(k for k in set(x) | set(y) if x.get(k) != y.get(k))
            if changed:
                metadata.extend(f"{key}:{k}" for k in changed)
            else:
                path_only.append(key)
        else:
            differing.append(key)
    return differing, path_only, metadata


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    before, after = sys.argv[1:]
    roots = [os.path.dirname(os.path.dirname(os.path.abspath(p))) for p in (before, after)]
    counts = {"identical": 0, "equal but for the checkout path": 0, "equal data, other attributes": 0,
              "DIFFERENT": 0, "MISSING after": 0, "new after": 0}
    attributes = set()
    for rel in sorted(set(files(before)) | set(files(after))):
        a, b = os.path.join(before, rel), os.path.join(after, rel)
        if not os.path.exists(b):
            verdict = "MISSING after"
        elif not os.path.exists(a):
            verdict = "new after"
        elif rel.endswith(".csv"):
            verdict = "identical" if open(a, "rb").read() == open(b, "rb").read() else "DIFFERENT"
        else:
            differing, path_only, metadata = differing_entries(a, b, roots)
            attributes.update(m.split(":", 1)[1] for m in metadata)
            verdict = ("DIFFERENT" if differing else "equal data, other attributes" if metadata
                       else "equal but for the checkout path" if path_only else "identical")
        counts[verdict] += 1
        if verdict in ("DIFFERENT", "MISSING after"):
            print(f"{verdict}: {rel}")
    print(", ".join(f"{n} {k}" for k, n in counts.items()))
    if attributes:
        print("attributes that differ (HDF5 metadata, not data):", ", ".join(sorted(attributes)))
    sys.exit(1 if counts["DIFFERENT"] or counts["MISSING after"] else 0)


if __name__ == "__main__":
    main()
