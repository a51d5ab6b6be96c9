#!/usr/bin/env bash
# Measures the renderer's milliseconds on a GPU in one prepared run and
# writes them to docs/figures/gpu/ as a whole set: one CSV per benchmark,
# each starting with the renderer string, and table.md with every table.
# Everything is timed with GL timer queries (--timing gpu) through the
# common benchmark harness (tests/bench/runtime/bench_harness.hpp).
#
#   scripts/gpu-figures.sh [--quick] [--allow-software] [--size WxH]
#                          [--out DIR] [--no-install] [--no-build] [--build-dir DIR]
#
# --quick runs a subset (cornell only, fewer frames and tap counts).
# --allow-software accepts a CPU rasteriser such as llvmpipe, whose timer
# queries mean nothing: ctest runs it that way at a tiny size so the script
# cannot rot. Covered: every pass of the default frame with each G-buffer
# generator (deepgi_bench), deep SAO per estimator, one layer against two
# (sao_bench), deep radiosity, one layer against two (radiosity_bench).
set -euo pipefail
cd "$(dirname "$0")/.."

quick=0 allow_software=0 install=1 build=1 build_dir=build
size=1920x1080
out=docs/figures/gpu
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=1 ;;
    --allow-software) allow_software=1 ;;
    --no-install) install=0 ;;
    --no-build) build=0 ;;
    --build-dir) [ $# -ge 2 ] || { echo "gpu-figures.sh: --build-dir needs a directory" >&2; exit 2; }
                 build_dir="$2"; shift ;;
    --size) [ $# -ge 2 ] || { echo "gpu-figures.sh: --size needs WIDTHxHEIGHT" >&2; exit 2; }
            size="$2"; shift ;;
    --out) [ $# -ge 2 ] || { echo "gpu-figures.sh: --out needs a directory" >&2; exit 2; }
           out="$2"; shift ;;
    *) echo "gpu-figures.sh: unknown option '$1' (see the comment at the top)" >&2; exit 2 ;;
  esac
  shift
done

# The packages of install-deps.sh include the GL vendor-neutral dispatch
# (libegl1, libglvnd0) through which the NVIDIA driver's EGL is found.
if [ "$install" = 1 ]; then scripts/install-deps.sh; fi
if [ "$build" = 1 ]; then scripts/build.sh > /dev/null; fi
bench="$build_dir/tests/bench/runtime"

scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
renderer="$("$build_dir/apps/deepgi/deepgi" --headless --scene cornell --size 64x36 \
  --output "$scratch/probe.png" --print-timings --timing gpu |
  sed -n 's/^renderer: \(.*\) ([^()]*)$/\1/p')"
echo "renderer: $renderer"
case "$renderer" in
  *llvmpipe*|*softpipe*|*"Software Rasterizer"*)
    if [ "$allow_software" = 0 ]; then
      echo "gpu-figures.sh: '$renderer' is a CPU rasteriser; its timer queries are not GPU figures (--allow-software to run anyway)" >&2
      exit 2
    fi ;;
esac

if [ "$quick" = 1 ]; then
  scenes=cornell frames=5 taps=11
else
  scenes=cornell,atrium,warehouse frames=15 taps=8,11,16,32
fi
common=(--size "$size" --scenes "$scenes" --frames "$frames" --warmup 3 --timing gpu)

mkdir -p "$scratch/set"
"$bench/deepgi_bench" "${common[@]}" > "$scratch/set/frame.md"
for method in solid-angle march published; do
  "$bench/sao_bench" "${common[@]}" --ao-method "$method" --taps "$taps" \
    > "$scratch/set/sao-$method.md"
done
"$bench/radiosity_bench" "${common[@]}" > "$scratch/set/radiosity.md"

# Markdown tables to CSV: each table row becomes a line, separator rows go,
# and every file starts with the renderer that measured it.
for table in "$scratch"/set/*.md; do
  csv="${table%.md}.csv"
  {
    echo "# renderer: $renderer"
    grep '^|' "$table" | grep -v '^|[-:| ]*$' |
      sed -e 's/^| *//' -e 's/ *|$//' -e 's/ *| */,/g' | awk '!seen[$0]++'
  } > "$csv"
done
{
  echo "# GPU figures"
  echo
  echo "Renderer: $renderer. Written by \`scripts/gpu-figures.sh$([ "$quick" = 1 ] && echo ' --quick')\`."
  for table in "$scratch"/set/*.md; do
    echo
    echo "## $(basename "$table" .md)"
    echo
    cat "$table"
  done
} > "$scratch/table.md"
rm "$scratch"/set/*.md
mv "$scratch/table.md" "$scratch/set/table.md"

# The whole set replaces the old one at once.
mkdir -p "$(dirname "$out")"
rm -rf "$out.new"
mv "$scratch/set" "$out.new"
rm -rf "$out.old"
if [ -e "$out" ]; then mv "$out" "$out.old"; fi
mv "$out.new" "$out"
rm -rf "$out.old"
echo "wrote $out: $(cd "$out" && ls | tr '\n' ' ')"
