#!/usr/bin/env bash
# Prints the Debian packages that hold the shared libraries the given programs load, one per line,
# sorted. The image's build stage runs it on the installed binaries so that the runtime stage
# installs exactly those packages, whatever libraries the build linked (no list to keep by hand).
# Exit 1 naming the library when one is not found or not owned by a package.
set -euo pipefail
(($#)) || { echo "usage: $0 PROGRAM..." >&2; exit 2; }
declare -A packages=()
for program in "$@"; do
  [[ -x $program ]] || { echo "runtime-packages: $program: not an executable" >&2; exit 1; }
  while read -r name arrow path _; do
    [[ $arrow == "=>" ]] || continue                      # linux-vdso, the loader itself
    [[ $path == "not" ]] && { echo "runtime-packages: $program: $name not found" >&2; exit 1; }
    owner=""
    # dpkg records a library under the path its package ships: /lib or /usr/lib (usrmerge).
    for candidate in "$path" "$(realpath "$path")" "/usr${path#/usr}" "${path#/usr}"; do
      owner=$(dpkg-query -S "$candidate" 2>/dev/null | head -n1 | cut -d: -f1) && [[ -n $owner ]] && break
    done
    [[ -n $owner ]] || { echo "runtime-packages: $program: no package owns $path" >&2; exit 1; }
    packages[$owner]=1
  done < <(ldd "$program")
done
printf '%s\n' "${!packages[@]}" | sort
