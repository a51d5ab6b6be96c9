#!/bin/sh
# Deep radiosity's E against the ray-traced one-bounce irradiance split by
# where its light comes from (layer 0, layer 1, neither): as
# measure_irradiance.sh (one bounce, --rho-prop 0, 120 frames with alpha
# 0.95), once with each layer count, then deepgi_compare_irradiance_split
# against the whole truth and the visible truth (E0 + E1 for two layers, E0
# for one). Prints one Markdown row per layer count. RADIUS (environment,
# metres) sets --radiosity-radius of both; unset, both resolve auto.
# usage: [RADIUS=R] measure_irradiance_split.sh BUILD_DIR WORK_DIR [SCENE] [SIZE] [extra deepgi flags...]
set -eu
build=$1; work=$2; scene=${3:-cornell}; size=${4:-160x90}
shift 2; [ $# -gt 0 ] && shift; [ $# -gt 0 ] && shift
height=${size#*x}
guard=$(( (height + 5) / 10 ))  # lround(0.1 * height), the default guard band
radius=${RADIUS:+--radiosity-radius $RADIUS}
mkdir -p "$work"
if [ ! -f "$work/$scene-ref/reference-irradiance-layer0.pfm" ]; then
  "$build/apps/deepgi/deepgi" reference --scene "$scene" --size "$size" --no-ao $radius \
    --output "$work/$scene-ref" > "$work/$scene-ref.log"
fi
for layers in 1 2; do
  "$build/apps/deepgi/deepgi" --headless --scene "$scene" --size "$size" --frames 120 \
    --rho-prop 0 --radiosity-alpha 0.95 --radiosity-layers $layers $radius "$@" \
    --output "$work/$scene-$layers.png" --dump "$work/$scene-$layers" > /dev/null
  "$build/reference/deepgi_compare_irradiance_split" "$work/$scene-$layers" "$work/$scene-ref" \
    $guard $layers "$scene" | tee "$work/$scene-$layers.txt" | grep '^|'
done
