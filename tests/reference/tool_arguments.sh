#!/usr/bin/env bash
# The measuring tools beside the reference (reference/tools): a command line
# a tool cannot parse gives exactly one line on stderr that starts with the
# tool's name and names the problem, nothing on stdout, and exit status 2;
# --help exits 0. The command lines of reference/tools/measure_*.sh and of
# the docs still parse: with empty folders such a run gets past its
# arguments and stops at the first image it reads.
# Usage: tool_arguments.sh FOLDER_OF_THE_TOOLS
set -u
tools=$1
scratch=$(mktemp -d)
trap 'rm -rf "$scratch"' EXIT
dump=$scratch/dump
ref=$scratch/ref
mkdir "$dump" "$ref"
# shellcheck source=../support/bad_arguments.sh
. "$(dirname "$0")/../support/bad_arguments.sh"

# bad TOOL TEXT ARGS...: exit 2, empty stdout, one stderr line that starts
# with "deepgi_TOOL: error:" and holds TEXT.
bad() {
  local tool=$1
  shift
  expect_bad "$tools/deepgi_$tool" "deepgi_$tool" "$@"
}

# parses TOOL ARGS...: the arguments parse; the run then stops at the first
# image it reads from the empty folders (exit 2, the file named, not an
# argument).
parses() {
  local tool=$1
  shift
  "$tools/deepgi_$tool" "$@" > "$scratch/out" 2> "$scratch/err"
  local status=$?
  local what="deepgi_$tool $*"
  [ "$status" -eq 2 ] || fail "$what: exit $status, not 2"
  grep -q "error: " "$scratch/err" && fail "$what: the arguments did not parse: $(cat "$scratch/err")"
  grep -q "\.pfm" "$scratch/err" || fail "$what: did not stop at an image: $(cat "$scratch/err")"
}

# help TOOL OPTION...: --help exits 0 and lists every one of OPTION.
help() {
  local tool=$1
  shift
  "$tools/deepgi_$tool" --help > "$scratch/out" 2> "$scratch/err"
  local status=$?
  [ "$status" -eq 0 ] || fail "deepgi_$tool --help: exit $status, not 0"
  for option in "$@"; do
    grep -qF -- "$option" "$scratch/out" || fail "deepgi_$tool --help does not list $option"
  done
}

# The three that compare a dump with a reference at a guard band.
for tool in compare_reference compare_irradiance compare_reflections; do
  bad $tool "DUMP_DIR is required"
  bad $tool "GUARD_PIXELS is required" "$dump" "$ref"
  bad $tool "GUARD_PIXELS" "$dump" "$ref" eighteen
  bad $tool "GUARD_PIXELS" "$dump" "$ref" -1
  bad $tool "GUARD_PIXELS" "$dump" "$ref" 0x12
  bad $tool "DUMP_DIR" "$scratch/no-such-folder" "$ref" 18
  bad $tool "REFERENCE_DIR" "$dump" "$scratch/no-such-folder" 18
  bad $tool "--no-such-flag" "$dump" "$ref" 18 --no-such-flag
  bad $tool "extra" "$dump" "$ref" 18 extra
  parses $tool "$dump" "$ref" 18
  help $tool DUMP_DIR REFERENCE_DIR GUARD_PIXELS
done

tool=compare_irradiance_split
bad $tool "LAYERS is required" "$dump" "$ref" 18
bad $tool "LAYERS" "$dump" "$ref" 18 3
bad $tool "--no-such-flag" "$dump" "$ref" 18 2 --no-such-flag
bad $tool "extra" "$dump" "$ref" 18 2 cornell extra
parses $tool "$dump" "$ref" 18 1
parses $tool "$dump" "$ref" 18 2 cornell # measure_irradiance_split.sh
help $tool DUMP_DIR REFERENCE_DIR GUARD_PIXELS LAYERS LABEL

tool=irradiance_region
bad $tool "SCENE is required" "$dump" "$ref"
bad $tool "--facing" "$dump" "$ref" cornell --facing 0,0,0
bad $tool "--facing" "$dump" "$ref" cornell --facing 0,1
bad $tool "--box" "$dump" "$ref" cornell --box 1,2,3
bad $tool "--toward" "$dump" "$ref" cornell --toward 0,0,0
bad $tool "--sky-rays" "$dump" "$ref" cornell --sky-rays 0
bad $tool "--layers" "$dump" "$ref" cornell --layers 3
bad $tool "--min-cos" "$dump" "$ref" cornell --min-cos
bad $tool "--guard-band" "$dump" "$ref" cornell --guard-band 7
bad $tool "--no-such-flag" "$dump" "$ref" cornell --no-such-flag 1
# docs/radiosity-studies.md's command lines, negative numbers included.
parses $tool "$dump" "$ref" cornell --min-cos -2
parses $tool "$dump" "$ref" atrium --facing 0,1,0 --box -4.55,-3.45,-1,0.02,-7.25,-4.95 \
  --toward 0.05,0.12,0.80 --layers 1 --sky-rays 4 --guard-band 0.1
help $tool DUMP_DIR REFERENCE_DIR SCENE --facing --min-cos --box --toward --guard-band \
  --sky-rays --layers

tool=irradiance_unoccluded_study
bad $tool "SCENE is required" "$dump"
bad $tool "--radius" "$dump" warehouse --radius 0
bad $tool "--radius" "$dump" warehouse --radius far
bad $tool "--layers" "$dump" warehouse --layers 0
bad $tool "--rays" "$dump" warehouse --rays 0
bad $tool "--stride" "$dump" warehouse --stride -2
bad $tool "--threads" "$dump" warehouse --threads 1.5
bad $tool "--no-such-flag" "$dump" warehouse --no-such-flag
bad $tool "--view-bands" "$dump" warehouse --view-bands 0.1,0.01
bad $tool "--view-bands" "$dump" warehouse --view-bands 0.01,,0.3
bad $tool "--view-bands" "$dump" warehouse --view-bands inf
bad $tool "--view-bands" "$dump" warehouse --view-bands
bad $tool "requires --reference" "$dump" warehouse --write-truth "$scratch/truth" --stride 1
bad $tool "requires --write-truth" "$dump" warehouse --reference "$ref" --stride 1
bad $tool "--stride 1" "$dump" warehouse --write-truth "$scratch/truth" --reference "$ref"
bad $tool "--reference" "$dump" warehouse --write-truth "$scratch/truth" --stride 1 \
  --reference "$scratch/no-such-folder"
bad $tool "must not be the --reference" "$dump" warehouse --write-truth "$ref" --reference "$ref" \
  --stride 1
# docs/radiosity-studies.md's command lines.
parses $tool "$dump" warehouse --layers 2 --rays 256 --stride 2
parses $tool "$dump" warehouse --radius 1.5 --rays 256 --stride 2
parses $tool "$dump" warehouse --radius auto --threads 2 --guard-band 0.1
# docs/radiosity-studies.md's, the shortfall study.
parses $tool "$dump" warehouse --layers 2 --rays 1024 --stride 1 --threads 2 --radius 1 \
  --view-bands 0.01,0.1,0.3 --write-truth "$scratch/truth" --reference "$ref"
help $tool DUMP_DIR SCENE --radius --guard-band --layers --rays --stride --threads --view-bands \
  --write-truth --reference

tool=irradiance_attribution
bad $tool "SCENE is required" "$dump" "$ref"
bad $tool "--radius" "$dump" "$ref" cornell --radius 0
bad $tool "--radius" "$dump" "$ref" cornell --radius far
bad $tool "--layers" "$dump" "$ref" cornell --layers 3
bad $tool "--repeat" "$dump" "$ref" cornell --repeat "$scratch/no-such-folder"
bad $tool "--guard-band" "$dump" "$ref" cornell --guard-band 7
bad $tool "--no-such-flag" "$dump" "$ref" cornell --no-such-flag
bad $tool "--view-band" "$dump" "$ref" cornell --view-band 0.1
bad $tool "--view-band" "$dump" "$ref" cornell --view-band 0.1,0.01
bad $tool "--view-band" "$dump" "$ref" cornell --view-band 0.1,0.1,0.3
bad $tool "--view-band" "$dump" "$ref" cornell --view-band 0,nan
# docs/radiosity-studies.md's command lines.
parses $tool "$dump" "$ref" cornell --repeat "$dump" --maps "$scratch/maps"
parses $tool "$dump" "$ref" ref-crease --radius 1 --maps "$scratch/maps"
# docs/radiosity-studies.md's shortfall study, a negative bound included.
parses $tool "$dump" "$ref" warehouse --radius 1 --view-band -2,0.01
parses $tool "$dump" "$ref" warehouse --view-band 0.3,2
help $tool DUMP_DIR REFERENCE_DIR SCENE --radius --layers --guard-band --repeat --maps --view-band

tool=ao_dense_study
bad $tool "SCENE is required" "$dump" "$ref"
bad $tool "--stride" "$dump" "$ref" cornell --stride 0
bad $tool "--subtract" "$dump" "$ref" cornell --subtract 2
bad $tool "--layers" "$dump" "$ref" cornell --layers 3
bad $tool "--bias" "$dump" "$ref" cornell --bias small
bad $tool "--radius" "$dump" "$ref" cornell --radius
bad $tool "--no-such-flag" "$dump" "$ref" cornell --no-such-flag 1
parses $tool "$dump" "$ref" cornell --bias 0.02 --footprint 0.5 --subtract 0 --clamp 0.1 \
  --cos-phi 1 --reach 1 --sub 2 --layers 1 --stride 3 --radius 0.5
help $tool DUMP_DIR REFERENCE_DIR SCENE --bias --footprint --subtract --clamp --cos-phi \
  --reach --sub --layers --stride --radius

if [ "$failures" -ne 0 ]; then
  echo "$failures failures"
  exit 1
fi
echo "every tool: bad arguments give one line and exit 2; the documented command lines parse"
