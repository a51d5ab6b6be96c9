// What the two files of rendered glTF scenes share (gltf_render_test.cpp:
// geometry and materials, gltf_lights_test.cpp: lights and shadows): the
// frame size and settings, a renderer run twice on a still camera and the
// outputs read back, and a pinhole projection worked out without the
// renderer's matrices. Files are built with gltf_builder.hpp and loaded from
// memory with crafted_gltf.hpp, whose PNG encoder the tests call as
// `test::encode_png`: the library's own `deepgi::encode_png` has the same
// signature, and the files' textures do not depend on the code under test.
#pragma once

#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "crafted_gltf.hpp"
#include "gltf_builder.hpp"

#include <glm/glm.hpp>

#include <cmath>

namespace deepgi::test {

constexpr int kWidth = 192;
constexpr int kHeight = 108;

inline RenderSettings settings_for(Generator generator) {
    RenderSettings settings;
    settings.width = kWidth;
    settings.height = kHeight;
    settings.generator = generator;
    settings.min_separation = 0.5f;
    settings.shadow_map_size = 512;
    return settings;
}

// A pinhole camera at `eye` looking down -Z (or +Z when `backwards`), field
// of view `yfov` over the viewport height: the internal (guard-banded)
// pixel a world point falls in, worked out without the renderer's matrices.
struct Pinhole {
    glm::vec3 eye;
    float yfov;
    bool backwards = false;
    glm::ivec2 pixel(glm::vec3 world, const FrameLayout& layout) const {
        glm::vec3 d = world - eye;
        if (backwards) d = glm::vec3(-d.x, d.y, -d.z);  // turned half about +Y
        const float t = std::tan(yfov / 2);
        const float aspect = float(kWidth) / float(kHeight);
        const float sx = (d.x / -d.z) / (t * aspect);  // -1..1 across the viewport
        const float sy = (d.y / -d.z) / t;
        return {layout.guard + int(std::floor((sx * 0.5f + 0.5f) * kWidth)),
                layout.guard + int(std::floor((sy * 0.5f + 0.5f) * kHeight))};
    }
};

struct Frame {
    FloatImage depth0, depth1, albedo0, albedo1, normal0, emissive0, light0;
    FrameLayout layout;
};

// Single-pass generators compare with the previous frame's layer 0, so a
// still camera renders twice.
inline Frame render(const Scene& scene, const Camera& camera,
                    Generator generator = Generator::peel) {
    Renderer renderer(scene, settings_for(generator), ShaderLoader::from_build_configuration());
    renderer.render(camera, CameraMotion::cut);
    renderer.render(camera);
    Frame frame;
    frame.depth0 = renderer.read_pass_output("gbuffer-depth-layer0");
    frame.depth1 = renderer.read_pass_output("gbuffer-depth-layer1");
    frame.albedo0 = renderer.read_pass_output("gbuffer-albedo-layer0");
    frame.albedo1 = renderer.read_pass_output("gbuffer-albedo-layer1");
    frame.normal0 = renderer.read_pass_output("gbuffer-normal-layer0");
    frame.emissive0 = renderer.read_pass_output("gbuffer-emissive-layer0");
    frame.light0 = renderer.read_pass_output("direct_light-radiance-layer0");
    frame.layout = renderer.layout();
    return frame;
}

}  // namespace deepgi::test
