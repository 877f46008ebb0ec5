#!/usr/bin/env bash
# A GigE Vision camera on a host with several network interfaces (issue 21): in a network
# namespace of its own with loopback and a second interface (a veth pair, 192.0.2.2/24: Debian's
# kernel here has no dummy module), the fake camera serves on 127.0.0.1; every URI `glarecam
# cameras` lists must capture, and `cameras` names loopback as the interface it streams to.
# Skips (exit 0, saying why) where a network namespace or a veth pair cannot be made.
# Usage: multihomed_cli_test.sh GLARECAM
set -uo pipefail
GLARECAM=$1
if [[ ${GLARECAM_IN_NETNS:-} != 1 ]]; then
  if ! unshare -n true 2>/dev/null; then
    echo "SKIP: cannot make a network namespace (unshare -n: not root, or not permitted here)"
    exit 0
  fi
  exec unshare -n env GLARECAM_IN_NETNS=1 bash "$0" "$@"
fi

WORK=$(mktemp -d)
FAKE_PID=
trap '[[ -n $FAKE_PID ]] && kill -9 $FAKE_PID 2>/dev/null; rm -rf "$WORK"' EXIT
source "$(dirname "$0")/cli_test_lib.sh"

ip link set lo up
if ! ip link add gc0 type veth peer name gc1 2>"$WORK/ip.err"; then
  echo "SKIP: no second interface in the namespace: $(cat "$WORK/ip.err")"
  exit 0
fi
ip addr add 192.0.2.2/24 dev gc0 && ip link set gc0 up && ip link set gc1 up
expect "two IPv4 interfaces up" test "$(ip -4 -o addr show up | wc -l)" -ge 2

"$GLARECAM" fake-camera --size 320x256 >"$WORK/fake.out" 2>"$WORK/fake.err" &
FAKE_PID=$!
for _ in $(seq 100); do [[ -s $WORK/fake.out ]] && break; sleep 0.1; done
expect "the fake camera serves on loopback" test "$(cat "$WORK/fake.out")" = "aravis:127.0.0.1"

check "cameras" 0 "$GLARECAM" cameras
cp "$WORK/out" "$WORK/cameras"
expect "cameras lists the fake camera" grep -q "^aravis:.*GV01" "$WORK/cameras"
expect "it streams to loopback, not to gc0" grep -q "GV01.*streams to lo (127.0.0.1)" "$WORK/cameras"
for listed in $(grep -o "^aravis:[^ ]*" "$WORK/cameras") aravis: aravis:127.0.0.1; do
  check "capture from $listed" 0 timeout 60 "$GLARECAM" capture --camera "$listed" \
    --exposures 1000,2000 --out "$WORK/stacks" --no-progress
done
expect "one stack per capture" test "$(ls "$WORK/stacks" | wc -l)" -eq 3
finish
