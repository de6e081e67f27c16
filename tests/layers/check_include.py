"""Compiles one layer probe with the command CMake generated for it and checks the outcome.

Usage: check_include.py COMPILE_COMMANDS SOURCE fails|compiles HEADER
'fails' passes only when the compiler stops because HEADER is not on the probe's include path."""
import json
import shlex
import subprocess
import sys

commands, source, expect, header = sys.argv[1:5]
entry = next((e for e in json.load(open(commands)) if e["file"] == source), None)
if entry is None:
    sys.exit(f"check_include: no compile command for {source} in {commands}")
argv = shlex.split(entry["command"]) if "command" in entry else entry["arguments"]
# Only the front end: drop the output file and check the syntax.
if "-o" in argv:
    i = argv.index("-o")
    del argv[i:i + 2]
argv.append("-fsyntax-only")
result = subprocess.run(argv, cwd=entry["directory"], capture_output=True, text=True)
out = result.stdout + result.stderr
if expect == "compiles":
    if result.returncode != 0:
        sys.exit(f"expected {source} to compile:\n{out}")
    print(f"{source}: compiles")
else:
    if result.returncode == 0:
        sys.exit(f"expected {source} not to compile: the layer sees {header}")
    if f"{header}: No such file or directory" not in out:
        sys.exit(f"{source} failed, but not for want of {header}:\n{out}")
    print(f"{source}: {header} is not visible to this layer, as required")
