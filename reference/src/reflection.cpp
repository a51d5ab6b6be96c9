// The mirror reflection at one layer-0 point (docs/reflections.md, "Against
// the ray tracer"): the reflected ray traced exactly, its hit shaded with the
// model the renderer's reflection pass applies to the texel it hits. A hit on
// another mirror is followed: the mirror sends its emission plus its
// reflectance times what its own reflected ray sees, up to
// kMaxMirrorBounces mirrors after the first, past which the last mirror is
// shaded as a diffuse surface of its base colour.
#include "deepgi/reference.hpp"
#include "sampling.hpp"

namespace deepgi {

using namespace reference_sampling;

namespace {

// What one reflected ray from `origin` along the unit `direction` sees: the
// first surface either side, shaded; `hit` is that first surface.
glm::dvec3 traced_radiance(const RayScene& scene, glm::vec3 origin, glm::vec3 direction,
                           float radiosity_radius, bool environment, float mirror_roughness,
                           int mirrors_left, const IrradianceRayBudget& budget, std::uint64_t seed,
                           RayScene::Hit& hit, int& rays, int& bounces) {
    hit = scene.intersect(origin, direction, 0.0f, 1e30f);
    if (!hit.hit) return environment ? scene.environment_radiance(direction) : glm::dvec3(0.0);
    // A back face: the ray is inside a solid (or behind an open mesh), where
    // the directly lit scene sends nothing towards it.
    if (glm::dot(hit.normal, direction) >= 0.0f) return glm::dvec3(0.0);
    const glm::vec3 y = origin + direction * hit.distance;
    const RayScene::Surface surface = scene.surface(hit);
    if (mirrors_left > 0 && scene.mirror(hit.primitive, mirror_roughness)) {
        // As compose shades a mirror pixel: its emission plus its
        // reflectance (base colour) times the reflected radiance, along the
        // reflection about its shading normal, leaving on the side it came from.
        ++bounces;
        const glm::vec3 next = glm::normalize(glm::reflect(direction, surface.shading_normal));
        const glm::vec3 next_origin = y + hit.normal * surface_offset(y, scene.scale());
        RayScene::Hit next_hit;
        const glm::dvec3 seen = traced_radiance(scene, next_origin, next, radiosity_radius,
                                                environment, mirror_roughness, mirrors_left - 1,
                                                budget, seed, next_hit, rays, bounces);
        return glm::dvec3(surface.emissive) + glm::dvec3(surface.albedo) * seen;
    }
    // direct_outgoing_radiance() holds the key light and the emission.
    glm::dvec3 radiance = direct_outgoing_radiance(scene, hit, y);
    if (surface.albedo != glm::vec3(0.0f)) {
        const IrradianceSample e =
            irradiance_at(scene, y, hit.normal, radiosity_radius, budget, seed);
        radiance += glm::dvec3(surface.albedo) / pi * e.irradiance;
        rays += e.rays;
    }
    return radiance;
}

}  // namespace

ReflectionSample mirror_reflection_at(const RayScene& scene, glm::vec3 eye, glm::vec3 position,
                                      glm::vec3 geometric_normal, glm::vec3 shading_normal,
                                      float radiosity_radius, bool environment,
                                      const IrradianceRayBudget& budget, std::uint64_t seed,
                                      float mirror_roughness) {
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
    result.radiance = traced_radiance(scene, origin, result.direction, radiosity_radius,
                                      environment, mirror_roughness, kMaxMirrorBounces, budget,
                                      seed, result.hit, result.rays, result.mirror_bounces);
    return result;
}

}  // namespace deepgi
