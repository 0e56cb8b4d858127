# Shared by the robustness tests (sourced: `. "$(dirname "$0")/common.sh"`), which are all run
# as `sh TEST.sh SYSID SOURCE_DIR`: a private work folder removed on exit, and two checks.
sysid=$1
src=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cd "$work" || exit 1
fail() { echo "FAIL: $*" >&2; [ -f err.txt ] && cat err.txt >&2; exit 1; }
# expect CODE MESSAGE-PART ARGS...: sysid ARGS exits with CODE, its stderr holds MESSAGE-PART
# (unless empty) and never an internal error.
expect() {
  code=$1; part=$2; shift 2
  "$sysid" "$@" >out.txt 2>err.txt; rc=$?
  [ "$rc" -eq "$code" ] || fail "$* exited $rc, expected $code"
  [ -z "$part" ] || grep -q -- "$part" err.txt || fail "$*: message lacks '$part'"
  grep -q "internal error" err.txt && fail "$*: internal error"
  return 0
}
