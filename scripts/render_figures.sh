#!/usr/bin/env bash
# Renders docs/gallery.md's "what each part adds" row for the cornell scene into
# docs/figures/: direct light only; + deep SAO on the environment term;
# + one bounce of deep radiosity (rho_prop 0); + multiple bounces
# (rho_prop 1). Every image gets the same frames, so the temporal filter has
# settled the same way in each. Then the first frame's blurred AO of each
# estimator. The exposure stays at 1 (the command line's default is auto,
# which would expose each term on its own and hide what it adds). Run after
# scripts/build.sh:
#   scripts/render_figures.sh [SIZE] [FRAMES]
set -euo pipefail
cd "$(dirname "$0")/.."
deepgi=${DEEPGI:-build/apps/deepgi/deepgi}
size=${1:-480x270}
frames=${2:-24}
out=docs/figures
mkdir -p "$out"
render() {
    local name=$1
    shift
    # deepgi writes the PNG atomically: a failed run leaves the old figure.
    "$deepgi" --headless --scene cornell --size "$size" --frames "$frames" \
        --exposure 1 --output "$out/cornell-$name.png" "$@"
    echo "wrote $out/cornell-$name.png"
}
render direct --no-ao --no-radiosity --no-environment
render ao --no-radiosity
render one-bounce --rho-prop 0
render bounces --rho-prop 1

# Blurred AO of the first frame, one image per estimator: the solid-angle
# default and the march (docs/deep-sao.md, "The march").
for method in solid-angle march; do
    "$deepgi" --headless --scene cornell --size "$size" --frames 1 --view ao-blurred \
        --ao-method "$method" --output "$out/cornell-ao-$method.png"
    echo "wrote $out/cornell-ao-$method.png"
done
