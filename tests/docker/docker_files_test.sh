#!/usr/bin/env bash
# The Docker image, checked without a Docker engine (CI machines have none, docs/docker.md):
# - docker/Dockerfile: Debian 12 only, runs the tree's own tools/setup-debian.sh and tools/build.sh,
#   every path it COPYs from the context exists, the stages compose.yaml names exist, entrypoint vdrive;
# - .dockerignore keeps build trees out of the context;
# - docker/compose.yaml parses as YAML with the services, capabilities and targets documented;
# - what the runtime stage relies on: `cmake --install` into a fresh prefix gives a vdrive and a
#   vdrive-master that run from another directory with nothing of the source tree (profiles built
#   in, installed YAML usable with --profile-dir, installed scenarios run), and
#   docker/runtime-packages.sh names installed packages that own every library they load.
# Usage: bash docker_files_test.sh <source-dir> <build-dir>
set -u
SRC=${1:?source directory}
BUILD=${2:?build directory}
fail() { echo "FAIL: $*"; exit 1; }
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
DF="$SRC/docker/Dockerfile"
[ -f "$DF" ] || fail "no $DF"

# --- Dockerfile ---------------------------------------------------------------------------------
froms=$(grep -E '^FROM ' "$DF" | awk '{print $2}' | sort -u | tr '\n' ' ')
for f in $froms; do
  case $f in debian:12|build|runtime|vdrive|master) ;; *) fail "Dockerfile: FROM $f is not debian:12 or one of its stages";; esac
done
grep -Eq '^FROM debian:12 AS build$' "$DF" || fail "Dockerfile: no build stage from debian:12"
[ "$(grep -E '^FROM ' "$DF" | tail -n1)" = "FROM runtime AS vdrive" ] || fail "Dockerfile: the default (last) stage is not vdrive"
grep -Eq '^RUN bash /src/tools/setup-debian.sh$' "$DF" || fail "Dockerfile: does not install packages with tools/setup-debian.sh"
grep -Eq 'bash /src/tools/build.sh' "$DF" || fail "Dockerfile: does not build with tools/build.sh"
grep -Eq '^ENTRYPOINT \["vdrive-entrypoint", "vdrive"\]$' "$DF" || fail "Dockerfile: entrypoint is not vdrive"
# No download but Debian packages: no curl/wget/git clone/pip/ADD of a URL.
if grep -Eiq '(curl|wget|git clone|pip install|^ADD +https?:)' "$DF"; then fail "Dockerfile downloads something"; fi
# The scripts it runs are the tree's (and executable where exec'd): each /src/X path exists as X.
for p in $(grep -oE '/src/[A-Za-z0-9_./-]+' "$DF" | sort -u); do
  [ "$p" = /src/ ] && continue
  [ -e "$SRC/${p#/src/}" ] || fail "Dockerfile uses $p, not in the tree"
done
# Every COPY from the build context (not --from=stage) names a path that exists.
while read -r _ srcpath _; do
  [ "$srcpath" = . ] && continue
  [ -e "$SRC/$srcpath" ] || fail "Dockerfile COPYs $srcpath, which does not exist"
done < <(grep -E '^COPY ' "$DF" | grep -v -- '--from=')
[ -x "$SRC/docker/entrypoint.sh" ] || fail "docker/entrypoint.sh is not executable (COPY keeps the mode)"
echo "ok: Dockerfile"

# --- .dockerignore ------------------------------------------------------------------------------
grep -Eq '^build/$' "$SRC/.dockerignore" || fail ".dockerignore does not exclude build/"
grep -Eq '^\.git/$' "$SRC/.dockerignore" || fail ".dockerignore does not exclude .git/"
echo "ok: .dockerignore"

# --- compose.yaml -------------------------------------------------------------------------------
python3 - "$SRC" <<'PY' || fail "docker/compose.yaml"
import os, re, sys, yaml
src = sys.argv[1]
with open(os.path.join(src, "docker/compose.yaml")) as f:
    c = yaml.safe_load(f)
stages = set(re.findall(r"^FROM \S+ AS (\S+)$", open(os.path.join(src, "docker/Dockerfile")).read(), re.M))
services = c["services"]
want = {"vdrive-nic": "host", "vdrive-line": "none", "master": "none"}
assert set(services) == set(want), f"services {sorted(services)}, expected {sorted(want)}"
for name, mode in want.items():
    s = services[name]
    assert s.get("network_mode") == mode, f"{name}: network_mode {s.get('network_mode')}, expected {mode}"
    caps = set(s.get("cap_add", []))
    assert {"NET_ADMIN", "NET_RAW"} <= caps, f"{name}: cap_add {sorted(caps)} lacks NET_ADMIN/NET_RAW"
    b = s["build"]
    ctx = os.path.normpath(os.path.join(src, "docker", b["context"]))
    assert ctx == os.path.normpath(src), f"{name}: build context {ctx} is not the checkout"
    assert os.path.isfile(os.path.join(ctx, b["dockerfile"])), f"{name}: no {b['dockerfile']}"
    assert b["target"] in stages, f"{name}: target {b['target']} not a stage of the Dockerfile ({sorted(stages)})"
    cmd = s["command"]
    assert "--iface" in cmd, f"{name}: command names no interface"
for name in ("vdrive-line", "master"):
    env = services[name]["environment"]
    iface = services[name]["command"][services[name]["command"].index("--iface") + 1]
    assert env["VDRIVE_WAIT_IFACE"] == iface, f"{name}: waits for {env['VDRIVE_WAIT_IFACE']}, serves {iface}"
    assert services[name].get("profiles") == ["veth"], f"{name}: not in profile veth"
assert services["vdrive-nic"]["build"]["target"] == "vdrive"
assert services["master"]["build"]["target"] == "master"
assert services["master"]["command"][0] == "op"
print("ok: compose.yaml")
PY

# --- cmake --install, run from elsewhere --------------------------------------------------------
PREFIX="$WORK/prefix"
cmake --install "$BUILD" --prefix "$PREFIX" >"$WORK/install.log" 2>&1 || { cat "$WORK/install.log"; fail "cmake --install"; }
for b in vdrive vdrive-master; do [ -x "$PREFIX/bin/$b" ] || fail "cmake --install gave no bin/$b"; done
mkdir "$WORK/elsewhere"
cd "$WORK/elsewhere" || fail "cd"
out=$("$PREFIX/bin/vdrive" list-drives) || fail "installed vdrive list-drives exited $?"
for id in a6b ds5c1 ds1000a; do echo "$out" | grep -Eq "^$id " || fail "installed vdrive list-drives lacks $id: $out"; done
"$PREFIX/bin/vdrive" od --drive a6b --index 0x6040 | grep -qi controlword || fail "installed vdrive od: no 6040h Controlword"
"$PREFIX/bin/vdrive-master" --help >/dev/null || fail "installed vdrive-master --help"
PROFILES="$PREFIX/share/vdrive/profiles"
for id in a6b ds5c1 ds1000a; do
  [ -f "$PROFILES/$id/profile.yaml" ] || fail "no installed $PROFILES/$id/profile.yaml"
  "$PREFIX/bin/vdrive" esi --drive "$id" --profile-dir "$PROFILES" -o "$WORK/$id.xml" || fail "vdrive esi --profile-dir (installed profiles) for $id"
  "$PREFIX/bin/vdrive" esi --drive "$id" -o "$WORK/$id.builtin.xml" || fail "vdrive esi (built-in) for $id"
  cmp -s "$WORK/$id.xml" "$WORK/$id.builtin.xml" || fail "$id: ESI from the installed profile differs from the built-in one"
done
[ ! -e "$PROFILES/CMakeLists.txt" ] || fail "build files installed with the profiles"
SCEN="$PREFIX/share/vdrive/scenarios"
[ "$(ls "$SCEN"/*.yaml | wc -l)" = "$(ls "$SRC"/scenarios/*.yaml | wc -l)" ] || fail "installed scenario library incomplete"
"$PREFIX/bin/vdrive" scenario run "$SCEN/plant_jam.yaml" >"$WORK/scen.txt" 2>&1 || { cat "$WORK/scen.txt"; fail "installed scenario (with its plant file) did not pass"; }
grep -q '^PASS plant_jam' "$WORK/scen.txt" || { cat "$WORK/scen.txt"; fail "no PASS line"; }
echo "ok: cmake --install runs from another directory"

# --- runtime-packages.sh ------------------------------------------------------------------------
pkgs=$(bash "$SRC/docker/runtime-packages.sh" "$PREFIX/bin/vdrive" "$PREFIX/bin/vdrive-master") || fail "runtime-packages.sh exited $?"
[ -n "$pkgs" ] || fail "runtime-packages.sh listed nothing"
for p in $pkgs; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || fail "runtime-packages.sh listed $p, not an installed package"
done
echo "$pkgs" | grep -qx libyaml-cpp0.7 || fail "libyaml-cpp0.7 (yaml-cpp) missing from: $pkgs"
# Every library vdrive loads lives in one of the listed packages (compared by real path: usrmerge).
for p in $pkgs; do dpkg -L "$p"; done | grep -E '\.so' | while read -r f; do [ -e "$f" ] && realpath "$f"; done \
  | sort -u >"$WORK/owned"
while read -r _ arrow path _; do
  [ "$arrow" = "=>" ] || continue
  grep -qxF "$(realpath "$path")" "$WORK/owned" || fail "$path (loaded by vdrive) is in none of: $pkgs"
done < <(ldd "$PREFIX/bin/vdrive")
bash "$SRC/docker/runtime-packages.sh" "$WORK/nonexistent" 2>"$WORK/rp.err"; rc=$?
[ $rc -eq 1 ] && grep -q "nonexistent: not an executable" "$WORK/rp.err" || fail "runtime-packages.sh on a missing file: exit $rc, $(cat "$WORK/rp.err")"
echo "ok: runtime-packages.sh"
echo PASS
