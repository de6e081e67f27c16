#!/usr/bin/env python3
"""Runs the command blocks the documents mark runnable, as a reader would type them.

A fenced ```sh block right after a line `<!-- runnable -->` is runnable. A document's runnable
blocks run in order in one bash (so a process started with `&` in one block can be stopped with
`kill %1` in a later one), with `set -e`, from a scratch directory that holds the checkout's
`scenarios/` and `docs/` (as links), and with the built `vdrive` and `vdrive-master` first on PATH.
A document passes when its bash exits 0 within the time limit.

Usage: doc_blocks.py SOURCE_DIR BUILD_DIR [DOC.md ...]   (default: README.md and docs/*.md)
Exit: 0 every document with runnable blocks passed, 1 one failed, 77 none to run.
"""
import glob
import os
import re
import signal
import subprocess
import sys
import tempfile

MARK = "<!-- runnable -->"
LIMIT_S = 300


def runnable_blocks(path):
    lines = open(path, encoding="utf-8").read().splitlines()
    blocks, i = [], 0
    while i < len(lines):
        if lines[i].strip() == MARK:
            j = i + 1
            if j >= len(lines) or not re.match(r"^```(sh|bash)\s*$", lines[j].strip()):
                raise SystemExit(f"{path}:{i + 1}: {MARK} is not followed by a ```sh block")
            k = j + 1
            while k < len(lines) and lines[k].strip() != "```":
                k += 1
            blocks.append((j + 2, lines[j + 1:k]))
            i = k
        i += 1
    return blocks


def main():
    source, build = os.path.abspath(sys.argv[1]), os.path.abspath(sys.argv[2])
    docs = sys.argv[3:] or [os.path.join(source, "README.md")] + sorted(glob.glob(os.path.join(source, "docs", "*.md")))
    env = dict(os.environ)
    env["PATH"] = f"{build}/vdrive:{build}/master:{env['PATH']}"
    ran, failed = 0, []
    for doc in docs:
        blocks = runnable_blocks(doc)
        if not blocks:
            continue
        ran += 1
        name = os.path.relpath(doc, source)
        script = ["set -e"]
        for first_line, body in blocks:
            script.append(f"echo '+ {name}:{first_line}'")
            script.extend(body)
        with tempfile.TemporaryDirectory() as work:
            for d in ("scenarios", "docs"):
                os.symlink(os.path.join(source, d), os.path.join(work, d))
            log_path = os.path.join(work, "output.log")
            with open(log_path, "w") as log:
                # Its own session, so whatever a block left running is stopped with it; the output
                # goes to a file, as a process left running would hold a pipe open.
                proc = subprocess.Popen(["bash", "-c", "\n".join(script)], cwd=work, env=env, stdout=log,
                                        stderr=subprocess.STDOUT, start_new_session=True)
                try:
                    code = proc.wait(timeout=LIMIT_S)
                    ok, why = code == 0, f"exit {code}"
                except subprocess.TimeoutExpired:
                    ok, why = False, f"over {LIMIT_S} s"
                finally:
                    try:
                        os.killpg(proc.pid, signal.SIGTERM)
                    except ProcessLookupError:
                        pass
                    proc.wait()
            out = open(log_path, encoding="utf-8", errors="replace").read()
        print(f"{'PASS' if ok else 'FAIL'} {name}: {len(blocks)} block(s){'' if ok else ', ' + why}")
        if not ok:
            print(out[-4000:])
            failed.append(name)
    if ran == 0:
        print("SKIP: no document marks a block runnable")
        return 77
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
