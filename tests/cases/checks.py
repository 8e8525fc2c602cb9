"""The checks of a test script: each prints ok or FAIL with what it checked; finish() exits 1
if any failed."""
import sys

failures = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what, flush=True)
    if not ok:
        failures.append(what)


def finish():
    sys.exit(1 if failures else 0)
