#!/bin/sh
# Deep radiosity's E against the ray-traced one-bounce irradiance split by
# where its light comes from (layer 0, layer 1, neither): as
# measure_irradiance.sh (one bounce, --rho-prop 0, 120 frames with alpha
# 0.95), once with each layer count, then deepgi_compare_irradiance_split
# against the whole truth and the visible truth (E0 + E1 for two layers, E0
# for one). Prints one Markdown row per layer count. Environment: RADIUS
# (metres) sets --radiosity-radius of both (unset: auto); GUARD the guard
# band as a fraction of the height (unset: the default 0.1); REFERENCE_FLAGS
# more flags for the reference (a ray budget, say).
# usage: [RADIUS=R] [GUARD=F] [REFERENCE_FLAGS=...] measure_irradiance_split.sh BUILD_DIR WORK_DIR [SCENE] [SIZE] [extra deepgi flags...]
set -eu
build=$1; work=$2; scene=${3:-cornell}; size=${4:-160x90}
shift 2; [ $# -gt 0 ] && shift; [ $# -gt 0 ] && shift
height=${size#*x}
band=${GUARD:-0.1}
# lround(band * height) pixels, as frame_layout() rounds the guard band.
guard=$(awk -v f="$band" -v h="$height" 'BEGIN { printf "%d", f * h + 0.5 }')
radius=${RADIUS:+--radiosity-radius $RADIUS}
mkdir -p "$work"
if [ ! -f "$work/$scene-ref/reference-irradiance-layer0.pfm" ]; then
  # shellcheck disable=SC2086
  "$build/apps/deepgi/deepgi" reference --scene "$scene" --size "$size" --no-ao $radius \
    --guard-band "$band" ${REFERENCE_FLAGS:-} --output "$work/$scene-ref" > "$work/$scene-ref.log"
fi
for layers in 1 2; do
  "$build/apps/deepgi/deepgi" --headless --scene "$scene" --size "$size" --frames 120 \
    --rho-prop 0 --radiosity-alpha 0.95 --radiosity-layers $layers $radius --guard-band "$band" "$@" \
    --output "$work/$scene-$layers.png" --dump "$work/$scene-$layers" > /dev/null
  "$build/reference/deepgi_compare_irradiance_split" "$work/$scene-$layers" "$work/$scene-ref" \
    $guard $layers "$scene" | tee "$work/$scene-$layers.txt" | grep '^|'
done
