#!/usr/bin/env bash
# Installs the Debian 12 packages vdrive needs. Idempotent; run as root.
#   setup-debian.sh          everything: build, test, benchmark, fuzz, run
#   setup-debian.sh --demo   only what building and running the program needs (tools/demo.sh):
#                            no test, browser, capture or fuzzing tools
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
program=(
  build-essential cmake ninja-build pkg-config
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libspdlog-dev libfmt-dev
  libeigen3-dev libode-dev
  libtinyxml2-dev libtomlplusplus-dev
  libcpp-httplib-dev libjs-chart.js
  fastddsgen libfastrtps-dev libfastcdr-dev
  iproute2 procps
)
tests=(
  git clang libclang-rt-14-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  chromium python3-websocket curl
  gnuplot-nox libpng-dev
  tshark
  python3 python3-yaml
)
packages=("${program[@]}")
[ "${1:-}" = "--demo" ] || packages+=("${tests[@]}")
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}"
  echo "wireshark-common wireshark-common/install-setuid boolean false" | debconf-set-selections
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
