#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace deepgi {

namespace {

glm::vec3 up_vector_for(glm::vec3 direction) {
    return std::abs(direction.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
}

}  // namespace

ShadowPass create_shadow_pass(const ShaderLoader& loader, const Scene& scene, int size) {
    ShadowPass pass;
    pass.size = size;
    pass.program = loader.build_program({{GL_VERTEX_SHADER, "shadow.vert"}});
    pass.depth = gl::create_texture_2d(GL_DEPTH_COMPONENT32F, size, size);
    glTextureParameteri(pass.depth.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(pass.depth.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(pass.depth.get(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(pass.depth.get(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    pass.framebuffer = gl::create_framebuffer();
    glNamedFramebufferTexture(pass.framebuffer.get(), GL_DEPTH_ATTACHMENT, pass.depth.get(), 0);
    glNamedFramebufferDrawBuffer(pass.framebuffer.get(), GL_NONE);
    gl::check_framebuffer(pass.framebuffer, "shadow");

    const KeyLight& light = scene.key_light;
    const glm::vec3 centre = (scene.bounds.min + scene.bounds.max) * 0.5f;
    const float radius = std::max(glm::length(scene.bounds.max - scene.bounds.min) * 0.5f, 1e-3f);
    const glm::vec3 direction = glm::normalize(light.direction);
    if (light.kind == LightKind::directional) {
        // An orthographic box around the scene's bounding sphere.
        const glm::vec3 eye = centre - direction * (2.0f * radius);
        const glm::mat4 view = glm::lookAt(eye, centre, up_vector_for(direction));
        const glm::mat4 projection =
            glm::orthoRH_ZO(-radius, radius, -radius, radius, 0.5f * radius, 3.5f * radius);
        pass.light_view_projection = projection * view;
        pass.normal_offset = 1.5f * (2.0f * radius / float(size));
    } else {
        const float fov =
            std::min(2.0f * light.outer_cone + glm::radians(10.0f), glm::radians(160.0f));
        const glm::mat4 view =
            glm::lookAt(light.position, light.position + direction, up_vector_for(direction));
        const glm::mat4 projection =
            glm::perspectiveRH_ZO(fov, 1.0f, 0.01f * radius, 4.0f * radius);
        pass.light_view_projection = projection * view;
        pass.normal_offset = 1.5f * (2.0f * radius * std::tan(fov * 0.5f) / float(size));
    }
    return pass;
}

void run_shadow_pass(const ShadowPass& pass, const SceneGpu& scene) {
    glBindFramebuffer(GL_FRAMEBUFFER, pass.framebuffer.get());
    glViewport(0, 0, pass.size, pass.size);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    // Single-sided walls and roofs must still block the light from behind.
    glDisable(GL_CULL_FACE);
    glEnable(GL_POLYGON_OFFSET_FILL);
    glPolygonOffset(1.5f, 2.0f);
    const float far_depth = 1.0f;
    glClearNamedFramebufferfv(pass.framebuffer.get(), GL_DEPTH, 0, &far_depth);
    glUseProgram(pass.program.get());
    glProgramUniformMatrix4fv(pass.program.get(), DEEPGI_UNIFORM_LIGHT_VIEW_PROJECTION, 1, GL_FALSE,
                              &pass.light_view_projection[0][0]);
    draw_scene(scene, 0);
    glDisable(GL_POLYGON_OFFSET_FILL);
}

}  // namespace deepgi
