#pragma once
// The scene as the passes draw it: one vertex and index buffer, one batch per material.
#include "deepgi/gl_objects.hpp"
#include "deepgi/scene.hpp"

namespace deepgi {

struct SceneGpu {
    gl::VertexArray vertex_array;
    gl::Buffer vertices;
    gl::Buffer indices;
    std::vector<DrawBatch> batches;
    std::vector<Material> materials;
    std::vector<gl::Texture> textures;
    // Per material, how its base colour and emissive textures are read.
    std::vector<gl::Sampler> base_colour_samplers;
    std::vector<gl::Sampler> emissive_samplers;
};

SceneGpu upload_scene(const Scene& scene);

// Draws every batch; `per_material` sets material uniforms first when non-null.
void draw_scene(const SceneGpu& scene, GLuint program_for_materials);

// Depth-only drawing that honours glTF alpha masks: opaque batches with
// `opaque_program`, then alpha-masked ones with `masked_program`, whose
// fragment shader runs the alpha test (alpha_mask.glsl) on the material
// uniforms set here. Only masked batches pay for the test's texture read.
void draw_scene_depth(const SceneGpu& scene, GLuint opaque_program, GLuint masked_program);

// Draws one batch's triangles; the caller binds the vertex array and sets uniforms.
void draw_batch(const DrawBatch& batch);

}  // namespace deepgi
