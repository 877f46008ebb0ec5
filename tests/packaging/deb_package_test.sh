#!/usr/bin/env bash
# The Debian package (`make package`, docs/operator.md "The Debian package"): built by CPack from
# this build, its control data, files and conffile, lintian without errors or warnings; then
# installed with dpkg into a fresh root (an overlay of this machine's root on a tmpfs, in a mount
# namespace of its own, so nothing here changes): its maintainer scripts create the service user
# and enable nothing, `glarecam --version` runs, `systemd-analyze verify` passes on the installed
# units; removal keeps the operator's edited config and the data, purge removes the config and
# never the data. Where the namespace or the mounts are not permitted, the install part checks the
# extracted tree instead and says so. Usage: deb_package_test.sh BUILD_DIR
set -uo pipefail
BUILD=$1
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
source "$(dirname "$0")/../apps/cli_test_lib.sh"

check "cpack builds the package" 0 cpack --config "$BUILD/CPackConfig.cmake" -B "$WORK/cpack"
DEB=$(ls "$WORK"/cpack/glarecam_*_*.deb 2>/dev/null | head -1)
expect "the package is glarecam_VERSION_ARCH.deb" test -n "$DEB"
[[ -n $DEB ]] || { finish; exit 1; }
ARCH=$(dpkg --print-architecture)
VERSION=$(dpkg-deb -f "$DEB" Version)
expect "named glarecam_${VERSION}_${ARCH}.deb" test "$(basename "$DEB")" = "glarecam_${VERSION}_${ARCH}.deb"
expect "its Architecture is this machine's" test "$(dpkg-deb -f "$DEB" Architecture)" = "$ARCH"
DEPENDS=$(dpkg-deb -f "$DEB" Depends)
# dpkg-shlibdeps: the shared libraries the binaries link, with versions.
for lib in libc6 libstdc++6 libopencv-core406 libcpp-httplib0.11 libsystemd0; do
  expect "Depends names $lib (dpkg-shlibdeps)" grep -q "$lib" <<<"$DEPENDS"
done
expect "Depends has versions" grep -q "(>= " <<<"$DEPENDS"
check "dpkg-deb -c" 0 dpkg-deb -c "$DEB"
for file in ./usr/bin/glarecam ./usr/bin/glarecamd ./usr/lib/systemd/system/glarecamd.service \
  ./usr/lib/systemd/system/glarecam-capture.service ./usr/lib/systemd/system/glarecam-capture.timer \
  ./usr/lib/sysusers.d/glarecam.conf ./usr/lib/udev/rules.d/99-glarecam.rules \
  ./etc/glarecam/glarecam.toml ./usr/share/man/man1/glarecam.1.gz \
  ./usr/share/man/man8/glarecamd.8.gz ./usr/share/doc/glarecam/operator.md \
  ./usr/share/doc/glarecam/copyright ./usr/share/doc/glarecam/changelog.gz \
  ./usr/share/glarecam/genicam/sfnc-linear-mono.conf; do
  expect "the package holds $file" grep -q " $file\$" "$WORK/out"
done
check "dpkg-deb -I" 0 dpkg-deb -I "$DEB"
expect "the config is a conffile" grep -q "^/etc/glarecam/glarecam.toml$" \
  <(dpkg-deb --ctrl-tarfile "$DEB" | tar -xOf - ./conffiles)
for script in postinst prerm postrm; do
  expect "it has a $script" grep -q " $script " "$WORK/out"
done
enables_or_starts() {  # a command of the maintainer scripts (not a comment) that enables or starts
  dpkg-deb --ctrl-tarfile "$DEB" | tar -xOf - ./postinst ./prerm ./postrm | grep -Ev '^\s*#' |
    grep -Eq '(systemctl|deb-systemd-helper|deb-systemd-invoke)[^|;]* (enable|start|unmask)\b|update-rc\.d'
}
enables_nothing() { ! enables_or_starts; }
expect "no maintainer script enables or starts anything" enables_nothing
# lintian: no error and no warning (docs/operator.md lists the info tags it leaves).
check "lintian finds no error or warning" 0 lintian --fail-on error,warning "$DEB"
[[ -s $WORK/out ]] && sed 's/^/  lintian: /' "$WORK/out"

# ---- installed into a fresh root --------------------------------------------------------------
installed_checks() {  # run inside the namespace: ROOT is the overlay root
  set -e
  local R=$1 deb=$2
  cp "$deb" "$R/tmp/glarecam.deb"
  in_root() { chroot "$R" "$@"; }
  in_root dpkg -i /tmp/glarecam.deb >"$R/tmp/dpkg-install.log" 2>&1 || { cat "$R/tmp/dpkg-install.log"; return 10; }
  in_root glarecam --version | grep -qx "$VERSION" || return 11
  in_root glarecamd --version | grep -qx "$VERSION" || return 12
  in_root id glarecam >/dev/null || return 13                     # systemd-sysusers ran
  in_root id -nG glarecam | grep -qw video || return 14           # with the devices' groups
  for unit in glarecamd.service glarecam-capture.service glarecam-capture.timer; do
    in_root systemd-analyze verify "/usr/lib/systemd/system/$unit" || return 15
  done
  grep -q '^ExecStart=/usr/bin/glarecamd ' "$R/usr/lib/systemd/system/glarecamd.service" || return 16
  ! ls "$R"/etc/systemd/system/*/glarecam* >/dev/null 2>&1 || return 17   # nothing enabled
  in_root man -w glarecamd >/dev/null 2>&1 || in_root test -e /usr/share/man/man8/glarecamd.8.gz || return 18
  # The operator's config and data.
  echo '# the operator was here' >>"$R/etc/glarecam/glarecam.toml"
  mkdir -p "$R/var/lib/glarecam/stacks/20260621T101503Z-a42.30"
  echo '{}' >"$R/var/lib/glarecam/stacks/20260621T101503Z-a42.30/stack.json"
  in_root dpkg -r glarecam >"$R/tmp/dpkg-remove.log" 2>&1 || { cat "$R/tmp/dpkg-remove.log"; return 20; }
  test ! -e "$R/usr/bin/glarecamd" || return 21
  grep -q 'the operator was here' "$R/etc/glarecam/glarecam.toml" || return 22
  test -e "$R/var/lib/glarecam/stacks/20260621T101503Z-a42.30/stack.json" || return 23
  in_root dpkg -P glarecam >"$R/tmp/dpkg-purge.log" 2>&1 || { cat "$R/tmp/dpkg-purge.log"; return 30; }
  test ! -e "$R/etc/glarecam/glarecam.toml" || return 31
  test -e "$R/var/lib/glarecam/stacks/20260621T101503Z-a42.30/stack.json" || return 32
  ! in_root dpkg-query -W -f='${db:Status-Status}' glarecam 2>/dev/null | grep -qx installed || return 33
  return 0
}
export -f installed_checks
export VERSION

namespace_root() {  # the overlay root, inside a private mount namespace
  unshare --mount --propagation private bash -c '
    set -e
    W=$1
    mkdir -p "$W/t" "$W/merged"
    mount -t tmpfs tmpfs "$W/t"
    mkdir -p "$W/t/upper" "$W/t/work"
    mount -t overlay overlay -o "lowerdir=/,upperdir=$W/t/upper,workdir=$W/t/work" "$W/merged"
    mount -t proc proc "$W/merged/proc"
    mount --rbind /dev "$W/merged/dev"
    installed_checks "$W/merged" "$2"' _ "$WORK/root" "$DEB"
}

if [[ $(id -u) -eq 0 ]] && unshare --mount --propagation private true 2>/dev/null; then
  namespace_root >"$WORK/install.log" 2>&1
  status=$?
  if [[ $status -eq 0 ]]; then
    passed=$((passed + 1))
  elif grep -qE "mount: .*(permission denied|not permitted|unknown filesystem)" "$WORK/install.log"; then
    echo "SKIP install into a fresh root: $(grep -m1 mount: "$WORK/install.log")"
  else
    failed=$((failed + 1))
    echo "FAIL install, remove and purge in a fresh root: step $status"
    sed 's/^/  /' "$WORK/install.log" | tail -20
  fi
else
  echo "SKIP install into a fresh root: needs root and a mount namespace (unshare --mount)"
  # What can be checked without one: the extracted tree runs.
  check "dpkg-deb -x" 0 dpkg-deb -x "$DEB" "$WORK/extracted"
  check "the extracted glarecam runs" 0 "$WORK/extracted/usr/bin/glarecam" --version
  sed "s|/usr/bin/|$WORK/extracted/usr/bin/|" "$WORK/extracted/usr/lib/systemd/system/glarecamd.service" \
    >"$WORK/glarecamd.service"
  check "the extracted unit verifies" 0 systemd-analyze verify "$WORK/glarecamd.service"
fi
finish
