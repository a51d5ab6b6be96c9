#!/bin/sh
# Deep radiosity with bounce propagation (--rho-prop 1, boost 1, a still
# camera averaged over FRAMES frames with alpha 0.95) against the ray-traced
# K-bounce irradiance (deepgi reference --bounces K) for K = 1, 2, 3 on
# cornell and atrium, and one bounce (--rho-prop 0) against K = 1 for
# comparison; deepgi_compare_irradiance over the viewport pixels where
# traced and rasterised layer-0 depth agree (docs/radiosity.md, "Bounces
# against the ray tracer"). References already in WORK_DIR are reused.
# usage: measure_bounces.sh BUILD_DIR WORK_DIR [SIZE] [FRAMES] [RAYS]
# RAYS caps the reference's irradiance rays per pixel (default 4096).
set -eu
build=$1; work=$2; size=${3:-160x90}; frames=${4:-120}; rays=${5:-4096}
height=${size#*x}
guard=$(( (height + 5) / 10 ))  # lround(0.1 * height), the default guard band
mkdir -p "$work"
echo "| scene | renderer | K | reference mean E | filtered MAE | filtered bias | blurred MAE | blurred bias |"
echo "|:--|:--|--:|--:|--:|--:|--:|--:|"
for scene in cornell atrium; do
  for rho in 1 0; do
    dump="$work/$scene-rho$rho"
    "$build/apps/deepgi/deepgi" --headless --scene "$scene" --size "$size" --frames "$frames" \
      --rho-prop "$rho" --radiosity-alpha 0.95 --output "$dump.png" --dump "$dump" \
      > "$dump.log"
    bounces="1 2 3"; [ "$rho" = 0 ] && bounces=1
    for k in $bounces; do
      ref="$work/$scene-ref-$k"
      if [ ! -f "$ref/reference-irradiance.pfm" ]; then
        "$build/apps/deepgi/deepgi" reference --scene "$scene" --size "$size" --no-ao \
          --bounces "$k" --irradiance-rays "$rays" --irradiance-ceiling-rays "$rays" \
          --output "$ref" > "$ref.log"
      fi
      out="$work/$scene-rho$rho-compare-$k.txt"
      "$build/reference/deepgi_compare_irradiance" "$dump" "$ref" "$guard" > "$out"
      # "NAME: MAE m, bias b, relative error r, relative bias rb": the relative pair.
      pick() {
        grep "^$1: " "$out" | sed 's/.*relative error \([^,]*\), relative bias \(.*\)$/\1 | \2/'
      }
      mean=$(sed -n 's/^reference: .*mean E \([^,]*\),.*/\1/p' "$out")
      echo "| $scene | --rho-prop $rho | $k | $mean | $(pick radiosity-irradiance-layer0) | $(pick radiosity-blurred) |"
    done
  done
done
