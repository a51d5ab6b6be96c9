#!/usr/bin/env bash
# Configures and builds the project into build/ (Release). Extra arguments go to
# CMake's configure step, e.g. -DAO_TAPS=16.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release "$@"
cmake --build build
