#!/usr/bin/env bash
# Cables two running containers together with a veth pair: one end becomes interface IF_A inside
# container A, the other IF_B inside container B, both up. This is the "cable" between a vdrive
# container and a master container (docs/docker.md); neither container needs a network of its
# own (network_mode: none). Run as root on the Docker host, after both containers started.
#
#   docker/veth-between.sh CONTAINER_A IF_A CONTAINER_B IF_B
#
# A container is named as Docker knows it (name or id), or as pid:N for any process whose
# network namespace is meant (no Docker needed: tests/docker/veth_between_test.sh uses that).
# The pair lives as long as both namespaces; it goes away with either container.
# Exit 2: bad arguments; 1: a container not running, a name taken, an ip command that failed.
set -euo pipefail

usage() { echo "usage: $0 CONTAINER_A IF_A CONTAINER_B IF_B   (CONTAINER: docker name/id or pid:N)" >&2; exit 2; }
die() { echo "veth-between: $*" >&2; exit 1; }
(($# == 4)) || usage

valid_ifname() { [[ $1 =~ ^[A-Za-z0-9_.-]{1,15}$ ]]; }   # IFNAMSIZ: at most 15 characters

# PID of a process inside the container's network namespace.
netns_pid() {
  local pid
  if [[ $1 == pid:* ]]; then
    pid=${1#pid:}
    [[ $pid =~ ^[0-9]+$ ]] || usage
  else
    command -v docker >/dev/null || die "docker not found (name containers as pid:N without Docker)"
    pid=$(docker inspect -f '{{.State.Pid}}' "$1" 2>/dev/null) || die "no container '$1'"
  fi
  [[ $pid != 0 && -d /proc/$pid ]] || die "'$1' is not running"
  echo "$pid"
}

a=$1 if_a=$2 b=$3 if_b=$4
valid_ifname "$if_a" || die "bad interface name '$if_a' (1-15 letters, digits, '_', '.', '-')"
valid_ifname "$if_b" || die "bad interface name '$if_b' (1-15 letters, digits, '_', '.', '-')"
pid_a=$(netns_pid "$a")
pid_b=$(netns_pid "$b")
[[ "$(readlink "/proc/$pid_a/ns/net")" != "$(readlink "/proc/$pid_b/ns/net")" ]] \
  || die "'$a' and '$b' share one network namespace"
for side in "$pid_a:$if_a:$a" "$pid_b:$if_b:$b"; do
  IFS=: read -r pid ifname name <<<"$side"
  nsenter -t "$pid" -n ip link show "$ifname" >/dev/null 2>&1 && die "'$name' already has an interface '$ifname'"
done

# Made in this namespace under temporary names (the final names may be taken here), then moved
# and renamed; if anything fails before both ends are moved, the pair is deleted again.
tmp_a="vb$$a" tmp_b="vb$$b"
ip link add "$tmp_a" type veth peer name "$tmp_b" || die "cannot create a veth pair"
trap 'ip link del "$tmp_a" 2>/dev/null || ip link del "$tmp_b" 2>/dev/null || true' EXIT
ip link set "$tmp_a" netns "$pid_a" || die "cannot move a veth end into '$a'"
ip link set "$tmp_b" netns "$pid_b" || die "cannot move a veth end into '$b'"
trap - EXIT
nsenter -t "$pid_a" -n ip link set "$tmp_a" name "$if_a" || die "cannot rename the end in '$a'"
nsenter -t "$pid_b" -n ip link set "$tmp_b" name "$if_b" || die "cannot rename the end in '$b'"
nsenter -t "$pid_a" -n ip link set "$if_a" up
nsenter -t "$pid_b" -n ip link set "$if_b" up
echo "veth-between: $a:$if_a <-> $b:$if_b"
