// Depth from the key light, for the direct-light pass's PCF lookups.
#include "passes/passes.hpp"
#include "scene/scene_gpu.hpp"
#include "shader_shared.hpp"

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace deepgi {

namespace {

// Where shadow_mask.frag (alpha_mask.glsl) samples a masked material's base colour.
constexpr GLuint base_colour_binding = 9;
// shadow.vert's uniform location of the light's view-projection.
constexpr GLint light_view_projection_location = 3;

// The cube map faces in GL's order (+X, -X, +Y, -Y, +Z, -Z): each face's
// view direction and the up vector that makes its image the texture's
// (s, t) layout for that face.
struct CubeFace {
    glm::vec3 forward, up;
};
constexpr CubeFace kCubeFaces[6] = {{{1, 0, 0}, {0, -1, 0}}, {{-1, 0, 0}, {0, -1, 0}},
                                    {{0, 1, 0}, {0, 0, 1}},  {{0, -1, 0}, {0, 0, -1}},
                                    {{0, 0, 1}, {0, -1, 0}}, {{0, 0, -1}, {0, -1, 0}}};

gl::Texture create_depth_cube(int size) {
    gl::Texture cube = gl::create_texture(GL_TEXTURE_CUBE_MAP);
    glTextureStorage2D(cube.get(), 1, GL_DEPTH_COMPONENT32F, size, size);
    glTextureParameteri(cube.get(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(cube.get(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(cube.get(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(cube.get(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
    return cube;
}

// A point light's cube faces are half the shadow map's side: six of them
// at full size would take 1.5 GB at the largest --shadow-map-size, and a
// 90-degree face needs fewer texels than a map spanning a whole scene.
int cube_face_size(int shadow_map_size) {
    return std::max(shadow_map_size / 2, limits::min_shadow_map_size);
}

glm::vec3 up_vector_for(glm::vec3 direction) {
    return std::abs(direction.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
}

class ShadowPass final : public Pass {
public:
    explicit ShadowPass(const ShaderLoader& loader)
        : program_(loader.build_program({{GL_VERTEX_SHADER, "shadow.vert"}})),
          masked_program_(loader.build_program(
              {{GL_VERTEX_SHADER, "shadow.vert"}, {GL_FRAGMENT_SHADER, "shadow_mask.frag"}},
              "#define ALPHA_MASK 1\n")) {}

    std::string_view name() const override { return "shadow"; }

    PassDeclaration declaration(const RenderSettings&) const override {
        return {.reads = {}, .writes = {"shadow.depth", "shadow.cube"}};
    }

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
        // Bound, never read, while the key light is not a point light.
        if (!placeholder_cube_) {
            placeholder_cube_ = create_depth_cube(1);
            label_texture(placeholder_cube_, name(), "cube placeholder");
        }
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
        // A point light reads the cube instead of this map.
        const bool point = frame.scene->key_light.kind == LightKind::point;
        if (point)
            render_cube(frame);
        else
            draw_casters(*frame.scene_gpu, frame.shadow.light_view_projection);
        glDisable(GL_POLYGON_OFFSET_FILL);
        frame.publish("shadow.depth", depth_.get());
        frame.publish("shadow.cube", point ? cube_.get() : placeholder_cube_.get());
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
    // Six perspective faces around the point light, made on first use so
    // that other lights do not pay for six maps.
    void render_cube(FrameResources& frame) {
        if (cube_size_ != cube_face_size(size_)) {
            cube_size_ = cube_face_size(size_);
            cube_ = create_depth_cube(cube_size_);
            label_texture(cube_, name(), "cube");
            for (int face = 0; face < 6; ++face) {
                cube_framebuffers_[face] = gl::create_framebuffer();
                glNamedFramebufferTextureLayer(cube_framebuffers_[face].get(), GL_DEPTH_ATTACHMENT,
                                               cube_.get(), 0, face);
                glNamedFramebufferDrawBuffer(cube_framebuffers_[face].get(), GL_NONE);
                gl::check_framebuffer(cube_framebuffers_[face], "shadow cube");
            }
        }
        const ShadowProjection& shadow = frame.shadow;
        const glm::mat4 projection =
            glm::perspectiveRH_ZO(glm::half_pi<float>(), 1.0f, shadow.cube_near, shadow.cube_far);
        const float far_depth = 1.0f;
        glViewport(0, 0, cube_size_, cube_size_);
        for (int face = 0; face < 6; ++face) {
            glBindFramebuffer(GL_FRAMEBUFFER, cube_framebuffers_[face].get());
            glClearNamedFramebufferfv(cube_framebuffers_[face].get(), GL_DEPTH, 0, &far_depth);
            const CubeFace& f = kCubeFaces[face];
            const glm::mat4 view =
                glm::lookAt(shadow.cube_centre, shadow.cube_centre + f.forward, f.up);
            draw_casters(*frame.scene_gpu, projection * view);
        }
    }

    void draw_casters(const SceneGpu& scene, const glm::mat4& light_view_projection) {
        for (GLuint program : {program_.get(), masked_program_.get()})
            glProgramUniformMatrix4fv(program, light_view_projection_location, 1, GL_FALSE,
                                      &light_view_projection[0][0]);
        draw_scene_depth(scene, program_.get(), masked_program_.get(), base_colour_binding);
    }

    gl::Program program_;
    gl::Program masked_program_;
    gl::Texture placeholder_cube_;  // 1x1, bound when the key light is not a point light
    gl::Texture cube_;              // DEPTH_COMPONENT32F cube, compare mode on
    gl::Framebuffer cube_framebuffers_[6];
    int cube_size_ = 0;
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
    if (light.kind == LightKind::point) {
        // Faces reach the farthest corner of the bounds; nearer than a
        // hundredth of the scene's radius nothing casts.
        const glm::vec3 reach = glm::max(glm::abs(scene.bounds.min - light.position),
                                         glm::abs(scene.bounds.max - light.position));
        result.cube_centre = light.position;
        result.cube_near = 0.01f * radius;
        result.cube_far = std::max(glm::length(reach) * 1.01f, 2.0f * result.cube_near);
        // 1.5 texels of a 90-degree face, per metre of distance.
        result.normal_offset = 1.5f * (2.0f / float(cube_face_size(size)));
        return result;
    }
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
