#pragma once
// Ray-traced ground truth (Embree 3, CPU) for deep SAO and deep radiosity: the
// same camera, guard band and pixel grid as layer 0 of the deep G-buffer, the
// ambient visibility that deep SAO estimates, and the one-bounce irradiance
// that the radiosity gather estimates. No GL here; only the scene, the
// camera and the frame layout of the runtime. Definitions: docs/reference.md.
#include "deepgi/image_io.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

namespace deepgi {

// The triangles of a scene in an Embree BVH. Counter-clockwise triangles face
// the camera, as in the G-buffer pass (which culls back faces).
class RayScene {
public:
    explicit RayScene(const Scene& scene);
    ~RayScene();
    RayScene(const RayScene&) = delete;
    RayScene& operator=(const RayScene&) = delete;

    struct Hit {
        bool hit = false;
        float distance = 0.0f;   // along the (unit) direction
        glm::vec3 normal{0.0f};  // unit geometric normal, counter-clockwise side
        unsigned primitive = 0;
        glm::vec2 barycentric{0.0f};  // Embree's (u, v): weights of vertices 1 and 2
    };
    // Nearest hit in (t_near, t_far) on either side of a triangle.
    Hit intersect(glm::vec3 origin, glm::vec3 direction, float t_near, float t_far) const;
    // Nearest hit in (t_near, t_far) whose front faces the ray (dot(n, d) < 0),
    // as a rasteriser with back-face culling sees it.
    Hit intersect_front(glm::vec3 origin, glm::vec3 direction, float t_near, float t_far) const;
    // Whether anything lies in (t_near, t_far) along the ray (shadow rays).
    bool occluded(glm::vec3 origin, glm::vec3 direction, float t_near, float t_far) const;
    // Scene extent, for offsets that scale with the scene.
    float scale() const { return scale_; }

    // What the G-buffer would store at a hit: the interpolated vertex normal
    // (unit; the geometric normal where the vertices have none), the linear
    // albedo (base colour times the texture, nearest texel) and the emissive.
    struct Surface {
        glm::vec3 shading_normal{0.0f};
        glm::vec3 albedo{0.0f};
        glm::vec3 emissive{0.0f};
    };
    Surface surface(const Hit& hit) const;
    // The scene's key light (copied at construction).
    const KeyLight& key_light() const;
    // Whether triangle `primitive`'s material is a mirror under this
    // threshold: roughness at most `mirror_roughness`, metallic at least 0.5
    // (as the G-buffer pass decides; docs/reflections.md).
    bool mirror(unsigned primitive, float mirror_roughness) const;
    // Whether any triangle is a mirror under this threshold.
    bool has_mirrors(float mirror_roughness) const;
    // The planar surface triangle `primitive` belongs to: the lowest index of
    // the triangles of its material that lie in its plane (unit normal and
    // offset equal after rounding to 1e-4, the offset in units of the scene's
    // extent). A box face or a quad is one surface; a curved mesh has one
    // per triangle. -1 for an out-of-range primitive.
    int surface_id(unsigned primitive) const;
    // The radiance of the environment seen along a world-space direction, as
    // environment.glsl gives it to the reflections: the irradiance onto a
    // surface facing that way over pi (scene ambient and background).
    glm::dvec3 environment_radiance(glm::vec3 direction) const;

    // A triangle that emits (some channel of its emissive above 0, area above
    // 0), for sampling emitters directly. Its emission is uniform: surface()
    // reads the material's emissive factor and no emissive texture.
    struct Emitter {
        unsigned primitive = 0;
        glm::dvec3 p0{0.0}, edge1{0.0}, edge2{0.0};  // points p0 + s edge1 + t edge2
        glm::dvec3 normal{0.0};                      // unit, counter-clockwise side
        glm::dvec3 emissive{0.0};
        double area = 0.0;
        // Chance of being picked: power x area (power: mean emissive channel)
        // over the scene's total, so the density per unit area,
        // probability / area, is proportional to the emitter's power.
        double probability = 0.0;
    };
    const std::vector<Emitter>& emitters() const;
    // Index into emitters() of triangle `primitive`, or -1 if it does not emit.
    int emitter_index(unsigned primitive) const;
    // The emitter whose share of [0, 1) in the order of emitters() holds u,
    // so emitter i comes out with its probability.
    std::size_t pick_emitter(double u) const;
    // The same pick, and where u lies within the emitter's share, rescaled
    // to [0, 1): uniform and independent of the pick when u is uniform, so
    // one stratified coordinate both picks the emitter and places the point.
    std::size_t pick_emitter(double u, double& within) const;

private:
    struct State;
    std::unique_ptr<State> state_;
    float scale_ = 1.0f;
};

// Ambient visibility at a surface point X with normal n, radius r, falloff
// f(d) = max(0, 1 - d^2 / r^2) (the falloff of deep SAO's AO(X, Y)):
//     AV(X) = 1 - (1/pi) * integral over the hemisphere of f(d(w)) cos(theta) dw
// where d(w) is the distance to the first surface along w (f = 0 past r).
// "Hit" visibility uses f = 1 for any hit within r instead.
struct AoSample {
    double visibility = 1.0;      // AV, the falloff-weighted definition
    double hit_visibility = 1.0;  // 1 - P(hit within r) under cosine weighting
    double standard_error = 0.0;  // of visibility: the spread of the sets' means
    // Occlusion (1 - AV) split by who could see the occluder; sums to 1 - AV.
    double occlusion_layer0 = 0.0;
    double occlusion_layer1 = 0.0;
    double occlusion_neither = 0.0;
    int rays = 0;
};

// Says which depth layer (0, 1) could see a world-space point, or -1.
using LayerClassifier = std::function<int(glm::vec3)>;

// Directions are stratified in independent sets as for irradiance (see
// IrradianceSample); the standard error is the spread of the sets' means.
struct AoRayBudget {
    int min_rays = 1024;
    int max_rays = 65536;  // never passed: a round that might pass it is not started
    // Stop once error_margin x the standard error is below target_error; the
    // margin as IrradianceRayBudget::error_margin.
    double target_error = 0.004;
    double error_margin = 1.3;
    int replicates = 16;  // independently scrambled sets of directions, at least 2
    int batch = 256;      // rays between checks (rounded up to whole rounds of the sets)
};

AoSample ambient_visibility_at(const RayScene& scene, glm::vec3 position, glm::vec3 normal,
                               float radius, const AoRayBudget& budget, std::uint64_t seed,
                               const LayerClassifier& classify = {});

// One-bounce irradiance at a surface point X with normal n, radius r:
//     E(X) = integral over the hemisphere of L(y(w)) cos(theta) dw
// where y(w) is the first surface along w; L = 0 when y is farther than r,
// when nothing is hit, or when w reaches y's back face; otherwise
//     L(y) = albedo(y) / pi * E_key(y) * max(0, n_s(y) . l) * V(y) + emissive(y)
// the outgoing radiance of the directly lit scene: the key light as
// lighting.glsl models it (directional, or a spot with 1/d^2 and the
// smoothstep cone), n_s the shading normal, and V a shadow ray to the light
// (exact, where the renderer filters a shadow map). This is what deep
// radiosity's B(Y) holds with boost 1, rho_prop 0 and no clamp.
//
// Estimator: each sample is one cosine-weighted direction (pdf cos / pi) and,
// when the scene has emitters, one point on an emitter (next-event
// estimation: a triangle picked by power x area, a uniform point on it, a
// shadow ray from X). The reflected key light comes from the cosine
// direction alone; the emissive term from both, combined by multiple
// importance sampling with the power heuristic, so a small bright emitter is
// found by the technique that finds it best. Emitter points obey the
// definition too: nothing beyond r, nothing from a back face, nothing
// hidden. Without emitters this is the plain cosine estimator E = pi mean(L).
//
// Sampling is stratified in independent replicates: the samples come in
// `replicates` sets, each the same Sobol (0, 2)-sequence under its own random
// nested scramble, one for the direction square and one for the emitter
// square (whose first coordinate picks the triangle and, rescaled, places
// the point). Each scrambled point is uniform, so every set's mean is
// unbiased; the sets are independent, so the standard error is the spread of
// the set means, sqrt(sum (m_k - E)^2 / (K (K - 1))) per channel over K sets.
// All sets hold the same number of samples, E is the mean of them all.
struct IrradianceSample {
    glm::dvec3 irradiance{0.0};
    glm::dvec3 standard_error{0.0};
    int rays = 0;     // rays from X: cosine directions and emitter shadow rays
    int samples = 0;  // cosine directions (each with its emitter point, if any)
    // E split by who could see the surface the light leaves (the classifier
    // given to irradiance_at(), as the occlusion split of AoSample): layer 0,
    // layer 1, neither. The same samples as `irradiance`, so the three sum to
    // it up to rounding; without a classifier all of it is in [2].
    glm::dvec3 by_layer[3] = {glm::dvec3(0.0), glm::dvec3(0.0), glm::dvec3(0.0)};
};

// Counted in rays from X: a cosine direction is one ray, an emitter point one
// more when it passes the radius and facing tests (the others cost no ray).
// Without emitters, rays and samples are the same.
struct IrradianceRayBudget {
    int min_rays = 1024;
    // Neither cap is passed: a round of samples that might pass it is not
    // started. A pixel whose error (times error_margin) is still at or
    // above largest_error at max_rays goes on up to ceiling_max_rays.
    int max_rays = 16384;
    int ceiling_max_rays = 65536;
    // Stop, checked after each batch of samples once min_rays are spent, when
    // error_margin x every channel's standard error is below
    // min(largest_error, max(target_absolute_error,
    //                        target_relative_error * largest channel of E)).
    double target_relative_error = 0.01;
    double target_absolute_error = 0.002;
    double largest_error = 0.005;
    // The standard error comes from `replicates` independent estimates, so
    // it is itself uncertain (about 1 / sqrt(2 (replicates - 1)), 18% for
    // 16); stopping at the first reading below the target favours low
    // readings (by about 1.25x), so the reading must be this much below it
    // for the actual error to be below the target.
    double error_margin = 1.3;
    int replicates = 16;  // independently scrambled point sets, at least 2
    int batch = 256;      // samples between checks (rounded up to whole rounds of the sets)
};

// The radiance the directly lit scene sends from `position` on the surface
// of `hit` (L(y) above, without the radius and facing conditions).
glm::dvec3 direct_outgoing_radiance(const RayScene& scene, const RayScene::Hit& hit,
                                    glm::vec3 position);

// With `bounces` K > 1, E_K instead: the same integral of L_K, where
//     L_K(y) = L_1(y) + albedo(y) / pi * E_(K-1)(y),   E_0 = 0,
// each E_k(y) over the hemisphere of y's geometric normal with the same
// radius window and front faces only; L_1 is L above. This is deep
// radiosity's B(Y) after K frames of rho_prop 1 (boost 1, no clamp), whose
// E_prev is last frame's E. The bounces past the first are one
// cosine-weighted path per sample (key light and emissive at each vertex,
// no emitter sampling there), with independent random directions per set,
// so the sets stay independent and the standard error stays honest. K = 1
// is the estimator above, draw for draw. Each further bounce is one more
// ray, counted against the caps.
//
// With `classify`, by_layer splits E by the layer that holds the surface the
// light leaves: the cosine ray's first surface y (all of L_K(y)) or the
// emitter point. The classifier traces no ray of the estimate and draws no
// random number, so E is the same with it or without.
IrradianceSample irradiance_at(const RayScene& scene, glm::vec3 position, glm::vec3 normal,
                               float radius, const IrradianceRayBudget& budget, std::uint64_t seed,
                               int bounces = 1, const LayerClassifier& classify = {});

// The mirror reflection at a layer-0 point X of a mirror (docs/reflections.md,
// "Against the ray tracer"): the ray leaves X along r = reflect(d, n_s), d
// the unit camera ray to X and n_s the shading normal (what the G-buffer
// stores), and its first surface y, either side, is shaded as the renderer
// shades a hit: L(y) = direct light (exact shadow ray) + emissive + albedo /
// pi * E(y), E the one-bounce irradiance of irradiance_at() at y over the
// radiosity radius. A back face gives 0 (inside a solid); a miss gives the
// environment's radiance along r. When y is itself a mirror (under
// `mirror_roughness`), L(y) = emissive + reflectance * the radiance its own
// reflected ray brings, followed through up to kMaxMirrorBounces mirrors
// after the first; a mirror past that is shaded as a diffuse surface.
constexpr int kMaxMirrorBounces = 3;

struct ReflectionSample {
    RayScene::Hit hit;          // the reflected ray's first surface (hit = false: none)
    glm::vec3 direction{0.0f};  // r, unit
    glm::dvec3 radiance{0.0};   // RGB reflected radiance (before the mirror's reflectance)
    int rays = 0;               // irradiance rays at the surface shaded
    int mirror_bounces = 0;     // further mirrors the ray was reflected by (0 to kMaxMirrorBounces)
};

ReflectionSample mirror_reflection_at(const RayScene& scene, glm::vec3 eye, glm::vec3 position,
                                      glm::vec3 geometric_normal, glm::vec3 shading_normal,
                                      float radiosity_radius, bool environment,
                                      const IrradianceRayBudget& budget, std::uint64_t seed,
                                      float mirror_roughness);

struct ReferenceSettings {
    RenderSettings render;  // size, guard band, min_separation (dz), ao.radius
    AoRayBudget rays;
    bool ambient_visibility = true;  // trace AO
    bool irradiance = false;         // trace one-bounce irradiance
    float radiosity_radius = 1.0f;   // m, as deepgi --radiosity-radius
    int bounces = 1;                 // K of irradiance_at: E_K instead of E_1
    IrradianceRayBudget irradiance_rays;
    // Trace the mirror reflection of every mirror pixel of layer 0 (under
    // render.mirror_roughness); a scene without mirrors traces nothing and
    // leaves the reflection images empty. Hit irradiance uses irradiance_rays.
    // Off by default, so callers that measure AO or E alone pay nothing for
    // mirrors; `deepgi reference` turns it on.
    bool reflections = false;
    std::uint64_t seed = 1;
    int threads = 0;  // 0: all hardware threads
    // Called with (pixels done, pixels total) from the calling thread.
    std::function<void(long long, long long)> progress;
};

// Every image covers the guard-banded internal buffer, rows bottom to top
// (the pixel grid of the G-buffer), so it lines up with `deepgi --dump`.
struct ReferenceImages {
    FloatImage depth_layer0;        // linear camera depth (m), 0 where nothing is hit
    FloatImage depth_layer1;        // nearest front face at least dz behind layer 0
    FloatImage ambient_visibility;  // AV with the falloff (1 on sky)
    FloatImage hit_visibility;      // 1 - P(hit within r)
    FloatImage occlusion_split;     // RGB: occluders seen by layer 0, layer 1, neither
    FloatImage standard_error;      // Monte Carlo standard error of AV
    FloatImage rays;                // rays spent per pixel
    // Only when ReferenceSettings::irradiance (empty otherwise):
    FloatImage irradiance;                 // RGB E_K, K = bounces (0 on sky)
    FloatImage irradiance_standard_error;  // RGB, per channel
    FloatImage irradiance_rays;            // rays spent per pixel
    // RGB parts of `irradiance` by who could see the surface the light
    // leaves (IrradianceSample::by_layer, layer_classifier()): layer 0,
    // layer 1, neither. They sum to `irradiance` up to float rounding.
    FloatImage irradiance_layer0;
    FloatImage irradiance_layer1;
    FloatImage irradiance_neither;
    // RGB direct light reflected at layer 0 (emissive excluded): what the
    // direct light pass writes, with an exact shadow ray for the shadow map.
    FloatImage direct_radiance;
    // Only when ReferenceSettings::reflections and the scene has a mirror
    // (empty otherwise):
    FloatImage reflection_radiance;  // RGB reflected radiance L(y) at mirror pixels, 0 elsewhere
    // Per pixel: the surface_id() of the reflected ray's hit (-1: none, the
    // environment; -2: not a mirror or no surface), its triangle (same
    // codes), and the hit distance from X (0 on a miss).
    FloatImage reflection_hit;
    // Per pixel: the surface_id() stored in layer 0 and in layer 1 (-1:
    // none), and 1 where layer 0 is a mirror, else 0; to map the renderer's
    // hit texel and layer to a surface.
    FloatImage surface_layers;
};

// The camera ray through the centre of internal pixel (x, y), exactly as the
// shaders reconstruct positions: camera space, unit-depth direction (z = -1).
glm::vec3 camera_ray_direction(const Camera& camera, const RenderSettings& settings, float x,
                               float y);

// Which layer of the deep G-buffer could store a point on a surface of the
// scene, by the definition the G-buffer is built with: follow the camera ray
// through the point itself; layer 0 is its nearest front face past the near
// plane, layer 1 its nearest front face at least min_separation (linear depth)
// behind that. The point is seen by the layer whose surface it is (same depth
// within float tolerance), and by neither when it lies on a face turned away
// from the camera, behind both layers, or outside the guard-banded frame.
// Exact, not a depth comparison with the rendered pixels: a face that the
// pixel grid samples edge-on (less than a pixel of it) is still seen, while
// the underside of a board seen edge-on is not. The classifier traces into
// `scene`, which must outlive it.
LayerClassifier layer_classifier(const RayScene& scene, const Camera& camera,
                                 const RenderSettings& render);

ReferenceImages render_reference(const RayScene& rays, const Camera& camera,
                                 const ReferenceSettings& settings);

}  // namespace deepgi
