#pragma once
// The one test every comparison of the renderer with the ray tracer uses to
// pick the pixels where both see the same surface (the measuring tools of
// reference/tools, the report's mirror rows, the reflection comparison).
#include <cmath>

namespace deepgi {

// Whether a pixel's rasterised layer-0 depth (the dump's) and the ray
// tracer's (the reference's, or a hit distance along the same camera ray)
// see the same surface: both hit something, within 1e-3 of each other.
// Silhouette pixels would otherwise compare different points.
inline bool same_surface_depth(float raster_depth, float traced_depth) {
    return raster_depth > 0.0f && traced_depth > 0.0f &&
           std::abs(raster_depth - traced_depth) <= 1e-3f * traced_depth;
}

}  // namespace deepgi
