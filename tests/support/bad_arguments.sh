# Sourced by the command-line checks of the tools and the benchmarks
# (tests/reference/tool_arguments.sh, tests/bench/runtime/bench_arguments.sh):
# a command line a program cannot take gives exactly one line on stderr that
# starts with "NAME: error:" and names the problem, nothing on stdout, and
# exit status 2. The sourcing script sets `scratch` (a folder) and reads
# `failures` at its end.
failures=0

fail() {
  echo "FAIL: $*"
  failures=$((failures + 1))
}

# expect_bad PROGRAM NAME TEXT ARGS...: PROGRAM (a path) run with ARGS exits
# 2, writes nothing to stdout and one stderr line that starts with
# "NAME: error: " and holds TEXT.
expect_bad() {
  local program=$1 name=$2 text=$3
  shift 3
  "$program" "$@" > "$scratch/out" 2> "$scratch/err"
  local status=$?
  local lines
  lines=$(wc -l < "$scratch/err")
  local what="$name $*"
  [ "$status" -eq 2 ] || fail "$what: exit $status, not 2"
  [ -s "$scratch/out" ] && fail "$what: wrote to stdout: $(head -c 200 "$scratch/out")"
  [ "$lines" -eq 1 ] || fail "$what: $lines lines on stderr: $(cat "$scratch/err")"
  grep -q "^$name: error: " "$scratch/err" || fail "$what: stderr does not start with the program's name: $(cat "$scratch/err")"
  grep -qF -- "$text" "$scratch/err" || fail "$what: stderr does not name '$text': $(cat "$scratch/err")"
}
