#!/usr/bin/env bash
# The benchmarks' shared flags (bench_harness.cpp): a value they cannot take
# gives exactly one line on stderr that starts with the benchmark's name and
# names the problem, nothing on stdout, and exit status 2, before any frame
# is rendered.
# Usage: bench_arguments.sh FOLDER_OF_THE_BENCHMARKS
set -u
benches=$1
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
# shellcheck source=../../support/bad_arguments.sh
. "$(dirname "$0")/../../support/bad_arguments.sh"

# bad BENCH TEXT ARGS...: exit 2, empty stdout, one stderr line that starts
# with "BENCH: error:" and holds TEXT.
bad() {
  local bench=$1
  shift
  expect_bad "$benches/$bench" "$bench" "$@"
}

for bench in temporal_convergence sao_bench radiosity_bench; do
  bad $bench "--set must be NAME=VALUE, got 'blur-extent'" --scenes cornell --set blur-extent
  bad $bench "no setting named 'radiosity-clamps'" --scenes cornell --set radiosity-clamps=16
  bad $bench "--radiosity-clamp must be" --scenes cornell --set radiosity-clamp=6000
  bad $bench "--blur-extent must be" --scenes cornell --set blur-extent=-1
  bad $bench "--size" --scenes cornell --size 0x0
done
bad temporal_convergence "--shaders $scratch/none: not a folder" --scenes cornell --shaders "$scratch/none"

if [ "$failures" -ne 0 ]; then
  echo "$failures failures"
  exit 1
fi
echo "bench arguments: all checks passed"
