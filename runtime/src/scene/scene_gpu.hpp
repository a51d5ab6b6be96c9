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

// Where a program that shades materials samples their textures: the numbers
// its shader declares, given by the pass that draws with it.
struct MaterialTextureBindings {
    GLuint base_colour = 0;
    GLuint emissive = 0;
};

// Draws every batch; when `program_for_materials` is non-zero, sets its
// material uniforms first and binds the material's textures at `bindings`.
// `instances` > 1 draws each batch that many times in one instanced call
// (gl_InstanceID), e.g. one per array layer chosen in the vertex shader.
void draw_scene(const SceneGpu& scene, GLuint program_for_materials,
                MaterialTextureBindings bindings, int instances = 1);

// Depth-only drawing that honours glTF alpha masks: opaque batches with
// `opaque_program`, then alpha-masked ones with `masked_program`, whose
// fragment shader runs the alpha test (alpha_mask.glsl) on the material
// uniforms set here, its base-colour texture bound at `base_colour_binding`.
// Only masked batches pay for the test's texture read.
void draw_scene_depth(const SceneGpu& scene, GLuint opaque_program, GLuint masked_program,
                      GLuint base_colour_binding);

// Draws one batch's triangles (`instances` times, instanced, when more than
// one); the caller binds the vertex array and sets uniforms.
void draw_batch(const DrawBatch& batch, int instances = 1);

}  // namespace deepgi
