// Monte Carlo ambient visibility and one-bounce irradiance on the G-buffer's
// pixel grid. Every pixel draws the keys that scramble its sample points
// from its own random stream (seed, pixel index), so the images do not
// depend on the number of threads or on scheduling.
#include "deepgi/reference.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <system_error>
#include <thread>

namespace deepgi {
namespace {

constexpr double pi = 3.14159265358979323846;

// SplitMix64: small, fast, and good enough for per-pixel streams of keys.
struct Random {
    std::uint64_t state;
    std::uint64_t next() {
        std::uint64_t z = (state += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }
};

std::uint64_t stream_seed(std::uint64_t seed, std::uint64_t index) {
    Random mix{seed ^ (index * 0xD1B54A32D192ED03ull)};
    mix.next();
    return mix.next();
}

// Randomised quasi-Monte Carlo points for both estimators.
//
// The first two dimensions of Sobol's sequence, in 32-bit fixed point: the
// index with its bits reversed (van der Corput), and the index through
// Pascal's matrix mod 2. Every aligned run of 2^m points is a (0, m, 2)-net:
// each of the 2^m boxes 2^-a wide and 2^-(m-a) high holds exactly one point,
// and a run of 16 k points is k such nets of 16, so the points stay evenly
// spread whenever the estimator stops.
std::uint32_t reverse_bits(std::uint32_t x) {
    x = (x << 16) | (x >> 16);
    x = ((x & 0x00FF00FFu) << 8) | ((x >> 8) & 0x00FF00FFu);
    x = ((x & 0x0F0F0F0Fu) << 4) | ((x >> 4) & 0x0F0F0F0Fu);
    x = ((x & 0x33333333u) << 2) | ((x >> 2) & 0x33333333u);
    return ((x & 0x55555555u) << 1) | ((x >> 1) & 0x55555555u);
}

std::uint32_t sobol_y(std::uint32_t index) {
    std::uint32_t bits = 0;
    for (std::uint32_t column = 1u << 31; index != 0; index >>= 1, column ^= column >> 1)
        if (index & 1u) bits ^= column;
    return bits;
}

// A random nested scramble of one coordinate, applied to its bits reversed
// (bit 0 the first binary digit). Each step changes bit k by a function of
// bits 0 .. k-1 only: adding carries upwards, and a product with an even
// factor has bit k made of the bits below k. So digit k of the coordinate
// flips or not by the digits before it, which permutes the two halves of
// every dyadic interval: the nets stay nets. The first addition of a
// uniform random 32-bit key makes every point uniform on the 2^-32 grid, so
// the mean over the points is unbiased; the products with fixed even
// factors and the second key spread each key's effect over the deeper
// digits (a cheap stand-in for Owen's independent coin per interval).
std::uint32_t nested_scramble(std::uint32_t reversed, std::uint64_t key) {
    reversed += std::uint32_t(key);
    reversed ^= reversed * 0x9E3779B8u;
    reversed += std::uint32_t(key >> 32);
    reversed ^= reversed * 0x85EBCA6Cu;
    reversed ^= reversed * 0xC2B2AE3Cu;
    return reverse_bits(reversed);
}

// One randomisation of the 2D points: point `index` of a set scrambled with
// its own pair of keys, from the Sobol digits reversed (the first coordinate's
// reversed digits are the index itself). Sets with independent keys are
// independent, and each set is stratified.
struct ScrambledPoints {
    std::uint64_t key_x = 0, key_y = 0;
    glm::dvec2 point(std::uint32_t index, std::uint32_t reversed_y) const {
        constexpr double scale = 1.0 / 4294967296.0;
        // Cell midpoints of the 2^-32 grid: never 0 or 1.
        return {(double(nested_scramble(index, key_x)) + 0.5) * scale,
                (double(nested_scramble(reversed_y, key_y)) + 0.5) * scale};
    }
};

// Orthonormal tangent frame around a unit normal (branchless, Duff et al.).
// How far a ray leaves a surface at `position` so that it does not hit the
// triangle it starts on again: relative to the distance from the origin,
// where float positions lose their precision, plus a hair of `length` (the
// ray's radius, or the scene's size) for points at the origin.
float surface_offset(glm::vec3 position, float length) {
    return 1e-5f * std::max({std::abs(position.x), std::abs(position.y), std::abs(position.z)}) +
           1e-6f * length;
}

void tangent_frame(glm::dvec3 n, glm::dvec3& t, glm::dvec3& b) {
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double c = n.x * n.y * a;
    t = {1.0 + sign * n.x * n.x * a, sign * c, -sign * n.x};
    b = {c, sign + n.y * n.y * a, -n.y};
}

}  // namespace

AoSample ambient_visibility_at(const RayScene& scene, glm::vec3 position, glm::vec3 normal,
                               float radius, const AoRayBudget& budget, std::uint64_t seed,
                               const LayerClassifier& classify) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(normal));
    glm::dvec3 t, b;
    tangent_frame(n, t, b);
    const float offset = surface_offset(position, radius);
    const glm::vec3 origin = position + glm::vec3(n) * offset;
    const double r2 = double(radius) * double(radius);

    // Stratified in independent sets, as irradiance_at: each set is the same
    // Sobol points under its own nested scramble, so its mean is unbiased
    // and the spread of the set means is the standard error.
    struct Set {
        ScrambledPoints directions;
        double occlusion = 0.0, hits = 0.0;
        double split[3] = {0.0, 0.0, 0.0};
    };
    const int set_count = std::max(2, budget.replicates);
    std::vector<Set> sets(static_cast<std::size_t>(set_count));
    Random random{seed};
    for (Set& set : sets) set.directions = {random.next(), random.next()};
    auto trace = [&](glm::dvec2 u, Set& set) {
        // Cosine-weighted direction: uniform on the unit disk, lifted.
        const double s = std::sqrt(u.x), phi = 2.0 * pi * u.y;
        const double z = std::sqrt(std::max(0.0, 1.0 - u.x));
        const glm::dvec3 w = t * (s * std::cos(phi)) + b * (s * std::sin(phi)) + n * z;
        const RayScene::Hit hit = scene.intersect(origin, glm::vec3(w), 0.0f, radius);
        if (!hit.hit) return;
        const double d = hit.distance + offset * z;  // from X, not the offset origin
        const double occlusion = std::max(0.0, 1.0 - d * d / r2);
        set.occlusion += occlusion;
        set.hits += 1.0;
        if (classify) {
            const int layer = classify(origin + glm::vec3(w) * hit.distance);
            set.split[layer == 0 ? 0 : layer == 1 ? 1 : 2] += occlusion;
        }
    };
    auto standard_error = [&](long long points) {
        double mean = 0.0;
        for (const Set& set : sets) mean += set.occlusion / double(points);
        mean /= double(set_count);
        double squares = 0.0;
        for (const Set& set : sets) {
            const double deviation = set.occlusion / double(points) - mean;
            squares += deviation * deviation;
        }
        return std::sqrt(squares / (double(set_count - 1) * double(set_count)));
    };

    // Points per set between stop tests; a round that might pass max_rays is
    // not started.
    const long long step = std::max(1, (budget.batch + set_count - 1) / set_count);
    long long points = 0, rays = 0;
    double error = 0.0;
    for (;;) {
        for (long long i = 0; i < step && (points == 0 || rays + set_count <= budget.max_rays);
             ++i, ++points, rays += set_count) {
            const std::uint32_t index = std::uint32_t(points);
            const std::uint32_t reversed_y = reverse_bits(sobol_y(index));
            for (Set& set : sets) trace(set.directions.point(index, reversed_y), set);
        }
        error = standard_error(points);
        if (rays + set_count > budget.max_rays) break;
        // The margin on a noisy reading, as for irradiance.
        if (rays >= budget.min_rays && budget.error_margin * error < budget.target_error) break;
    }
    AoSample result;
    const double count = double(rays);
    double occlusion = 0.0, hits = 0.0, split[3] = {0.0, 0.0, 0.0};
    for (const Set& set : sets) {
        occlusion += set.occlusion;
        hits += set.hits;
        for (int k = 0; k < 3; ++k) split[k] += set.split[k];
    }
    result.visibility = 1.0 - occlusion / count;
    result.hit_visibility = 1.0 - hits / count;
    result.standard_error = error;
    result.occlusion_layer0 = split[0] / count;
    result.occlusion_layer1 = split[1] / count;
    result.occlusion_neither = classify ? split[2] / count : occlusion / count;
    result.rays = int(rays);
    return result;
}

namespace {

// The key light reflected at `position` on `hit`'s surface: L(y) without the
// emissive term.
glm::dvec3 reflected_key_light(const RayScene& scene, const RayScene::Hit& hit,
                               const RayScene::Surface& surface, glm::vec3 position) {
    if (surface.albedo == glm::vec3(0.0f)) return glm::dvec3(0.0);
    // The key light as light_irradiance() in lighting.glsl, in world space.
    const KeyLight& light = scene.key_light();
    const glm::vec3 axis = glm::normalize(light.direction);
    glm::vec3 to_light;
    glm::vec3 incident = light.colour * light.intensity;
    float shadow_far = std::numeric_limits<float>::infinity();
    if (light.kind == LightKind::directional) {
        to_light = -axis;
    } else {
        const glm::vec3 offset = light.position - position;
        const float distance_squared = std::max(glm::dot(offset, offset), 1e-4f);
        to_light = offset / std::sqrt(distance_squared);
        shadow_far = glm::length(offset);
        // KHR_lights_punctual's range window, 1 - (d / range)^4, clamped.
        float window = 1.0f;
        if (light.range > 0.0f) {
            const float ratio = distance_squared / (light.range * light.range);
            window = std::clamp(1.0f - ratio * ratio, 0.0f, 1.0f);
        }
        incident *= window / distance_squared;
    }
    if (light.kind == LightKind::spot) {
        // smoothstep(cos outer, cos inner, cos angle), as in GLSL.
        const float edge0 = std::cos(light.outer_cone), edge1 = std::cos(light.inner_cone);
        const float cos_angle = glm::dot(-to_light, axis);
        float cone;
        if (edge1 != edge0) {
            const float t = std::clamp((cos_angle - edge0) / (edge1 - edge0), 0.0f, 1.0f);
            cone = t * t * (3.0f - 2.0f * t);
        } else {
            cone = cos_angle >= edge0 ? 1.0f : 0.0f;
        }
        incident *= cone;
    }
    const float cosine = glm::dot(surface.shading_normal, to_light);
    if (!(cosine > 0.0f) || incident == glm::vec3(0.0f)) return glm::dvec3(0.0);
    // Shadow ray from just off the side the surface was hit on; the renderer
    // filters a shadow map here, the reference takes the exact visibility.
    const glm::vec3 side = glm::dot(hit.normal, to_light) >= 0.0f ? hit.normal : -hit.normal;
    const glm::vec3 origin = position + side * surface_offset(position, scene.scale());
    if (scene.occluded(origin, to_light, 0.0f, shadow_far)) return glm::dvec3(0.0);
    return glm::dvec3(surface.albedo) / pi * glm::dvec3(incident) * double(cosine);
}

// Power heuristic (exponent 2) weight of a technique with density `mine`
// against one with density `other`, both per unit solid angle.
double power_heuristic(double mine, double other) {
    const double a = mine * mine, b = other * other;
    return a + b > 0.0 ? a / (a + b) : 0.0;
}

}  // namespace

glm::dvec3 direct_outgoing_radiance(const RayScene& scene, const RayScene::Hit& hit,
                                    glm::vec3 position) {
    const RayScene::Surface surface = scene.surface(hit);
    glm::dvec3 radiance(surface.emissive);
    const glm::dvec3 reflected = reflected_key_light(scene, hit, surface, position);
    // Added only when lit, so an unlit point returns its emissive unchanged.
    if (reflected != glm::dvec3(0.0)) radiance += reflected;
    return radiance;
}

IrradianceSample irradiance_at(const RayScene& scene, glm::vec3 position, glm::vec3 normal,
                               float radius, const IrradianceRayBudget& budget,
                               std::uint64_t seed) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(normal));
    glm::dvec3 t, b;
    tangent_frame(n, t, b);
    // Both techniques measure directions and distances from the offset origin.
    const glm::vec3 origin = position + glm::vec3(n) * surface_offset(position, radius);
    const glm::dvec3 origin_d(origin);
    const std::vector<RayScene::Emitter>& emitters = scene.emitters();
    const bool sample_emitters = !emitters.empty();
    long long rays = 0;

    // One sample's estimate of E / pi from a point of the direction square
    // and, when the scene has emitters, a point of the emitter square.
    auto sample = [&](glm::dvec2 direction_point, glm::dvec2 emitter_point) {
        glm::dvec3 value(0.0);

        // Cosine-weighted direction (pdf cos / pi): L itself estimates E / pi.
        const double u1 = direction_point.x, u2 = direction_point.y;
        const double s = std::sqrt(u1), phi = 2.0 * pi * u2;
        const double z = std::sqrt(std::max(0.0, 1.0 - u1));
        const glm::vec3 w(t * (s * std::cos(phi)) + b * (s * std::sin(phi)) + n * z);
        ++rays;
        const RayScene::Hit hit = scene.intersect(origin, w, 0.0f, radius);
        // Nothing within the radius, or the back of a one-sided surface:
        // the gather reads neither, so neither sends light here.
        if (hit.hit && glm::dot(hit.normal, w) < 0.0f) {
            const glm::vec3 y = origin + w * hit.distance;
            const RayScene::Surface surface = scene.surface(hit);
            const glm::dvec3 reflected = reflected_key_light(scene, hit, surface, y);
            if (reflected != glm::dvec3(0.0)) value += reflected;
            if (surface.emissive != glm::vec3(0.0f)) {
                double weight = 1.0;
                const int e = sample_emitters ? scene.emitter_index(hit.primitive) : -1;
                if (e >= 0) {
                    // The density with which emitter sampling would have
                    // chosen this direction, per unit solid angle.
                    const RayScene::Emitter& emitter = emitters[std::size_t(e)];
                    const double distance = double(hit.distance);
                    const double cos_y = -glm::dot(emitter.normal, glm::dvec3(w));
                    const double p_emitter = emitter.probability / emitter.area * distance *
                                             distance / std::max(cos_y, 1e-12);
                    weight = power_heuristic(z / pi, p_emitter);
                }
                value += glm::dvec3(surface.emissive) * weight;
            }
        }

        // A point y on an emitter, uniform over its area (pdf probability /
        // area; per unit solid angle times d^2 / cos_y). The first coordinate
        // picks the emitter and, rescaled within the emitter's share, places
        // the point with the second, so the square maps onto all emitters
        // by area x power and its strata stay strata there. The definition
        // holds here too: nothing beyond the radius, nothing from a back
        // face, and y must be the first surface.
        if (sample_emitters) {
            double v1 = 0.0;
            const RayScene::Emitter& emitter = emitters[scene.pick_emitter(emitter_point.x, v1)];
            const double v2 = emitter_point.y;
            const double root = std::sqrt(v1);
            const glm::dvec3 y =
                emitter.p0 + emitter.edge1 * (root * (1.0 - v2)) + emitter.edge2 * (root * v2);
            const glm::dvec3 to_y = y - origin_d;
            const double distance = glm::length(to_y);
            if (distance > 0.0 && distance <= double(radius)) {
                const glm::dvec3 d = to_y / distance;
                const double cos_x = glm::dot(n, d);
                const double cos_y = -glm::dot(emitter.normal, d);
                if (cos_x > 0.0 && cos_y > 0.0) {
                    // Stop just short of y so the emitter does not shadow
                    // itself.
                    ++rays;
                    if (!scene.occluded(origin, glm::vec3(d), 0.0f,
                                        float(distance * (1.0 - 1e-4)))) {
                        const double p_emitter =
                            emitter.probability / emitter.area * distance * distance / cos_y;
                        // L cos_x / p_emitter times the power heuristic
                        // weight p_emitter^2 / (p_emitter^2 + p_cos^2), as
                        // E / pi; written so that no density divides.
                        const double p_cos = cos_x / pi;
                        value +=
                            emitter.emissive *
                            (cos_x * p_emitter / (pi * (p_emitter * p_emitter + p_cos * p_cos)));
                    }
                }
            }
        }
        return value;
    };

    // Independent replicates: each set scrambles the same Sobol points with
    // its own seeds, for the direction square and the emitter square apart.
    // Within a set the points are stratified, so a set's mean varies less
    // than that of as many independent samples; across sets the means are
    // independent and identically distributed, so their spread gives an
    // honest standard error. All sets grow by the same points in lockstep
    // and stay the same size, so E is the plain mean over all samples.
    struct Replicate {
        ScrambledPoints directions, emitter_points;
        glm::dvec3 sum{0.0};  // of the samples' E / pi
    };
    const int replicate_count = std::max(2, budget.replicates);
    std::vector<Replicate> replicates(static_cast<std::size_t>(replicate_count));
    Random random{seed};
    for (Replicate& r : replicates) {
        r.directions = {random.next(), random.next()};
        if (sample_emitters) r.emitter_points = {random.next(), random.next()};
    }
    auto estimate = [&](long long points, glm::dvec3& error) {
        glm::dvec3 mean(0.0);
        for (const Replicate& r : replicates) mean += r.sum / double(points);
        mean /= double(replicate_count);
        glm::dvec3 squares(0.0);
        for (const Replicate& r : replicates) {
            const glm::dvec3 deviation = r.sum / double(points) - mean;
            squares += deviation * deviation;
        }
        error = pi * glm::sqrt(squares / (double(replicate_count - 1) * double(replicate_count)));
        return pi * mean;
    };

    // Points per set between stop tests, and the most rays one more point in
    // every set can cost: the caps are never passed.
    const long long step = std::max(1, (budget.batch + replicate_count - 1) / replicate_count);
    const long long most_per_point = (sample_emitters ? 2LL : 1LL) * replicate_count;
    const long long ceiling_cap = std::max(budget.max_rays, budget.ceiling_max_rays);
    long long points = 0, cap = budget.max_rays;
    glm::dvec3 irradiance(0.0), error(0.0);
    for (;;) {
        for (long long i = 0; i < step && (points == 0 || rays + most_per_point <= cap);
             ++i, ++points) {
            const std::uint32_t index = std::uint32_t(points);
            const std::uint32_t reversed_y = reverse_bits(sobol_y(index));
            for (Replicate& r : replicates)
                r.sum += sample(
                    r.directions.point(index, reversed_y),
                    sample_emitters ? r.emitter_points.point(index, reversed_y) : glm::dvec2(0.0));
        }
        irradiance = estimate(points, error);
        // The error estimate from a few sets is itself noisy, and stopping on
        // the first low reading would favour readings that are too low; the
        // margin asks for a reading clearly below the target.
        const double reading = budget.error_margin * std::max({error.x, error.y, error.z});
        // Past max_rays only while the error is still at or above the
        // largest accepted.
        cap = reading < budget.largest_error ? budget.max_rays : ceiling_cap;
        if (rays + most_per_point > cap) break;
        if (rays >= budget.min_rays) {
            const double target =
                std::min(budget.largest_error,
                         std::max(budget.target_absolute_error,
                                  budget.target_relative_error *
                                      std::max({irradiance.x, irradiance.y, irradiance.z})));
            if (reading < target) break;
        }
    }
    IrradianceSample result;
    result.irradiance = irradiance;
    result.standard_error = error;
    result.rays = int(rays);
    result.samples = int(points * replicate_count);
    return result;
}

glm::vec3 camera_ray_direction(const Camera& camera, const RenderSettings& settings, float x,
                               float y) {
    // As camera_position_at() in gbuffer_encoding.glsl: ndc from the pixel
    // centre over the internal size, scaled by 1 / P00 and 1 / P11.
    const FrameLayout layout = frame_layout(settings);
    const glm::mat4 projection = guard_band_projection(camera, settings);
    const glm::vec2 ray_scale{1.0f / projection[0][0], 1.0f / projection[1][1]};
    const glm::vec2 ndc =
        glm::vec2(x, y) *
            glm::vec2(1.0f / float(layout.internal_width), 1.0f / float(layout.internal_height)) *
            2.0f -
        1.0f;
    return {ndc * ray_scale, -1.0f};
}

LayerClassifier layer_classifier(const RayScene& scene, const Camera& camera,
                                 const RenderSettings& render) {
    const FrameLayout layout = frame_layout(render);
    const int w = layout.internal_width, h = layout.internal_height;
    const glm::mat4 view = camera_view_matrix(camera);
    const glm::vec3 eye = glm::vec3(glm::inverse(view)[3]);
    const glm::mat4 projection = guard_band_projection(camera, render);
    const glm::vec2 ray_scale{1.0f / projection[0][0], 1.0f / projection[1][1]};
    const float near_plane = camera.near_plane, separation = render.min_separation;
    return [&scene, view, eye, ray_scale, w, h, near_plane, separation](glm::vec3 world) -> int {
        const glm::vec3 c = glm::vec3(view * glm::vec4(world, 1.0f));
        const float depth = -c.z;
        if (!(depth >= near_plane)) return -1;
        // Inside the guard-banded frame (the layers exist nowhere else).
        const glm::vec2 ndc = glm::vec2(c.x, c.y) / (depth * ray_scale);
        const float fx = (ndc.x * 0.5f + 0.5f) * float(w), fy = (ndc.y * 0.5f + 0.5f) * float(h);
        if (!(fx >= 0.0f && fy >= 0.0f && fx < float(w) && fy < float(h))) return -1;
        // The camera ray through the point, of unit depth as in the peel, so
        // distances along it are linear depths.
        const glm::vec3 direction = (world - eye) / depth;
        // The point and the ray's hit carry float error of the point's
        // coordinates and of its depth; a surface this close in depth is the
        // same surface.
        const float tolerance = 1e-4f * depth + surface_offset(world, 0.0f);
        const RayScene::Hit first = scene.intersect_front(eye, direction, near_plane, 1e30f);
        if (!first.hit) return -1;
        if (std::abs(first.distance - depth) <= tolerance) return 0;
        if (depth < first.distance) return -1;  // a face turned away from the camera
        const RayScene::Hit second =
            scene.intersect_front(eye, direction, first.distance + separation, 1e30f);
        if (second.hit && std::abs(second.distance - depth) <= tolerance) return 1;
        return -1;
    };
}

ReferenceImages render_reference(const RayScene& scene, const Camera& camera,
                                 const ReferenceSettings& settings) {
    const RenderSettings& render = settings.render;
    const FrameLayout layout = frame_layout(render);
    const int w = layout.internal_width, h = layout.internal_height;
    const std::size_t pixels = std::size_t(w) * std::size_t(h);
    const glm::mat4 view = camera_view_matrix(camera);
    const glm::mat4 camera_to_world = glm::inverse(view);
    const glm::vec3 eye = glm::vec3(camera_to_world[3]);
    const glm::mat4 projection = guard_band_projection(camera, render);
    const glm::vec2 ray_scale{1.0f / projection[0][0], 1.0f / projection[1][1]};

    auto image = [&](int channels, float fill) {
        FloatImage result;
        result.width = w;
        result.height = h;
        result.channels = channels;
        result.pixels.assign(pixels * std::size_t(channels), fill);
        return result;
    };
    ReferenceImages out;
    out.depth_layer0 = image(1, 0.0f);
    out.depth_layer1 = image(1, 0.0f);
    out.ambient_visibility = image(1, 1.0f);
    out.hit_visibility = image(1, 1.0f);
    out.occlusion_split = image(3, 0.0f);
    out.standard_error = image(1, 0.0f);
    out.rays = image(1, 0.0f);
    if (settings.irradiance) {
        out.irradiance = image(3, 0.0f);
        out.irradiance_standard_error = image(3, 0.0f);
        out.irradiance_rays = image(1, 0.0f);
        out.direct_radiance = image(3, 0.0f);
    }
    std::vector<glm::vec3> positions(pixels), normals(pixels);
    std::vector<RayScene::Hit> first_hits(pixels);

    // More workers than rows would idle; the count is also what the system
    // grants: a thread that cannot be created leaves the work to the others.
    const int thread_count =
        std::min(h, settings.threads > 0 ? settings.threads
                                         : int(std::max(1u, std::thread::hardware_concurrency())));
    auto parallel_rows = [&](auto&& row_work, bool report) {
        std::atomic<int> next_row{0};
        std::atomic<long long> done{0};
        std::vector<std::thread> workers;
        auto work = [&] {
            for (int y = next_row++; y < h; y = next_row++) {
                row_work(y);
                done += w;
            }
        };
        for (int i = 0; i < thread_count; ++i) {
            try {
                workers.emplace_back(work);
            } catch (const std::system_error&) {
                if (workers.empty()) throw;
                break;
            }
        }
        if (report && settings.progress) {
            while (done.load() < (long long)pixels) {
                settings.progress(done.load(), (long long)pixels);
                std::this_thread::sleep_for(std::chrono::milliseconds(200));
            }
            settings.progress((long long)pixels, (long long)pixels);
        }
        for (auto& worker : workers) worker.join();
    };

    // Camera rays: layer 0 is the nearest front face past the near plane;
    // layer 1 the nearest front face at least dz behind it (the peel).
    // With a camera-space direction of unit depth, t is linear depth.
    parallel_rows(
        [&](int y) {
            for (int x = 0; x < w; ++x) {
                const std::size_t i = std::size_t(y) * w + x;
                const glm::vec2 ndc =
                    (glm::vec2(float(x), float(y)) + 0.5f) / glm::vec2(float(w), float(h)) * 2.0f -
                    1.0f;
                const glm::vec3 direction_camera(ndc * ray_scale, -1.0f);
                const glm::vec3 direction =
                    glm::vec3(camera_to_world * glm::vec4(direction_camera, 0.0f));
                const RayScene::Hit first =
                    scene.intersect_front(eye, direction, camera.near_plane, 1e30f);
                if (!first.hit) continue;
                out.depth_layer0.pixels[i] = first.distance;
                positions[i] = eye + direction * first.distance;
                normals[i] = first.normal;
                first_hits[i] = first;
                const RayScene::Hit second = scene.intersect_front(
                    eye, direction, first.distance + render.min_separation, 1e30f);
                if (second.hit) out.depth_layer1.pixels[i] = second.distance;
            }
        },
        false);

    const LayerClassifier classify = layer_classifier(scene, camera, render);

    if (settings.ambient_visibility)
        parallel_rows(
            [&](int y) {
                for (int x = 0; x < w; ++x) {
                    const std::size_t i = std::size_t(y) * w + x;
                    if (out.depth_layer0.pixels[i] <= 0.0f) continue;
                    const AoSample s = ambient_visibility_at(
                        scene, positions[i], normals[i], render.ao.radius, settings.rays,
                        stream_seed(settings.seed, i), classify);
                    out.ambient_visibility.pixels[i] = float(s.visibility);
                    out.hit_visibility.pixels[i] = float(s.hit_visibility);
                    out.standard_error.pixels[i] = float(s.standard_error);
                    out.rays.pixels[i] = float(s.rays);
                    out.occlusion_split.pixels[3 * i + 0] = float(s.occlusion_layer0);
                    out.occlusion_split.pixels[3 * i + 1] = float(s.occlusion_layer1);
                    out.occlusion_split.pixels[3 * i + 2] = float(s.occlusion_neither);
                }
            },
            true);

    // Irradiance streams are offset by the pixel count, so they share no
    // random numbers with the ambient visibility of any pixel.
    if (settings.irradiance)
        parallel_rows(
            [&](int y) {
                for (int x = 0; x < w; ++x) {
                    const std::size_t i = std::size_t(y) * w + x;
                    if (out.depth_layer0.pixels[i] <= 0.0f) continue;
                    const IrradianceSample s = irradiance_at(
                        scene, positions[i], normals[i], settings.radiosity_radius,
                        settings.irradiance_rays, stream_seed(settings.seed, pixels + i));
                    for (int c = 0; c < 3; ++c) {
                        out.irradiance.pixels[3 * i + c] = float(s.irradiance[c]);
                        out.irradiance_standard_error.pixels[3 * i + c] =
                            float(s.standard_error[c]);
                    }
                    out.irradiance_rays.pixels[i] = float(s.rays);
                    const glm::dvec3 direct =
                        direct_outgoing_radiance(scene, first_hits[i], positions[i]) -
                        glm::dvec3(scene.surface(first_hits[i]).emissive);
                    for (int c = 0; c < 3; ++c)
                        out.direct_radiance.pixels[3 * i + c] = float(direct[c]);
                }
            },
            true);
    return out;
}

}  // namespace deepgi
