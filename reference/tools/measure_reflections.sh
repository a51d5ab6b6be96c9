#!/bin/sh
# The reflection pass against the traced mirror reflections
# (docs/reflections.md, "Against the ray tracer"): one `deepgi reference`
# (no AO), then per layer count (1, 2) and step count (16, 32, 64) a
# headless render of FRAMES frames (the temporal filter's mean) with its dump,
# compared by deepgi_compare_reflections over the viewport's mirror pixels.
# `deepgi report` measures the same for every scene with mirrors, at the
# report's settings (docs/report.md, "Mirror reflections"); this tool keeps
# the renderer's defaults and any extra flags.
# usage: measure_reflections.sh BUILD_DIR WORK_DIR [SCENE] [SIZE] [FRAMES] [extra deepgi flags...]
set -eu
build=$1; work=$2; scene=${3:-gallery}; size=${4:-160x90}; frames=${5:-32}
shift 2; for _ in 1 2 3; do [ $# -gt 0 ] && shift; done
height=${size#*x}
guard=$(( (height + 5) / 10 ))  # lround(0.1 * height), the default guard band
mkdir -p "$work"
if [ ! -f "$work/$scene-ref/reference-reflection-radiance.pfm" ]; then
  "$build/apps/deepgi/deepgi" reference --scene "$scene" --size "$size" --no-ao \
    --output "$work/$scene-ref"
fi
for layers in 1 2; do
  for steps in 16 32 64; do
    dump="$work/$scene-l$layers-s$steps"
    "$build/apps/deepgi/deepgi" --headless --scene "$scene" --size "$size" --frames "$frames" \
      --reflection-layers $layers --reflection-steps $steps "$@" \
      --output "$dump.png" --dump "$dump" > /dev/null
    printf 'layers=%s steps=%s ' $layers $steps
    "$build/reference/deepgi_compare_reflections" "$dump" "$work/$scene-ref" $guard
  done
done
