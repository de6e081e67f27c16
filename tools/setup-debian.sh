#!/usr/bin/env bash
# Installs every Debian 12 package vdrive needs to build, test and run. Idempotent; run as root.
set -euo pipefail
export DEBIAN_FRONTEND=noninteractive
packages=(
  build-essential cmake ninja-build pkg-config git
  clang libclang-rt-14-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  libyaml-cpp-dev libcli11-dev nlohmann-json3-dev libspdlog-dev libfmt-dev
  libeigen3-dev libode-dev
  libtinyxml2-dev libtomlplusplus-dev
  libcpp-httplib-dev libjs-chart.js
  chromium python3-websocket curl
  fastddsgen libfastrtps-dev libfastcdr-dev
  gnuplot-nox libpng-dev
  iproute2 tshark procps
  python3 python3-yaml
)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  echo "setup: installing ${missing[*]}"
  echo "wireshark-common wireshark-common/install-setuid boolean false" | debconf-set-selections
  apt-get update -qq
  apt-get install -y -qq --no-install-recommends "${missing[@]}"
fi
