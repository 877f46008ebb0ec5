#!/usr/bin/env bash
# scripts/make-man: glarecam(1) and glarecamd(8) from the executables' --help, mentioning every
# command and option, rendering without a warning; --check catches a page that lacks one; bad
# usage exits 2. Usage: make_man_test.sh SOURCE_DIR BIN_DIR
set -uo pipefail
SOURCE=$1
BIN=$2
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
source "$SOURCE/tests/apps/cli_test_lib.sh"
MAKE_MAN=$SOURCE/scripts/make-man

check "make-man writes the pages" 0 "$MAKE_MAN" "$BIN/glarecam" "$BIN/glarecamd" "$WORK/man"
for page in glarecam.1 glarecamd.8; do
  expect "$page written" test -s "$WORK/man/$page"
  expect "$page.gz is gzip -n (no name, no time)" bash -c \
    "gzip -dc '$WORK/man/$page.gz' | cmp -s - '$WORK/man/$page' && [[ \$(od -An -tu4 -j4 -N4 '$WORK/man/$page.gz') -eq 0 ]]"
  check "man renders $page without a warning" 0 env LC_ALL=C.UTF-8 MANWIDTH=80 \
    man --warnings -E UTF-8 -l -Tutf8 -Z "$WORK/man/$page.gz"
  expect "no warning from $page" test ! -s "$WORK/err"
done
check "--check: every command and option is on the pages" 0 \
  "$MAKE_MAN" --check "$BIN/glarecam" "$BIN/glarecamd" "$WORK/man"
# Every command glarecam --help lists has its section.
for command in $("$BIN/glarecam" --help | sed -n '/^Subcommands:/,$p' | awk 'NR > 1 && NF { print $1 }'); do
  escaped=${command//-/\\-}  # roff's hyphen
  expect "glarecam.1 has a section for $command" grep -qF ".SS glarecam $escaped" "$WORK/man/glarecam.1"
done
expect "glarecamd.8 has --status" grep -q '^\.B \\-\\-status' "$WORK/man/glarecamd.8"
expect "glarecamd.8 names its signals" grep -q SIGHUP "$WORK/man/glarecamd.8"
# A page that lacks an option fails --check, naming it.
sed -i '/\\-\\-time\\-lapse/d' "$WORK/man/glarecamd.8"
check "--check fails on a missing option" 1 "$MAKE_MAN" --check "$BIN/glarecam" "$BIN/glarecamd" "$WORK/man"
expect "and names it" grep -q -- "--time-lapse" "$WORK/err"
check "bad usage exits 2" 2 "$MAKE_MAN" "$BIN/glarecam"
check "not an executable exits 2" 2 "$MAKE_MAN" "$WORK/none" "$BIN/glarecamd" "$WORK/x"
finish
