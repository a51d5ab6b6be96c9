// Ambient visibility at one point by Monte Carlo (docs/reference.md): rays
// over the hemisphere, stratified with scrambled Sobol points, until the
// standard error is below the budget's target.
#include "deepgi/reference.hpp"
#include "sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace deepgi {

using namespace reference_sampling;

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

}  // namespace deepgi
