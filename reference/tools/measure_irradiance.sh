#!/bin/sh
# Deep radiosity's layer-0 E against the ray-traced one-bounce irradiance:
# one bounce (rho_prop 0), a long temporal average (alpha 0.95, 120 frames of
# a static camera), then deepgi_compare_irradiance over the viewport.
# usage: measure_irradiance.sh BUILD_DIR WORK_DIR [SCENE] [SIZE] [extra deepgi flags...]
set -eu
build=$1; work=$2; scene=${3:-cornell}; size=${4:-320x180}
shift 2; [ $# -gt 0 ] && shift; [ $# -gt 0 ] && shift
height=${size#*x}
guard=$(( (height + 5) / 10 ))  # lround(0.1 * height), the default guard band
mkdir -p "$work"
if [ ! -f "$work/$scene-ref/reference-irradiance.pfm" ]; then
  "$build/apps/deepgi/deepgi" reference --scene "$scene" --size "$size" --no-ao \
    --output "$work/$scene-ref"
fi
"$build/apps/deepgi/deepgi" --headless --scene "$scene" --size "$size" --frames 120 \
  --rho-prop 0 --radiosity-alpha 0.95 "$@" --output "$work/$scene.png" --dump "$work/$scene"
"$build/reference/deepgi_compare_irradiance" "$work/$scene" "$work/$scene-ref" $guard
