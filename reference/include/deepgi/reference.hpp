#pragma once
// Ray-traced ground truth (Embree 3, CPU) for the deep SAO pass: the same
// camera, guard band and pixel grid as layer 0 of the deep G-buffer, and the
// ambient visibility that deep SAO estimates. No GL here; only the scene, the
// camera and the frame layout of the runtime. Definitions: docs/reference.md.
#include "deepgi/image_io.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"

#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <memory>

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
    };
    // Nearest hit in (t_near, t_far) on either side of a triangle.
    Hit intersect(glm::vec3 origin, glm::vec3 direction, float t_near, float t_far) const;
    // Nearest hit in (t_near, t_far) whose front faces the ray (dot(n, d) < 0),
    // as a rasteriser with back-face culling sees it.
    Hit intersect_front(glm::vec3 origin, glm::vec3 direction, float t_near, float t_far) const;
    // Scene extent, for offsets that scale with the scene.
    float scale() const { return scale_; }

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
    double standard_error = 0.0;  // of visibility: sqrt(sample variance / rays)
    // Occlusion (1 - AV) split by who could see the occluder; sums to 1 - AV.
    double occlusion_layer0 = 0.0;
    double occlusion_layer1 = 0.0;
    double occlusion_neither = 0.0;
    int rays = 0;
};

// Says which depth layer (0, 1) could see a world-space point, or -1.
using LayerClassifier = std::function<int(glm::vec3)>;

struct AoRayBudget {
    int min_rays = 1024;
    int max_rays = 65536;
    double target_error = 0.004;  // stop once the standard error is below this
    int batch = 256;
};

AoSample ambient_visibility_at(const RayScene& scene, glm::vec3 position, glm::vec3 normal,
                               float radius, const AoRayBudget& budget, std::uint64_t seed,
                               const LayerClassifier& classify = {});

struct ReferenceSettings {
    RenderSettings render;  // size, guard band, min_separation (dz), ao.radius
    AoRayBudget rays;
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
};

// The camera ray through the centre of internal pixel (x, y), exactly as the
// shaders reconstruct positions: camera space, unit-depth direction (z = -1).
glm::vec3 camera_ray_direction(const Camera& camera, const RenderSettings& settings, float x,
                               float y);

ReferenceImages render_reference(const RayScene& rays, const Camera& camera,
                                 const ReferenceSettings& settings);

}  // namespace deepgi
