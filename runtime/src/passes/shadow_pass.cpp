// Depth from the key light, for the direct-light pass's PCF lookups.
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

class ShadowPass final : public Pass {
public:
    explicit ShadowPass(const ShaderLoader& loader)
        : program_(loader.build_program({{GL_VERTEX_SHADER, "shadow.vert"}})) {}

    std::string_view name() const override { return "shadow"; }

    void resize(FrameResources& frame) override {
        const int size = frame.settings->shadow_map_size;
        frame.shadow = shadow_projection(*frame.scene, size);
        if (size == size_) return;
        size_ = size;
        depth_ = gl::create_texture_2d(GL_DEPTH_COMPONENT32F, size, size);
        label_texture(depth_, name(), "depth");
        glTextureParameteri(depth_.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTextureParameteri(depth_.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
        glTextureParameteri(depth_.get(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
        glTextureParameteri(depth_.get(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
        framebuffer_ = gl::create_framebuffer();
        glNamedFramebufferTexture(framebuffer_.get(), GL_DEPTH_ATTACHMENT, depth_.get(), 0);
        glNamedFramebufferDrawBuffer(framebuffer_.get(), GL_NONE);
        gl::check_framebuffer(framebuffer_, "shadow");
    }

    void run(FrameResources& frame) override {
        glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.get());
        glViewport(0, 0, size_, size_);
        glEnable(GL_DEPTH_TEST);
        glDepthFunc(GL_LESS);
        glDepthMask(GL_TRUE);
        // Single-sided walls and roofs must still block the light from behind.
        glDisable(GL_CULL_FACE);
        glEnable(GL_POLYGON_OFFSET_FILL);
        glPolygonOffset(1.5f, 2.0f);
        const float far_depth = 1.0f;
        glClearNamedFramebufferfv(framebuffer_.get(), GL_DEPTH, 0, &far_depth);
        glUseProgram(program_.get());
        glProgramUniformMatrix4fv(program_.get(), DEEPGI_UNIFORM_LIGHT_VIEW_PROJECTION, 1, GL_FALSE,
                                  &frame.shadow.light_view_projection[0][0]);
        draw_scene(*frame.scene_gpu, 0);
        glDisable(GL_POLYGON_OFFSET_FILL);
        frame.publish("shadow.depth", depth_.get());
    }

    std::vector<PassOutput> outputs(const FrameResources&) const override {
        return {{.name = "shadow-depth",
                 .texture = depth_.get(),
                 .width = size_,
                 .height = size_,
                 .channels = 1,
                 .decode = OutputDecode::shadow_depth}};
    }

private:
    gl::Program program_;
    gl::Texture depth_;  // DEPTH_COMPONENT32F, compare mode on for PCF
    gl::Framebuffer framebuffer_;
    int size_ = 0;
};

}  // namespace

ShadowProjection shadow_projection(const Scene& scene, int size) {
    ShadowProjection result;
    result.size = size;
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
        result.light_view_projection = projection * view;
        result.normal_offset = 1.5f * (2.0f * radius / float(size));
    } else {
        const float fov =
            std::min(2.0f * light.outer_cone + glm::radians(10.0f), glm::radians(160.0f));
        const glm::mat4 view =
            glm::lookAt(light.position, light.position + direction, up_vector_for(direction));
        const glm::mat4 projection =
            glm::perspectiveRH_ZO(fov, 1.0f, 0.01f * radius, 4.0f * radius);
        result.light_view_projection = projection * view;
        result.normal_offset = 1.5f * (2.0f * radius * std::tan(fov * 0.5f) / float(size));
    }
    return result;
}

std::unique_ptr<Pass> make_shadow_pass(const ShaderLoader& loader, const Scene&) {
    return std::make_unique<ShadowPass>(loader);
}

}  // namespace deepgi
