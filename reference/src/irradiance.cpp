// Irradiance at one point (docs/reference.md): the key light reflected and
// the emissive surfaces seen, combined by multiple importance sampling, plus
// K - 1 further diffuse bounces by cosine-weighted paths, until the standard
// error is below the budget's targets.
#include "deepgi/reference.hpp"
#include "sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace deepgi {

using namespace reference_sampling;

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

// Slot of a classifier's answer in a split: layer 0, layer 1, neither.
int layer_slot(int layer) {
    return layer == 0 ? 0 : layer == 1 ? 1 : 2;
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
                               float radius, const IrradianceRayBudget& budget, std::uint64_t seed,
                               int bounces, const LayerClassifier& classify) {
    const glm::dvec3 n = glm::normalize(glm::dvec3(normal));
    glm::dvec3 t, b;
    tangent_frame(n, t, b);
    // Both techniques measure directions and distances from the offset origin.
    const glm::vec3 origin = position + glm::vec3(n) * surface_offset(position, radius);
    const glm::dvec3 origin_d(origin);
    const std::vector<RayScene::Emitter>& emitters = scene.emitters();
    const bool sample_emitters = !emitters.empty();
    long long rays = 0;

    // The light y passes on from bounces 2..K: one cosine-weighted path
    // from y, `more` bounces long, each step within the radius and onto a
    // front face, as the gather at y would see it. Returns an estimate of
    // E_more(y) / pi (E_0 = 0), so y's radiance gains albedo(y) times it.
    auto passed_on = [&](glm::vec3 y, glm::vec3 y_normal, int more, Random& random) {
        glm::dvec3 result(0.0), throughput(1.0);
        for (; more > 0; --more) {
            const glm::dvec3 ny(y_normal);
            glm::dvec3 ty, by;
            tangent_frame(ny, ty, by);
            constexpr double scale = 1.0 / 18446744073709551616.0;
            const double v1 = double(random.next()) * scale, v2 = double(random.next()) * scale;
            const double s = std::sqrt(v1), phi = 2.0 * pi * v2;
            const double z = std::sqrt(std::max(0.0, 1.0 - v1));
            const glm::vec3 w(ty * (s * std::cos(phi)) + by * (s * std::sin(phi)) + ny * z);
            const glm::vec3 from = y + y_normal * surface_offset(y, radius);
            ++rays;
            const RayScene::Hit hit = scene.intersect(from, w, 0.0f, radius);
            if (!hit.hit || !(glm::dot(hit.normal, w) < 0.0f)) break;
            const glm::vec3 next = from + w * hit.distance;
            const RayScene::Surface surface = scene.surface(hit);
            // Cosine sampling alone (pdf cos / pi): L(next) estimates E / pi.
            result += throughput * direct_outgoing_radiance(scene, hit, next);
            throughput *= glm::dvec3(surface.albedo);
            if (throughput == glm::dvec3(0.0)) break;
            y = next;
            y_normal = hit.normal;
        }
        return result;
    };

    // One sample's estimate of E / pi from a point of the direction square
    // and, when the scene has emitters, a point of the emitter square.
    // `parts` gains the same light by who holds the surface it comes from
    // (layer 0, layer 1, neither), when a classifier is given; the total is
    // summed as it always was, so E does not move by a bit.
    auto sample = [&](glm::dvec2 direction_point, glm::dvec2 emitter_point, Random& random,
                      glm::dvec3* parts) {
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
            // L_K(y) = L_1(y) + albedo(y) / pi * E_(K-1)(y).
            if (bounces > 1 && surface.albedo != glm::vec3(0.0f))
                value += glm::dvec3(surface.albedo) * passed_on(y, hit.normal, bounces - 1, random);
            // All of it leaves y, further bounces included: y's layer holds it.
            if (classify && value != glm::dvec3(0.0)) parts[layer_slot(classify(y))] += value;
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
                        const glm::dvec3 sent =
                            emitter.emissive *
                            (cos_x * p_emitter / (pi * (p_emitter * p_emitter + p_cos * p_cos)));
                        value += sent;
                        if (classify) parts[layer_slot(classify(glm::vec3(y)))] += sent;
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
        // Directions past the first bounce: plain random numbers, so the
        // sets stay independent (and one bounce draws none, unchanged).
        Random bounce_random{0};
        glm::dvec3 sum{0.0};  // of the samples' E / pi
        glm::dvec3 parts[3] = {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};  // sum, split
    };
    const int replicate_count = std::max(2, budget.replicates);
    std::vector<Replicate> replicates(static_cast<std::size_t>(replicate_count));
    Random random{seed};
    for (Replicate& r : replicates) {
        r.directions = {random.next(), random.next()};
        if (sample_emitters) r.emitter_points = {random.next(), random.next()};
    }
    if (bounces > 1)
        for (Replicate& r : replicates) r.bounce_random.state = random.next();
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
    const long long most_per_point =
        ((sample_emitters ? 2LL : 1LL) + std::max(0, bounces - 1)) * replicate_count;
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
                    sample_emitters ? r.emitter_points.point(index, reversed_y) : glm::dvec2(0.0),
                    r.bounce_random, r.parts);
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
    // The parts as E itself: pi times the mean of the set means, so they sum
    // to E up to rounding. Without a classifier all of E is "neither", as
    // the occlusion split of ambient_visibility_at().
    if (classify) {
        for (int k = 0; k < 3; ++k) {
            glm::dvec3 mean(0.0);
            for (const Replicate& r : replicates) mean += r.parts[k] / double(points);
            result.by_layer[k] = pi * (mean / double(replicate_count));
        }
    } else {
        result.by_layer[2] = irradiance;
    }
    return result;
}

}  // namespace deepgi
