#!/bin/sh
# Deep SAO against the ray-traced reference on the reference and built-in
# scenes, one and two layers: MAE and bias before and after the blur, and
# after the blur against the visible truth (deepgi_compare_reference).
# Extra flags go to deepgi, e.g. --frames 9 for a static camera's whole
# rotation cycle accumulated.
# The scene lengths are the library's metres by default (AO radius 0.5 m,
# minimum separation 0.5 m, thickness 0.2 m), as ctest deepgi_ao_accuracy and
# the tables of docs/ao-accuracy.md and docs/deep-sao.md use them; LENGTHS=auto
# takes the command line's default instead, a fraction of each scene's size.
# (Other lengths: LENGTHS=auto and the lengths among the extra flags.)
# usage: [LENGTHS=auto] measure_ao.sh BUILD_DIR WORK_DIR [SIZE] [extra deepgi flags...]
set -eu
build=$1; work=$2; size=${3:-320x180}
shift 2; [ $# -gt 0 ] && shift
if [ "${LENGTHS:-metres}" = auto ]; then
  lengths=""
else
  lengths="--ao-radius 0.5 --min-separation 0.5"
  thickness="--ao-thickness 0.2"
fi
height=${size#*x}
guard=$(( (height + 5) / 10 ))  # lround(0.1 * height), the default guard band
mkdir -p "$work"
for scene in ref-crease ref-slab ref-board ref-bench cornell atrium warehouse; do
  if [ ! -f "$work/$scene-ref/reference-ao-visibility.pfm" ]; then
    "$build/apps/deepgi/deepgi" reference --scene $scene --size $size $lengths --output "$work/$scene-ref" >/dev/null
  fi
  for layers in 1 2; do
    "$build/apps/deepgi/deepgi" --headless --scene $scene --size $size --ao-layers $layers $lengths ${thickness:-} "$@" \
      --output "$work/$scene-$layers.png" --dump "$work/$scene-$layers"
    echo "== $scene, $layers layer(s)"
    "$build/reference/deepgi_compare_reference" "$work/$scene-$layers" "$work/$scene-ref" $guard | grep '^ao-'
  done
done
