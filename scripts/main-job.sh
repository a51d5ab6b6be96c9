#!/usr/bin/env bash
# The main job, after scripts/build.sh: regenerate the tau table and the shader
# headers, and render the demo headless to an image. Results land in out/.
set -euo pipefail
cd "$(dirname "$0")/.."
mkdir -p out
spiralgen=build/apps/spiralgen/spiralgen
"$spiralgen" table --max-n 99 --format md --out out/tau_table.md
"$spiralgen" table --max-n 99 --format json --out out/tau_table.json
cat out/tau_table.md
# The shader headers are build outputs: remove them and let the build make them
# again, so this job always shows them being generated from the optimizer.
rm -f build/generated/*.glsl build/generated/*.hpp
cmake --build build --target spiral_generated_headers
echo "generated headers in build/generated:" && ls build/generated
# 64 still frames: after 16 the gather's noise still shows as grain on the
# upper walls at this size (docs/radiosity-studies.md, "How fast a still
# camera converges"); 64 take about 45 s on llvmpipe with two cores.
build/apps/deepgi/deepgi --headless --scene cornell --size 1280x720 --frames 64 --output out/demo.png
echo "rendered out/demo.png"
