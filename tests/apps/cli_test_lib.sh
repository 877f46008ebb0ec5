# Helpers of the CLI test scripts (sourced): check runs a command and compares its exit status,
# expect checks a condition; finish prints the tally and fails the script on any failure.
# The sourcing script sets WORK (a temporary directory).
passed=0
failed=0

check() {  # check NAME EXPECTED_STATUS COMMAND... ; leaves stdout/stderr in $WORK/out, $WORK/err
  local name=$1 expected=$2
  shift 2
  "$@" >"$WORK/out" 2>"$WORK/err"
  local status=$?
  if [[ $status -eq $expected ]]; then
    passed=$((passed + 1))
  else
    failed=$((failed + 1))
    echo "FAIL $name: exit $status, expected $expected"
    sed 's/^/  stderr: /' "$WORK/err" | head -5
  fi
}

expect() {  # expect NAME CONDITION-COMMAND...
  local name=$1
  shift
  if "$@"; then passed=$((passed + 1)); else failed=$((failed + 1)); echo "FAIL $name"; fi
}

one_line_naming() {  # stderr is exactly one line and contains $1
  [[ $(wc -l <"$WORK/err") -eq 1 ]] && grep -qF -- "$1" "$WORK/err"
}

json_number() {  # json_number KEY FILE: the first number after "KEY": in pretty-printed JSON
  grep -m1 -o "\"$1\": [-0-9.e+]*" "$2" | sed 's/.*: //'
}

near() {  # near VALUE TARGET TOLERANCE
  awk -v v="$1" -v t="$2" -v tol="$3" 'BEGIN { d = v - t; if (d < 0) d = -d; exit !(v != "" && d <= tol) }'
}

finish() {
  echo "$passed passed, $failed failed"
  [[ $failed -eq 0 ]]
}
