#include "scene/scene_gpu.hpp"

#include "shader_shared.hpp"

#include <cstddef>

namespace deepgi {

SceneGpu upload_scene(const Scene& scene) {
    SceneGpu gpu;
    gpu.vertices = gl::create_buffer();
    gpu.indices = gl::create_buffer();
    glNamedBufferStorage(gpu.vertices.get(), GLsizeiptr(scene.vertices.size() * sizeof(Vertex)),
                         scene.vertices.data(), 0);
    glNamedBufferStorage(gpu.indices.get(),
                         GLsizeiptr(scene.indices.size() * sizeof(std::uint32_t)),
                         scene.indices.data(), 0);
    gpu.vertex_array = gl::create_vertex_array();
    const GLuint vao = gpu.vertex_array.get();
    glVertexArrayVertexBuffer(vao, 0, gpu.vertices.get(), 0, sizeof(Vertex));
    glVertexArrayElementBuffer(vao, gpu.indices.get());
    const struct {
        GLuint location;
        GLint size;
        GLuint offset;
    } attributes[] = {{DEEPGI_ATTRIBUTE_POSITION, 3, offsetof(Vertex, position)},
                      {DEEPGI_ATTRIBUTE_NORMAL, 3, offsetof(Vertex, normal)},
                      {DEEPGI_ATTRIBUTE_UV, 2, offsetof(Vertex, uv)},
                      {DEEPGI_ATTRIBUTE_COLOUR, 4, offsetof(Vertex, colour)}};
    for (const auto& attribute : attributes) {
        glEnableVertexArrayAttrib(vao, attribute.location);
        glVertexArrayAttribFormat(vao, attribute.location, attribute.size, GL_FLOAT, GL_FALSE,
                                  attribute.offset);
        glVertexArrayAttribBinding(vao, attribute.location, 0);
    }
    gpu.batches = scene.batches;
    gpu.materials = scene.materials;
    for (const auto& image : scene.textures) {
        gl::Texture texture = gl::create_texture(GL_TEXTURE_2D);
        int levels = 1;
        while ((std::max(image.width, image.height) >> levels) > 0) ++levels;
        glTextureStorage2D(texture.get(), levels, GL_SRGB8_ALPHA8, image.width, image.height);
        // glTF rows run top to bottom with v = 0 at the top, matching GL's first row at v = 0.
        glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
        glTextureSubImage2D(texture.get(), 0, 0, 0, image.width, image.height, GL_RGBA,
                            GL_UNSIGNED_BYTE, image.rgba8.data());
        glGenerateTextureMipmap(texture.get());
        gpu.textures.push_back(std::move(texture));
    }
    // Filters and wraps live in sampler objects: one image may be read
    // through different glTF samplers by different materials.
    auto make_sampler = [](const TextureSampler& source) {
        gl::Sampler sampler = gl::create_sampler();
        glSamplerParameteri(sampler.get(), GL_TEXTURE_MAG_FILTER, source.mag_filter);
        glSamplerParameteri(sampler.get(), GL_TEXTURE_MIN_FILTER, source.min_filter);
        glSamplerParameteri(sampler.get(), GL_TEXTURE_WRAP_S, source.wrap_s);
        glSamplerParameteri(sampler.get(), GL_TEXTURE_WRAP_T, source.wrap_t);
        return sampler;
    };
    for (const auto& material : scene.materials) {
        gpu.base_colour_samplers.push_back(make_sampler(material.base_colour_sampler));
        gpu.emissive_samplers.push_back(make_sampler(material.emissive_sampler));
    }
    return gpu;
}

void draw_batch(const DrawBatch& batch, int instances) {
    const void* first =
        reinterpret_cast<const void*>(std::uintptr_t(batch.first_index) * sizeof(std::uint32_t));
    if (instances == 1)
        glDrawElements(GL_TRIANGLES, GLsizei(batch.index_count), GL_UNSIGNED_INT, first);
    else
        glDrawElementsInstanced(GL_TRIANGLES, GLsizei(batch.index_count), GL_UNSIGNED_INT, first,
                                instances);
}

namespace {

// Material m's base colour as gbuffer.frag and alpha_mask.glsl read it: the
// factor, whether there is a texture, and the texture with its sampler.
void set_base_colour(const SceneGpu& scene, std::size_t m, GLuint program, GLuint binding) {
    const Material& material = scene.materials[m];
    glProgramUniform4fv(program, DEEPGI_UNIFORM_BASE_COLOUR_FACTOR, 1, &material.base_colour.x);
    const bool textured = material.base_colour_texture >= 0;
    glProgramUniform1i(program, DEEPGI_UNIFORM_HAS_BASE_COLOUR_TEXTURE, textured ? 1 : 0);
    if (textured) {
        glBindTextureUnit(binding, scene.textures[std::size_t(material.base_colour_texture)].get());
        glBindSampler(binding, scene.base_colour_samplers[m].get());
    }
}

}  // namespace

void draw_scene(const SceneGpu& scene, GLuint program_for_materials,
                MaterialTextureBindings bindings, int instances) {
    glBindVertexArray(scene.vertex_array.get());
    for (const auto& batch : scene.batches) {
        if (program_for_materials != 0) {
            const std::size_t m = std::size_t(batch.material);
            const Material& material = scene.materials[m];
            set_base_colour(scene, m, program_for_materials, bindings.base_colour);
            glProgramUniform3fv(program_for_materials, DEEPGI_UNIFORM_EMISSIVE_FACTOR, 1,
                                &material.emissive.x);
            const bool emissive_textured = material.emissive_texture >= 0;
            glProgramUniform1i(program_for_materials, DEEPGI_UNIFORM_HAS_EMISSIVE_TEXTURE,
                               emissive_textured ? 1 : 0);
            if (emissive_textured) {
                glBindTextureUnit(bindings.emissive,
                                  scene.textures[std::size_t(material.emissive_texture)].get());
                glBindSampler(bindings.emissive, scene.emissive_samplers[m].get());
            }
            glProgramUniform1f(program_for_materials, DEEPGI_UNIFORM_ALPHA_CUTOFF,
                               material.alpha_cutoff);
            glProgramUniform2f(program_for_materials, DEEPGI_UNIFORM_MATERIAL_SURFACE,
                               material.roughness, material.metallic);
        }
        draw_batch(batch, instances);
    }
    // Other passes read their textures with the textures' own parameters.
    if (program_for_materials != 0) {
        glBindSampler(bindings.base_colour, 0);
        glBindSampler(bindings.emissive, 0);
    }
}

void draw_scene_depth(const SceneGpu& scene, GLuint opaque_program, GLuint masked_program,
                      GLuint base_colour_binding) {
    const auto is_masked = [&](const DrawBatch& batch) {
        return scene.materials[std::size_t(batch.material)].alpha_cutoff >= 0.0f;
    };
    glBindVertexArray(scene.vertex_array.get());
    glUseProgram(opaque_program);
    for (const auto& batch : scene.batches)
        if (!is_masked(batch)) draw_batch(batch);
    glUseProgram(masked_program);
    for (const auto& batch : scene.batches) {
        if (!is_masked(batch)) continue;
        const std::size_t m = std::size_t(batch.material);
        set_base_colour(scene, m, masked_program, base_colour_binding);
        glProgramUniform1f(masked_program, DEEPGI_UNIFORM_ALPHA_CUTOFF,
                           scene.materials[m].alpha_cutoff);
        draw_batch(batch);
    }
    glBindSampler(base_colour_binding, 0);
}

}  // namespace deepgi
