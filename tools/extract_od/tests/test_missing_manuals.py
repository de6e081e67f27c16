"""Without the vendor manuals (a clone of the public repository has none), the checks that read them
are skipped with a message saying what is missing and how to supply it; where $VDRIVE_REQUIRE_SEEDS is
set (.ci/run) the same absence is a failure."""
import os
import subprocess
import sys
import tempfile
import unittest

from odtest import SKIP, run

HERE = os.path.dirname(os.path.abspath(__file__))


def run_without_manuals(module, require):
    with tempfile.TemporaryDirectory() as empty:
        env = dict(os.environ, VDRIVE_SEEDS=empty, PYTHONDONTWRITEBYTECODE="1")
        env.pop("VDRIVE_REQUIRE_SEEDS", None)
        if require:
            env["VDRIVE_REQUIRE_SEEDS"] = "1"
        return subprocess.run([sys.executable, os.path.join(HERE, module)], env=env,
                              capture_output=True, text=True, timeout=120)


class MissingManuals(unittest.TestCase):
    def test_checks_that_read_the_manuals_are_skipped_with_a_message(self):
        for module in ("test_counts.py", "test_regenerate.py"):
            proc = run_without_manuals(module, require=False)
            self.assertEqual(proc.returncode, SKIP, f"{module}: {proc.stdout}{proc.stderr}")
            self.assertIn("SKIPPED", proc.stdout)
            self.assertIn("VDRIVE_SEEDS", proc.stdout, "the message says how to supply the manuals")

    def test_where_ci_requires_them_their_absence_fails(self):
        for module in ("test_counts.py", "test_regenerate.py"):
            proc = run_without_manuals(module, require=True)
            self.assertEqual(proc.returncode, 1, f"{module}: {proc.stdout}{proc.stderr}")
            self.assertIn("SEEDS MISSING", proc.stdout)


if __name__ == "__main__":
    run("__main__")
