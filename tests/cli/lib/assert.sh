# Shared assertions and set-up for tests/cli/*.sh (sourced; needs QUADAPT_SOURCE_DIR). Every check fails the script when false —
# never `[ a ] && [ b ]`, which `set -e` does not stop on.
fail() { echo "FAIL: $*" >&2; exit 1; }

# expect_exit CODE NAME_IN_MESSAGE CMD...: CMD exits with CODE and, for CODE 2, prints exactly one
# line on stderr that contains NAME_IN_MESSAGE. Leaves stderr in $ERR.
expect_exit() {
  local want=$1 name=$2; shift 2
  local rc=0
  ERR=$("$@" 2>&1 >/dev/null) || rc=$?
  if [ "$rc" -ne "$want" ]; then fail "exit $rc (want $want): $* :: $ERR"; fi
  if [ "$want" -eq 2 ]; then
    if [ "$(printf '%s\n' "$ERR" | grep -c .)" -ne 1 ]; then fail "not one line on stderr: $* :: $ERR"; fi
    case "$ERR" in *"$name"*) ;; *) fail "message does not name '$name': $* :: $ERR" ;; esac
  fi
}

# same_bytes A B: the two files are identical.
same_bytes() { cmp -s "$1" "$2" || fail "$1 and $2 differ"; }

# in_temp_dir: a fresh directory $T, removed at exit, becomes the current directory.
in_temp_dir() {
  T=$(mktemp -d)
  trap 'rm -rf "$T"' EXIT
  cd "$T"
}
E="$QUADAPT_SOURCE_DIR/examples"
