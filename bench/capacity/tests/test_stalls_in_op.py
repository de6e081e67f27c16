"""stalls_in_op.py: which host stalls of a `vdrive run` log fall after the line reached Op."""
import os
import subprocess
import sys
import tempfile
import unittest

SCRIPT = os.path.join(os.path.dirname(__file__), "..", "stalls_in_op.py")

# Two parts: part 2 stalls while the master brings the line up, part 1 once in Op, and part 2
# once in Op with a "more host stalls" summary line (the reader's ring overflowed).
LOG = """\
[2026-11-28 02:54:04.490] [part 2] [warning] host stall 1.8 ms (threshold 1.0 ms): drives 21-40 caught up 15 control steps
[2026-11-28 02:54:09.690] [vdrive] [info] slave 1 @0x1001 a6b: SafeOp -> Op
[2026-11-28 02:54:09.697] [part 2] [info] slave 21 @0x1015 ds5c1: SafeOp -> Op
[2026-11-28 02:54:09.800] [part 2] [warning] host stall 2.5 ms (threshold 2.0 ms): slaves 21-40 missed 1 SYNC0 pulse
[2026-11-28 02:54:16.572] [vdrive] [warning] host stall 10.7 ms (threshold 2.0 ms): slaves 1-20 missed 9 SYNC0 pulses and caught up 86 control steps
[2026-11-28 02:54:17.000] [part 2] [warning] 5 more host stalls (longest so far 14.2 ms)
[2026-11-28 02:54:25.588] [vdrive] [warning] host stalls: 1, longest 10.7 ms (docs/reliability.md)
"""


def run(text, parts):
    with tempfile.NamedTemporaryFile("w", suffix=".log", delete=False) as f:
        f.write(text)
    try:
        r = subprocess.run([sys.executable, SCRIPT, f.name, str(parts)], capture_output=True, text=True)
    finally:
        os.unlink(f.name)
    return r.returncode, r.stdout.strip()


class StallsInOp(unittest.TestCase):
    def test_counts_only_stalls_after_op_plus_the_margin_per_part(self):
        # Part 2's 1.8 ms stall came before Op, its 2.5 ms one within 0.25 s of the last "-> Op".
        self.assertEqual(run(LOG, 2), (1, "1, longest 10.7 ms/5, longest 14.2 ms"))

    def test_a_line_without_stalls_in_op_passes(self):
        quiet = "\n".join(l for l in LOG.splitlines() if "host stall" not in l or "02:54:04" in l) + "\n"
        self.assertEqual(run(quiet, 2), (0, "none/none"))

    def test_a_log_that_never_reached_op_is_its_own_answer(self):
        code, out = run(LOG.replace("-> Op", "-> SafeOp"), 2)
        self.assertEqual((code, out), (2, "the line never reached Op"))

    def test_bad_arguments_are_refused(self):
        self.assertEqual(run(LOG, 0)[0], 2)

    def test_a_log_that_cannot_be_read_is_named(self):
        r = subprocess.run([sys.executable, SCRIPT, "/nonexistent/vdrive.log", "1"], capture_output=True, text=True)
        self.assertEqual(r.returncode, 2)
        self.assertEqual(r.stderr.strip(), "stalls_in_op.py: cannot read /nonexistent/vdrive.log: No such file or directory")
        self.assertNotIn("Traceback", r.stderr)


if __name__ == "__main__":
    unittest.main()
