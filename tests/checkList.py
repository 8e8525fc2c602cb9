"""The ok / FAIL lines of the python tests and their exit status: `check = CheckList()`, then
`check(condition, "what was checked")` as often as needed, and `check.finish()` at the end (exit
status 1 when any check failed)."""
import sys


class CheckList:
    def __init__(self):
        self.failures = []

    def __call__(self, ok, text):
        print(("ok   " if ok else "FAIL ") + text, flush=True)
        if not ok:
            self.failures.append(text)
        return ok

    def finish(self):
        if self.failures:
            print(f"{len(self.failures)} check(s) failed")
            sys.exit(1)
        print("all checks passed")
