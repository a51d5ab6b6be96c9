// The mirror reflection at one layer-0 point (docs/reflections.md, "Against
// the ray tracer"): the reflected ray traced exactly, its hit shaded with the
// model the renderer's reflection pass applies to the texel it hits.
#include "deepgi/reference.hpp"
#include "sampling.hpp"

namespace deepgi {

using namespace reference_sampling;

ReflectionSample mirror_reflection_at(const RayScene& scene, glm::vec3 eye, glm::vec3 position,
                                      glm::vec3 geometric_normal, glm::vec3 shading_normal,
                                      float radiosity_radius, bool environment,
                                      const IrradianceRayBudget& budget, std::uint64_t seed) {
    ReflectionSample result;
    // As reflection.frag: r = reflect(normalize(X), n) with the G-buffer's
    // (shading) normal, here in world space.
    const glm::vec3 d = glm::normalize(position - eye);
    result.direction = glm::normalize(glm::reflect(d, shading_normal));
    // Leave the mirror on the side the camera sees, so that the ray does not
    // hit the triangle it starts on.
    const glm::vec3 side =
        glm::dot(geometric_normal, d) < 0.0f ? geometric_normal : -geometric_normal;
    const glm::vec3 origin = position + side * surface_offset(position, scene.scale());
    result.hit = scene.intersect(origin, result.direction, 0.0f, 1e30f);
    if (!result.hit.hit) {
        if (environment) result.radiance = scene.environment_radiance(result.direction);
        return result;
    }
    // A back face: the ray is inside a solid (or behind an open mesh), where
    // the directly lit scene sends nothing towards it.
    if (glm::dot(result.hit.normal, result.direction) >= 0.0f) return result;
    const glm::vec3 y = origin + result.direction * result.hit.distance;
    const RayScene::Surface surface = scene.surface(result.hit);
    // direct_outgoing_radiance() holds the key light and the emission.
    result.radiance = direct_outgoing_radiance(scene, result.hit, y);
    if (surface.albedo != glm::vec3(0.0f)) {
        const IrradianceSample e =
            irradiance_at(scene, y, result.hit.normal, radiosity_radius, budget, seed);
        result.radiance += glm::dvec3(surface.albedo) / pi * e.irradiance;
        result.rays = e.rays;
    }
    return result;
}

}  // namespace deepgi
