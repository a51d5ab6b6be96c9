#include "sao_reference.hpp"

#include "support/textbook_camera.hpp"

#include <algorithm>
#include <bit>
#include <cmath>

namespace deepgi::test {

namespace {

// The shader's own hash source (shaders/pixel_rotation_hash.h).
namespace shader {
using uint = std::uint32_t;
#define DEEPGI_SHARED_FUNCTION inline
#include "pixel_rotation_hash.h"
#undef DEEPGI_SHARED_FUNCTION
}  // namespace shader

// The thick spiral's sector count per tap count, the shader's own macro.
#include "ao_thick_sectors.h"

// The march (sao.frag, march_visibility): AV = 1 - mean f(d) over cosine-
// weighted rays, each marched until it is first inside the solid behind a
// stored surface: to its back face (at least two steps deep), or `thickness`
// deep where it has none; not where that surface and X's meet at a convex
// edge.
float march_visibility(int x, int y, glm::vec3 position, glm::vec3 normal, const SaoInputs& inputs,
                       const AoSettings& settings) {
    const FloatImage& base = inputs.pyramid.at(0);
    const float width = float(base.width);
    const float height = float(base.height);
    const glm::vec3 axis = std::abs(normal.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
    const glm::vec3 tangent = glm::normalize(glm::cross(normal, axis));
    const glm::vec3 bitangent = glm::cross(normal, tangent);
    const std::uint32_t hash = pixel_rotation_hash(std::uint32_t(x), std::uint32_t(y));
    // The first frame: point 0 of the temporal sequence adds nothing to either.
    const float offset = float(shader::avalanche32(hash ^ 0x68e31da4u) >> 8) * (1.0f / 16777216.0f);
    const float phi = pixel_rotation_angle(std::uint32_t(x), std::uint32_t(y));
    const float c = std::cos(phi), s = std::sin(phi);
    const float radius = settings.radius;
    const float step_length = radius / float(DEEPGI_AO_MARCH_STEPS);
    float occlusion = 0.0f;
    for (int i = 0; i < DEEPGI_AO_MARCH_RAYS; ++i) {
        // Ray i of the golden-angle disk, turned by the pixel's rotation, and
        // lifted to the hemisphere (Malley's method: cosine-weighted).
        const float golden = float(i) * 0.618034f;
        const float angle = 6.2831855f * (golden - std::floor(golden));
        const float disk_radius = std::sqrt((float(i) + 0.5f) / float(DEEPGI_AO_MARCH_RAYS));
        const float dx = std::cos(angle), dy = std::sin(angle);
        const glm::vec2 disk = glm::vec2(c * dx - s * dy, s * dx + c * dy) * disk_radius;
        const glm::vec3 direction = tangent * disk.x + bitangent * disk.y +
                                    normal * std::sqrt(std::max(0.0f, 1.0f - glm::dot(disk, disk)));
        float previous = 0.0f;
        float hit = -1.0f;
        for (int k = 0; k < DEEPGI_AO_MARCH_STEPS && hit < 0.0f; ++k) {
            const float t = (float(k) + offset) * step_length;
            const glm::vec3 q = position + direction * t;
            const float z = -q.z;
            if (z <= inputs.near_plane) break;
            const float at_x = (q.x / (z * inputs.ray_scale.x) * 0.5f + 0.5f) * width;
            const float at_y = (q.y / (z * inputs.ray_scale.y) * 0.5f + 0.5f) * height;
            if (at_x < 0.0f || at_y < 0.0f || at_x >= width || at_y >= height) break;
            const int px = int(at_x), py = int(at_y);
            for (int layer = 0; layer < settings.layers && hit < 0.0f; ++layer) {
                const float depth = base.at(px, py, layer);
                if (depth <= 0.0f || z <= depth) continue;
                const float back_face = inputs.back_faces.at(std::size_t(layer)).at(px, py);
                const float solid_end = back_face > 0.0f
                                            ? std::max(back_face, depth + 2.0f * step_length)
                                            : depth + settings.thickness;
                if (z >= solid_end) continue;
                const glm::vec3 surface =
                    camera_position(float(px) + 0.5f, float(py) + 0.5f, depth, inputs);
                const FloatImage& normals = layer == 0 ? inputs.normals : inputs.normals_layer1;
                const glm::vec3 surface_normal(normals.at(px, py, 0), normals.at(px, py, 1),
                                               normals.at(px, py, 2));
                // Behind the stored depth, within the slab, and behind the
                // surface's plane by more than its reconstruction error.
                const float tolerance = settings.bias + 1.0e-3f * z;
                const float below = glm::dot(q - surface, surface_normal);
                if (below >= -tolerance) continue;
                // Not where that surface and X's meet at a convex edge: each
                // on or behind the other's plane. The pixel's solid reaches
                // past the edge there, beside X's face, where a ray leaving X
                // finds nothing.
                if (glm::dot(position - surface, surface_normal) < tolerance &&
                    glm::dot(surface - position, normal) < tolerance)
                    continue;
                const float above =
                    glm::dot(position + direction * previous - surface, surface_normal);
                hit = above > 0.0f ? previous + (t - previous) * above / (above - below) : t;
            }
            previous = t;
        }
        if (hit >= 0.0f) occlusion += std::max(0.0f, 1.0f - hit * hit / (radius * radius));
    }
    return 1.0f - occlusion / float(DEEPGI_AO_MARCH_RAYS);
}

float obscurance(glm::vec3 v, glm::vec3 normal, float radius_squared, float bias) {
    constexpr float epsilon = 1.0e-4f;
    const float vv = glm::dot(v, v);
    const float vn = glm::dot(v, normal);
    return (1.0f - vv / radius_squared) * std::max((vn - bias) / std::sqrt(vv + epsilon), 0.0f);
}

// Where a tap lands (sao.frag, spiral_tap): its pyramid level and texel, and
// the level-0 pixel that texel's depth was copied from.
struct TapLookup {
    bool inside = false;  // false: off the guard-banded buffer
    int level = 0;
    int texel_x = 0, texel_y = 0;
    int source_x = 0, source_y = 0;
};

TapLookup look_up_tap(const spiral::codegen::Tap& tap, int x, int y, float c, float s,
                      float radius_pixels, float q, const SaoInputs& inputs) {
    const FloatImage& base = inputs.pyramid.at(0);
    const int max_mip = int(inputs.pyramid.size()) - 1;
    TapLookup lookup;
    const float offset_x = std::clamp((c * tap.x - s * tap.y) * radius_pixels, -65536.0f, 65536.0f);
    const float offset_y = std::clamp((s * tap.x + c * tap.y) * radius_pixels, -65536.0f, 65536.0f);
    const int tap_x = int(std::floor(float(x) + 0.5f + offset_x));
    const int tap_y = int(std::floor(float(y) + 0.5f + offset_y));
    if (tap_x < 0 || tap_y < 0 || tap_x >= base.width || tap_y >= base.height) return lookup;
    // m_i = clamp(floor(log2(h_i / q)), 0, MAX_MIP), h_i = alpha_i * R.
    const float steps = std::min(tap.alpha * radius_pixels / q, 65536.0f);
    lookup.level =
        steps < 1.0f ? 0 : std::min(int(std::floor(std::log2(std::floor(steps)))), max_mip);
    const FloatImage& mip = inputs.pyramid[std::size_t(lookup.level)];
    lookup.texel_x = std::min(tap_x >> lookup.level, mip.width - 1);
    lookup.texel_y = std::min(tap_y >> lookup.level, mip.height - 1);
    // The level-0 pixel the texel's depth was copied from: each level takes
    // corner ((y & 1) ^ 1, (x & 1) ^ 1) of its 2x2 block in the level below,
    // clamped at odd sizes.
    lookup.source_x = lookup.texel_x;
    lookup.source_y = lookup.texel_y;
    for (int l = lookup.level; l > 0; --l) {
        const FloatImage& finer = inputs.pyramid[std::size_t(l - 1)];
        const int corner_x = (lookup.source_y & 1) ^ 1, corner_y = (lookup.source_x & 1) ^ 1;
        lookup.source_x = std::min(2 * lookup.source_x + corner_x, finer.width - 1);
        lookup.source_y = std::min(2 * lookup.source_y + corner_y, finer.height - 1);
    }
    lookup.inside = true;
    return lookup;
}

// The thick spiral (docs/design.md, section 5.6): each tap's solid, from the
// front surface to its back face along the camera ray, occludes the band of
// elevations between its ends at its azimuth; bands are unioned per azimuth
// sector in bins of equal cosine-weighted measure (u = sin^2 of the
// elevation), and a bin counts once, weighted by the falloff at the distance
// of the first tap (in order of growing radius) that covers it; a sector is
// seen where a layer-0 surface falls into it. The
// sector count grows with the tap count (shaders/ao_thick_sectors.h).
constexpr int thick_bins = 32;
constexpr int thick_max_sectors = 8;

float spiral_thick_visibility(int x, int y, glm::vec3 position, glm::vec3 normal, float depth,
                              const SaoInputs& inputs,
                              const std::vector<spiral::codegen::Tap>& taps,
                              const AoSettings& settings, int thick_sectors) {
    const float height = float(inputs.pyramid.at(0).height);
    const float radius_pixels = settings.radius * (0.5f * height) / (inputs.ray_scale.y * depth);
    const float threshold = settings.bias + 0.5f * (2.0f * inputs.ray_scale.y * depth / height);
    const float phi = pixel_rotation_angle(std::uint32_t(x), std::uint32_t(y));
    const float c = std::cos(phi), s = std::sin(phi);
    // The sectors turn with the pixel's rotation.
    const glm::vec3 axis = std::abs(normal.z) < 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(1, 0, 0);
    const glm::vec3 axis_t = glm::normalize(glm::cross(normal, axis));
    const glm::vec3 axis_b = glm::cross(normal, axis_t);
    const glm::vec3 tangent = c * axis_t + s * axis_b;
    const glm::vec3 bitangent = glm::cross(normal, tangent);
    const float radius_squared = settings.radius * settings.radius;
    // covered[k][j]: bin j of sector k is already occluded by a nearer tap;
    // seen[k]: some tap on the buffer fell into sector k.
    bool covered[thick_max_sectors][thick_bins] = {};
    bool seen[thick_max_sectors] = {};
    double occlusion = 0.0;
    // Each tap stands for half the radial spacing of the taps of its sector
    // on either side of it (alpha units).
    const float cell = 0.5f * float(thick_sectors) / float(taps.size());
    for (const auto& tap : taps) {
        const float direction_x = (c * tap.x - s * tap.y) / tap.alpha;
        const float direction_y = (s * tap.x + c * tap.y) / tap.alpha;
        const TapLookup lookup = look_up_tap(tap, x, y, c, s, radius_pixels, inputs.q, inputs);
        if (!lookup.inside) continue;
        const FloatImage& mip = inputs.pyramid[std::size_t(lookup.level)];
        const float centre_x = float(lookup.source_x) + 0.5f;
        const float centre_y = float(lookup.source_y) + 0.5f;
        for (int layer = 0; layer < settings.layers; ++layer) {
            const float front = mip.at(lookup.texel_x, lookup.texel_y, layer);
            if (front <= 0.0f) continue;
            const float back_face =
                inputs.back_faces.at(std::size_t(layer)).at(lookup.source_x, lookup.source_y);
            const float back =
                back_face > 0.0f ? std::max(back_face, front) : front + settings.thickness;
            const glm::vec3 front_point = camera_position(centre_x, centre_y, front, inputs);
            const glm::vec3 f = front_point - position;
            const glm::vec3 b = camera_position(centre_x, centre_y, back, inputs) - position;
            // The tap's tangent plane across its cell of the sector's radii.
            const FloatImage& normals = layer == 0 ? inputs.normals : inputs.normals_layer1;
            const glm::vec3 tap_normal(normals.at(lookup.source_x, lookup.source_y, 0),
                                       normals.at(lookup.source_x, lookup.source_y, 1),
                                       normals.at(lookup.source_x, lookup.source_y, 2));
            auto cell_end = [&](float alpha) {
                const float at_x = float(x) + 0.5f + direction_x * alpha * radius_pixels;
                const float at_y = float(y) + 0.5f + direction_y * alpha * radius_pixels;
                const glm::vec3 ray = camera_position(at_x, at_y, 1.0f, inputs);
                const float along = glm::dot(ray, tap_normal);
                const float t =
                    std::abs(along) > 1.0e-6f ? glm::dot(front_point, tap_normal) / along : front;
                return ray * std::clamp(t, 0.1f * front, 10.0f * front) - position;
            };
            // A tap straight above X has no azimuth: 0, as the shader takes it
            // (atan2 of signed zeros could give +-pi).
            const float along_b = glm::dot(f, bitangent), along_t = glm::dot(f, tangent);
            const float azimuth =
                along_b == 0.0f && along_t == 0.0f ? 0.0f : std::atan2(along_b, along_t);
            const int sector =
                std::clamp(int(std::floor((azimuth / 6.2831853f + 0.5f) * float(thick_sectors))), 0,
                           thick_sectors - 1);
            // Layer 0 makes its sector seen; a layer-1 solid counts only in
            // a sector already seen (ao_spiral_thick.glsl, `informs`).
            if (layer == 0)
                seen[sector] = true;
            else if (!seen[sector])
                continue;
            const glm::vec3 near_end = cell_end(std::max(tap.alpha - cell, 0.0f));
            const glm::vec3 far_end = cell_end(tap.alpha + cell);
            // Distance: the segment's point nearest to X.
            const glm::vec3 e = b - f;
            const float ee = glm::dot(e, e);
            const glm::vec3 nearest =
                ee > 0.0f ? f + e * std::clamp(-glm::dot(f, e) / ee, 0.0f, 1.0f) : f;
            const float dd = glm::dot(nearest, nearest);
            if (dd >= radius_squared) continue;
            if (glm::dot(f, normal) <= threshold && glm::dot(b, normal) <= threshold) continue;
            // u = sin^2 of the elevation above X's plane raised by the
            // threshold; a point below it is at 0.
            auto u = [&](glm::vec3 v) {
                const float h = glm::dot(v, normal) - threshold;
                return h > 0.0f ? std::min(h * h / glm::dot(v, v), 1.0f) : 0.0f;
            };
            const float us[4] = {u(f), u(b), u(near_end), u(far_end)};
            const float lowest = *std::min_element(us, us + 4);
            const float highest = *std::max_element(us, us + 4);
            // The tap's plane meets X's camera ray at or behind X: a crease,
            // and the band reaches down to the horizon.
            const float toward_x = glm::dot(position, tap_normal);
            const bool crease =
                toward_x != 0.0f && glm::dot(front_point, tap_normal) / toward_x >= 1.0f;
            const int first =
                crease ? 0 : std::min(int(lowest * float(thick_bins)), thick_bins - 1);
            const int last = std::min(int(highest * float(thick_bins)), thick_bins - 1);
            int fresh = 0;
            for (int j = first; j <= last; ++j) {
                fresh += !covered[sector][j];
                covered[sector][j] = true;
            }
            occlusion += double(1.0f - dd / radius_squared) * fresh;
        }
    }
    // The overhang test (ao_spiral_thick.glsl, add_overhang): a probe r / 4
    // above X, then one r / 2 above X; the first layer whose stored point on
    // a probe's camera ray hides it, lies at least r / 8 above X's plane and
    // within r of X is over X if at least 45 degrees up (u >= 1/2), and then
    // closes every seen sector from that point's elevation to the zenith.
    // The first probe over X decides; a probe whose point is lower hands on
    // to the next.
    const float width = float(inputs.pyramid.at(0).width);
    for (const float up : {0.25f, 0.5f}) {
        const glm::vec3 probe = position + up * settings.radius * normal;
        const float probe_depth = -probe.z;
        const float probe_x = (probe.x / (probe_depth * inputs.ray_scale.x) + 1.0f) * 0.5f * width;
        const float probe_y = (probe.y / (probe_depth * inputs.ray_scale.y) + 1.0f) * 0.5f * height;
        if (!(probe_depth > 0.0f && probe_x >= 0.0f && probe_y >= 0.0f && probe_x < width &&
              probe_y < height))
            continue;
        bool over = false;
        for (int layer = 0; layer < settings.layers; ++layer) {
            const float front = inputs.pyramid[0].at(int(probe_x), int(probe_y), layer);
            const glm::vec3 v = probe * (front / probe_depth) - position;
            const float h = glm::dot(v, normal), dd = glm::dot(v, v);
            if (!(front > 0.0f && front < probe_depth && h >= 0.125f * settings.radius &&
                  dd < radius_squared))
                continue;
            const float rise = h - threshold;
            const float u = rise > 0.0f ? std::min(rise * rise / dd, 1.0f) : 0.0f;
            if (u < 0.5f) break;  // not over X: within 45 degrees of its zenith only
            int fresh = 0;
            for (int k = 0; k < thick_sectors; ++k)
                for (int j = std::min(int(u * float(thick_bins)), thick_bins - 1);
                     seen[k] && j < thick_bins; ++j)
                    fresh += !covered[k][j];
            occlusion += double(1.0f - dd / radius_squared) * fresh;
            over = true;
            break;
        }
        if (over) break;
    }
    const int sectors_seen = int(std::count(seen, seen + thick_sectors, true));
    return sectors_seen == 0 ? 1.0f : float(1.0 - occlusion / double(sectors_seen * thick_bins));
}

}  // namespace

glm::vec3 camera_position(float centre_x, float centre_y, float depth, const SaoInputs& inputs) {
    const float width = float(inputs.pyramid[0].width);
    const float height = float(inputs.pyramid[0].height);
    const float ndc_x = centre_x * (1.0f / width) * 2.0f - 1.0f;
    const float ndc_y = centre_y * (1.0f / height) * 2.0f - 1.0f;
    return {ndc_x * inputs.ray_scale.x * depth, ndc_y * inputs.ray_scale.y * depth, -depth};
}

std::uint32_t avalanche32(std::uint32_t x) {
    return shader::avalanche32(x);
}

std::uint32_t pixel_rotation_hash(std::uint32_t x, std::uint32_t y, std::uint32_t seed) {
    return shader::pixel_rotation_hash_xy(x, y, seed);
}

float pixel_rotation_angle(std::uint32_t x, std::uint32_t y, std::uint32_t seed) {
    return float(pixel_rotation_hash(x, y, seed) >> 8) * (1.0f / 16777216.0f) * 6.2831855f;
}

glm::vec2 camera_ray_scale(const Camera& camera, const RenderSettings& settings) {
    // From the textbook camera, not the library's projection: the viewport's
    // half-height spans tan(fov / 2) at unit depth, and the guard band widens
    // the buffer by the same projection, so NDC 1 lies (H / 2 + g) pixels
    // from the centre.
    const TextbookCamera t = textbook_camera(camera, settings);
    const double per_pixel = double(t.tan_half_fov) / (0.5 * double(t.height));
    return {float(per_pixel * (0.5 * double(t.width) + double(t.guard))),
            float(per_pixel * (0.5 * double(t.height) + double(t.guard)))};
}

glm::vec2 renderer_ray_scale(const Camera& camera, const RenderSettings& settings) {
    const glm::mat4 projection = guard_band_projection(camera, settings);
    return {1.0f / projection[0][0], 1.0f / projection[1][1]};
}

FloatImage reference_ambient_visibility(const SaoInputs& inputs,
                                        const std::vector<spiral::codegen::Tap>& taps,
                                        const AoSettings& settings, int thick_sectors) {
    if (thick_sectors == 0) thick_sectors = DEEPGI_AO_THICK_SECTORS_FOR(int(taps.size()));
    thick_sectors = std::clamp(thick_sectors, 1, thick_max_sectors);
    const FloatImage& base = inputs.pyramid.at(0);
    const int width = base.width;
    const int height = base.height;
    FloatImage result;
    result.width = width;
    result.height = height;
    result.channels = 1;
    result.pixels.assign(std::size_t(width) * std::size_t(height), 1.0f);
    const float radius_squared = settings.radius * settings.radius;
    const float n = float(taps.size());

    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const float depth = base.at(x, y, 0);
            if (depth <= 0.0f) continue;  // sky
            const glm::vec3 position =
                camera_position(float(x) + 0.5f, float(y) + 0.5f, depth, inputs);
            const glm::vec3 normal(inputs.normals.at(x, y, 0), inputs.normals.at(x, y, 1),
                                   inputs.normals.at(x, y, 2));
            if (settings.method == deepgi::AoMethod::march) {
                result.pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)] = std::pow(
                    march_visibility(x, y, position, normal, inputs, settings), settings.intensity);
                continue;
            }
            if (settings.method == deepgi::AoMethod::spiral_thick) {
                result.pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)] =
                    std::pow(spiral_thick_visibility(x, y, position, normal, depth, inputs, taps,
                                                     settings, thick_sectors),
                             settings.intensity);
                continue;
            }
            const float radius_pixels =
                settings.radius * (0.5f * float(height)) / (inputs.ray_scale.y * depth);
            const float phi = pixel_rotation_angle(std::uint32_t(x), std::uint32_t(y));
            const float c = std::cos(phi);
            const float s = std::sin(phi);
            float sum = 0.0f;
            for (const auto& tap : taps) {
                const TapLookup lookup =
                    look_up_tap(tap, x, y, c, s, radius_pixels, inputs.q, inputs);
                if (!lookup.inside) continue;
                const FloatImage& mip = inputs.pyramid[std::size_t(lookup.level)];
                const int texel_x = lookup.texel_x, texel_y = lookup.texel_y;
                const int source_x = lookup.source_x, source_y = lookup.source_y;
                float occlusion = 0.0f;
                if (settings.method == deepgi::AoMethod::solid_angle) {
                    // Solid-angle method: the term of the obscurance integral
                    // over the seen surface (docs/deep-sao.md), tap weight
                    // alpha_i * (z_Y / z_X)^2 / cos(view angle at Y).
                    const float footprint = 2.0f * inputs.ray_scale.y * depth / float(height);
                    const float beta = settings.bias + 0.5f * footprint;
                    for (int layer = 0; layer < settings.layers; ++layer) {
                        const float tap_depth = mip.at(texel_x, texel_y, layer);
                        if (tap_depth <= 0.0f) continue;
                        const glm::vec3 y = camera_position(
                            float(source_x) + 0.5f, float(source_y) + 0.5f, tap_depth, inputs);
                        const FloatImage& normals =
                            layer == 0 ? inputs.normals : inputs.normals_layer1;
                        const glm::vec3 tap_normal(normals.at(source_x, source_y, 0),
                                                   normals.at(source_x, source_y, 1),
                                                   normals.at(source_x, source_y, 2));
                        const glm::vec3 v = y - position;
                        const float vv = glm::dot(v, v);
                        if (vv >= radius_squared || vv <= 0.0f) continue;
                        // The bias is a threshold: points less than beta
                        // above the tangent plane are X's own surface.
                        const float vn = glm::dot(v, normal);
                        if (vn <= beta) continue;
                        const float length_v = std::sqrt(vv);
                        const float cos_x = vn / length_v;
                        const float cos_y = std::abs(glm::dot(v, tap_normal)) / length_v;
                        if (cos_y <= 0.0f) continue;
                        const glm::vec3 view_ray = glm::normalize(y);
                        const float cos_phi = -view_ray.z;  // the tap's angle off the optical axis
                        const float cos_view = std::max(glm::dot(tap_normal, -view_ray), 0.1f);
                        const float ratio = tap_depth / depth;
                        occlusion = std::max(occlusion, tap.alpha * ratio * ratio * cos_phi *
                                                            (1.0f - vv / radius_squared) * cos_x *
                                                            cos_y / (vv * cos_view));
                    }
                    sum += occlusion;
                    continue;
                }
                for (int layer = 0; layer < settings.layers; ++layer) {
                    const float tap_depth = mip.at(texel_x, texel_y, layer);
                    if (tap_depth <= 0.0f) continue;
                    const glm::vec3 v = camera_position(float(source_x) + 0.5f,
                                                        float(source_y) + 0.5f, tap_depth, inputs) -
                                        position;
                    occlusion =
                        std::max(occlusion, obscurance(v, normal, radius_squared, settings.bias));
                }
                sum += occlusion;
            }
            float visibility;
            if (settings.method == deepgi::AoMethod::solid_angle) {
                // Signed: 1 minus an unbiased estimate of the obscurance,
                // clamped only where it is consumed. The exponent applies to
                // the positive range; below 0 the value is kept as it is.
                const float estimate = 1.0f - 2.0f * radius_squared / n * sum;
                visibility = estimate > 0.0f ? std::pow(estimate, settings.intensity) : estimate;
            } else {
                visibility = std::pow(std::max(0.0f, 1.0f - std::sqrt(3.14159265f / n * sum)),
                                      settings.intensity);
            }
            result.pixels[std::size_t(y) * std::size_t(width) + std::size_t(x)] = visibility;
        }
    }
    return result;
}

FloatImage reference_pyramid_level(const FloatImage& finer) {
    FloatImage coarser;
    coarser.width = std::max(1, finer.width / 2);
    coarser.height = std::max(1, finer.height / 2);
    coarser.channels = finer.channels;
    coarser.pixels.resize(std::size_t(coarser.width) * std::size_t(coarser.height) *
                          std::size_t(finer.channels));
    for (int y = 0; y < coarser.height; ++y) {
        for (int x = 0; x < coarser.width; ++x) {
            // One texel of the 2x2 block, the corner alternating with the other
            // axis's parity (McGuire et al. 2012); clamped for odd or unit sizes.
            const int from_x = std::min(2 * x + ((y & 1) ^ 1), finer.width - 1);
            const int from_y = std::min(2 * y + ((x & 1) ^ 1), finer.height - 1);
            for (int c = 0; c < finer.channels; ++c) {
                coarser.pixels[(std::size_t(y) * std::size_t(coarser.width) + std::size_t(x)) *
                                   std::size_t(finer.channels) +
                               std::size_t(c)] = finer.at(from_x, from_y, c);
            }
        }
    }
    return coarser;
}

}  // namespace deepgi::test
