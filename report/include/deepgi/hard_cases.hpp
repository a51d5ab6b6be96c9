#pragma once
// The numerical hard cases of the deep G-buffer and deep SAO (docs/deep-sao.md,
// "Numerical stability"): the scenes, settings and parameter lists that both
// the stability tests and the report's stability table render, built here once
// so that the two always exercise the same inputs, and what they read back
// from a rendered case.
#include "deepgi/image_io.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/settings.hpp"

#include <string>
#include <utility>
#include <vector>

namespace deepgi {
class ShaderLoader;
}

namespace deepgi::hard_cases {

// The parameters of every case; the defaults are the documented set.
struct Parameters {
    // Render size of every case but the tiny images.
    int width = 160;
    int height = 90;

    // Scale invariance: these scenes, each scaled by each factor with every
    // length setting scaled to match, give the AV of the unscaled scene.
    std::vector<std::string> scaled_scenes = {"ref-crease", "ref-slab"};
    std::vector<float> scales = {1e-3f, 1e3f, 1.0f / 1024.0f, 1024.0f};
    double scale_tolerance = 1e-3;  // largest |AV difference| per pixel

    // Far geometry: an open floor whose centre ray is 1 km long, seen through
    // a 1 mm near plane, at these pitches (degrees) and AO radii (m).
    std::vector<float> far_pitches = {-90.0f, -45.0f};
    std::vector<float> far_radii = {0.5f, 50.0f};

    // Grazing views of an open floor 1 m below the camera (pitch in degrees).
    std::vector<float> grazing_pitches = {-20.0f, -5.0f, -1.0f, -0.2f};

    // Layer counts of the grazing and guard-band cases.
    std::vector<int> layers = {1, 2};

    // Depth discontinuity in the guard band: AO radii (m) to try at each edge.
    std::vector<float> guard_radii = {0.05f, 0.5f, 20.0f};

    // Degenerate images: these sizes of these scenes.
    std::vector<std::pair<int, int>> tiny_sizes = {{1, 1}, {3, 2}};
    std::vector<std::string> tiny_scenes = {"ref-slab", "cornell"};

    // An open plane is unoccluded: its AV may not fall below this.
    double open_surface_min_visibility = 0.99;
};

// The settings every case starts from: the given size and a small shadow map
// (the cases are about AO; the shadow map only costs time).
RenderSettings base_settings(int width, int height);

// Everything with a length scaled by s: geometry, camera position and near
// plane. Angles and pixel measures stay.
Scene scaled_scene(Scene scene, float s);
// The AO radius, bias and march thickness and the layer separation scaled by s.
RenderSettings scaled_settings(RenderSettings settings, float s);

// A 20 km open floor (y = 0) and a camera with a 1 mm near plane at the
// height where its centre ray, pitched by pitch_degrees (< 0), meets the
// floor 1 km away.
Scene far_floor(float pitch_degrees);

// A 20 km open floor 1 m below a camera at the origin pitched by pitch_degrees.
Scene grazing_floor(float pitch_degrees);

// Visible-frame pixel columns (from the left edge of the visible frame; < 0
// is inside the guard band) where guard_edge() puts its depth discontinuity:
// halfway into the left guard band, at the first visible column, and one
// column further in.
std::vector<int> guard_edge_columns(const RenderSettings& settings);

// A near wall (0.3 m) whose right edge falls at visible column edge_column of
// a camera at the origin looking down -Z, in front of a far wall (50 m): depth
// jumps by a factor of 160 between neighbouring pixels there.
Scene guard_edge(const RenderSettings& settings, int edge_column);

// What a case gives back: the AV before and after the blur, and level 0 of
// the depth pyramid (> 0 where layer 0 hit a surface).
struct AoFrame {
    FloatImage depth;
    FloatImage raw;
    FloatImage blurred;
};

// One frame of `scene` from its default camera; needs a current GL context.
AoFrame render_ao(const Scene& scene, const RenderSettings& settings, const ShaderLoader& loader);

// The lowest raw or blurred AV over the viewport pixels (guard band excluded)
// that hit a surface, and how many such pixels there are; 1 when none.
double lowest_on_surfaces(const AoFrame& frame, int guard, long long* surface_pixels);

}  // namespace deepgi::hard_cases
