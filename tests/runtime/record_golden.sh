#!/usr/bin/env bash
# Re-records the reference images of deepgi_golden_images (tests/runtime/golden/)
# from the current build, with the GL renderer that made them. Run it after a
# change meant to alter pixels, look at the new images, and commit them on
# their own. Usage: tests/runtime/record_golden.sh [build folder, default build]
set -euo pipefail
cd "$(dirname "$0")/../.."
build=${1:-build}
cmake --build "$build" --target deepgi_golden_images deepgi
"$build/tests/runtime/deepgi_golden_images" record "$build/tests/runtime/golden_images_record"
