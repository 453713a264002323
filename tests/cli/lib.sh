# Shared by the command-line test scripts: a scratch folder, pass/fail counting, and
# expect_error, which runs a command and checks exit code, message and that no file was left.
# Source it after setting $skyspec; call `finish NAME` last.
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
pass=0
fail=0

ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*"; }

# run_expecting_error NAME EXIT_CODE 'text that must appear in stderr' OUTPUT_DIR COMMAND...
run_expecting_error() {
  local name=$1 code=$2 text=$3 out=$4
  shift 4
  "$@" >"$work/stdout" 2>"$work/stderr"
  local rc=$?
  if [ "$rc" != "$code" ]; then bad "$name: exit $rc, expected $code"; cat "$work/stderr"; return; fi
  if ! grep -qF -- "$text" "$work/stderr"; then bad "$name: stderr lacks '$text':"; cat "$work/stderr"; return; fi
  if [ -d "$out" ] && [ -n "$(ls -A "$out")" ]; then bad "$name: left files: $(ls "$out")"; return; fi
  ok
}

finish() {
  echo "$1: $pass passed, $fail failed"
  [ "$fail" = 0 ]
}
