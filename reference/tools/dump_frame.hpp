// The frame behind a dump. deepgi --headless --dump writes its images at
// the internal size, the viewport plus the guard band on each side
// (frame_layout, docs/design.md); the tools that work out again what the
// renderer did need the viewport, the guard band and the lengths it ran
// with, and every tool that sets a dump against the reference compares the
// pixels where both see the same surface (deepgi::same_surface_depth, the
// reference library's test, which the report uses too).
#pragma once

#include "deepgi/renderer.hpp"
#include "deepgi/same_surface_depth.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/settings.hpp"

#include <fmt/format.h>

#include <stdexcept>

namespace deepgi_tools {

// The settings of the 16:9 viewport whose internal size with this guard band
// is width x height (the sizes measure_*.sh render); every other setting is
// the default. Throws when no 16:9 viewport has that internal size.
inline deepgi::RenderSettings dump_viewport(int width, int height, float guard_band_fraction) {
    deepgi::RenderSettings settings;
    settings.guard_band_fraction = guard_band_fraction;
    for (int viewport_height = 1; viewport_height <= height; ++viewport_height) {
        settings.height = viewport_height;
        settings.width = viewport_height * 16 / 9;
        const deepgi::FrameLayout layout = deepgi::frame_layout(settings);
        if (layout.internal_height == height && layout.internal_width == width) return settings;
    }
    throw std::runtime_error(
        fmt::format("{}x{} is not a 16:9 size with this guard band", width, height));
}

// Every scene length `auto`, as deepgi's command line leaves them, but the
// radiosity radius (metres, or auto_length), resolved against the scene's
// size as the renderer resolves them.
inline deepgi::RenderSettings with_scene_lengths(deepgi::RenderSettings settings,
                                                 const deepgi::Scene& scene,
                                                 float radiosity_radius) {
    settings = deepgi::with_auto_lengths(settings);
    settings.radiosity.radius = radiosity_radius;
    return deepgi::resolve_auto_lengths(settings, deepgi::scene_scale(scene));
}

}  // namespace deepgi_tools
