// The renderer's frame. render_frame() lists the passes top to bottom in the
// order they run; the later illumination passes (depth pyramid, deep SAO,
// radiosity, temporal filter, blur) go between direct light and compose.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/renderer.hpp"
#include "gl/pass_timer.hpp"
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <fmt/format.h>
#include <spiral/fileio.hpp>

#include <algorithm>
#include <array>
#include <cmath>

namespace deepgi {

namespace fs = std::filesystem;
using shader_shared::FrameConstants;

namespace {

constexpr std::array<std::pair<Generator, std::string_view>, 3> generator_names = {
    {{Generator::peel, "peel"},
     {Generator::previous, "previous"},
     {Generator::reproject, "reproject"}}};

constexpr std::array<std::pair<DebugView, std::string_view>, 13> view_names = {{
    {DebugView::final_image, "final"},
    {DebugView::normal_layer0, "normal-layer0"},
    {DebugView::normal_layer1, "normal-layer1"},
    {DebugView::albedo_layer0, "albedo-layer0"},
    {DebugView::albedo_layer1, "albedo-layer1"},
    {DebugView::emissive, "emissive"},
    {DebugView::motion, "motion"},
    {DebugView::depth_layer0, "depth-layer0"},
    {DebugView::depth_layer1, "depth-layer1"},
    {DebugView::direct_layer0, "direct-layer0"},
    {DebugView::direct_layer1, "direct-layer1"},
    {DebugView::ao_raw, "ao-raw"},
    {DebugView::ao_blurred, "ao-blurred"},
}};

}  // namespace

std::string_view to_string(Generator generator) {
    for (auto [value, name] : generator_names) {
        if (value == generator) return name;
    }
    return "?";
}

std::optional<Generator> parse_generator(std::string_view text) {
    for (auto [value, name] : generator_names) {
        if (name == text) return value;
    }
    return std::nullopt;
}

std::string_view to_string(DebugView view) {
    for (auto [value, name] : view_names) {
        if (value == view) return name;
    }
    return "?";
}

std::optional<DebugView> parse_debug_view(std::string_view text) {
    for (auto [value, name] : view_names) {
        if (name == text) return value;
    }
    return std::nullopt;
}

const std::vector<DebugView>& all_debug_views() {
    static const std::vector<DebugView> views = [] {
        std::vector<DebugView> list;
        for (auto [value, name] : view_names) list.push_back(value);
        return list;
    }();
    return views;
}

FrameLayout frame_layout(const RenderSettings& settings) {
    FrameLayout layout;
    layout.guard =
        static_cast<int>(std::lround(settings.guard_band_fraction * float(settings.height)));
    layout.internal_width = settings.width + 2 * layout.guard;
    layout.internal_height = settings.height + 2 * layout.guard;
    return layout;
}

glm::mat4 guard_band_projection(const Camera& camera, const RenderSettings& settings) {
    const FrameLayout layout = frame_layout(settings);
    const float focal = 1.0f / std::tan(camera.vertical_fov * 0.5f);
    const float aspect = float(settings.width) / float(settings.height);
    // The viewport keeps its field of view; the guard band widens the frustum.
    glm::mat4 projection(0.0f);
    projection[0][0] = focal / aspect * float(settings.width) / float(layout.internal_width);
    projection[1][1] = focal * float(settings.height) / float(layout.internal_height);
    projection[2][3] = -1.0f;              // clip w = linear depth
    projection[3][2] = camera.near_plane;  // clip z = near, so stored depth = near / linear depth
    return projection;
}

struct RendererState {
    Scene scene;
    RenderSettings settings;
    ShaderLoader loader;
    SceneGpu scene_gpu;
    gl::VertexArray empty_vertex_array;
    gl::Buffer frame_constants;
    ShadowPass shadow;
    GBufferPass gbuffer;
    DirectLightPass direct_light;
    ComposePass compose;
    TonemapPass tonemap;
    DebugViewPass debug_view;
    DepthPyramidPass depth_pyramid;  // deep SAO (issue 5)
    SaoPass sao;
    BilateralBlurPass ao_blur;
    PassTimer timer{true};
    std::optional<Camera> previous_camera;

    RendererState(const Scene& source, const RenderSettings& render_settings,
                  const ShaderLoader& shader_loader)
        : scene(source), settings(render_settings), loader(shader_loader) {}
};

namespace {

void validate(const RenderSettings& settings) {
    if (settings.width < 1 || settings.height < 1 || settings.width > 16384 ||
        settings.height > 16384) {
        throw InputError(fmt::format("image size {}x{} is out of range (1 to 16384)",
                                     settings.width, settings.height));
    }
    if (!(settings.min_separation >= 0.0f) || !std::isfinite(settings.min_separation)) {
        throw InputError("minimum separation must be a finite number of metres >= 0");
    }
    if (!(settings.guard_band_fraction >= 0.0f && settings.guard_band_fraction <= 1.0f)) {
        throw InputError("guard band fraction must be in [0, 1]");
    }
    if (settings.shadow_map_size < 16 || settings.shadow_map_size > 8192) {
        throw InputError("shadow map size must be in [16, 8192]");
    }
    validate_ao_settings(settings.ao);
}

void allocate_passes(RendererState& state) {
    const FrameLayout layout = frame_layout(state.settings);
    state.shadow = create_shadow_pass(state.loader, state.scene, state.settings.shadow_map_size);
    state.gbuffer =
        create_gbuffer_pass(state.loader, layout.internal_width, layout.internal_height);
    state.direct_light =
        create_direct_light_pass(state.loader, layout.internal_width, layout.internal_height);
    state.compose =
        create_compose_pass(state.loader, layout.internal_width, layout.internal_height);
    state.tonemap = create_tonemap_pass(state.loader, state.settings.width, state.settings.height);
    state.debug_view = create_debug_view_pass(state.loader);
    state.depth_pyramid =
        create_depth_pyramid_pass(state.loader, layout.internal_width, layout.internal_height,
                                  state.settings.ao.max_mip_level);
    state.sao = create_sao_pass(state.loader, layout.internal_width, layout.internal_height);
    state.ao_blur = create_bilateral_blur_pass(state.loader, layout.internal_width,
                                               layout.internal_height, GL_R16F);
    state.previous_camera.reset();
}

FrameConstants make_frame_constants(const RendererState& state, const Camera& camera,
                                    const Camera& previous) {
    const RenderSettings& settings = state.settings;
    const FrameLayout layout = frame_layout(settings);
    const KeyLight& light = state.scene.key_light;
    FrameConstants constants{};
    constants.view = camera_view_matrix(camera);
    constants.projection = guard_band_projection(camera, settings);
    constants.previous_view = camera_view_matrix(previous);
    constants.previous_view_projection =
        guard_band_projection(previous, settings) * constants.previous_view;
    constants.camera_to_light_clip =
        state.shadow.light_view_projection * glm::inverse(constants.view);
    constants.camera_ray_scale = {1.0f / constants.projection[0][0],
                                  1.0f / constants.projection[1][1], camera.near_plane, 0.0f};
    const glm::vec3 direction = glm::normalize(light.direction);
    if (light.kind == LightKind::directional) {
        constants.light_vector = glm::vec4(
            glm::normalize(glm::vec3(constants.view * glm::vec4(-direction, 0.0f))), 0.0f);
    } else {
        constants.light_vector = constants.view * glm::vec4(light.position, 1.0f);
    }
    constants.spot_axis = glm::vec4(glm::vec3(constants.view * glm::vec4(direction, 0.0f)),
                                    std::cos(light.outer_cone));
    constants.light_radiance =
        glm::vec4(light.colour * light.intensity, std::cos(light.inner_cone));
    constants.ambient = glm::vec4(state.scene.ambient, 0.0f);
    constants.background = glm::vec4(state.scene.background, 0.0f);
    constants.internal_size = {float(layout.internal_width), float(layout.internal_height),
                               1.0f / float(layout.internal_width),
                               1.0f / float(layout.internal_height)};
    const float depth_view_range =
        std::max(glm::length(state.scene.bounds.max - state.scene.bounds.min), 1e-3f);
    constants.parameters = {settings.min_separation, settings.exposure, state.shadow.normal_offset,
                            depth_view_range};
    constants.layout_info = {layout.guard, settings.width, settings.height,
                             static_cast<int>(settings.generator)};
    constants.options = {
        light.kind == LightKind::directional ? DEEPGI_LIGHT_DIRECTIONAL : DEEPGI_LIGHT_SPOT,
        static_cast<int>(settings.view), 0, 0};
    return constants;
}

bool wants_cpu_clock(TimingMode mode) {
    if (mode == TimingMode::cpu) return true;
    if (mode == TimingMode::gpu) return false;
    return query_context_info().is_software_renderer;
}

// One frame, in the order the passes run.
void render_frame(RendererState& state, const Camera& camera) {
    const Camera previous = state.previous_camera.value_or(camera);
    const FrameConstants constants = make_frame_constants(state, camera, previous);
    glNamedBufferSubData(state.frame_constants.get(), 0, sizeof(constants), &constants);
    glBindBufferBase(GL_UNIFORM_BUFFER, DEEPGI_UBO_FRAME, state.frame_constants.get());
    glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
    const GLuint empty = state.empty_vertex_array.get();

    state.timer.begin_frame();
    {
        ScopedPass timed(state.timer, "shadow");
        run_shadow_pass(state.shadow, state.scene_gpu);
    }
    {
        ScopedPass timed(state.timer, "gbuffer");
        run_gbuffer_pass(state.gbuffer, state.scene_gpu, state.settings.generator);
    }
    {
        ScopedPass timed(state.timer, "direct_light");
        run_direct_light_pass(state.direct_light, state.gbuffer.targets, state.shadow, empty);
    }
    {
        ScopedPass timed(state.timer, "depth_pyramid");
        run_depth_pyramid_pass(state.depth_pyramid, state.gbuffer.targets);
    }
    {
        ScopedPass timed(state.timer, "sao");
        run_sao_pass(state.sao, state.settings.ao, state.depth_pyramid, state.gbuffer.targets,
                     empty);
    }
    {
        ScopedPass timed(state.timer, "ao_blur");
        run_bilateral_blur_pass(state.ao_blur, state.sao.visibility.get(),
                                state.depth_pyramid.pyramid.get(),
                                state.gbuffer.targets.normal.get(), empty);
    }
    {
        ScopedPass timed(state.timer, "compose");
        run_compose_pass(state.compose, state.gbuffer.targets, state.direct_light,
                         state.ao_blur.output.get(), empty);
    }
    if (state.settings.view == DebugView::final_image) {
        ScopedPass timed(state.timer, "tonemap");
        run_tonemap_pass(state.tonemap, state.compose, empty);
    } else {
        ScopedPass timed(state.timer, "debug_view");
        run_debug_view_pass(state.debug_view, state.gbuffer.targets, state.direct_light,
                            state.sao.visibility.get(), state.ao_blur.output.get(), state.tonemap,
                            empty);
    }
    state.timer.end_frame();
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    state.previous_camera = camera;
}

glm::vec3 decode_octahedral_normal(float x, float y) {
    glm::vec3 n(x, y, 1.0f - std::abs(x) - std::abs(y));
    const float t = std::max(-n.z, 0.0f);
    n.x += n.x >= 0.0f ? -t : t;
    n.y += n.y >= 0.0f ? -t : t;
    return glm::normalize(n);
}

float srgb_decode(float encoded) {
    return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

std::vector<float> read_layer(GLuint texture, int layer, int width, int height, GLenum format,
                              int components) {
    std::vector<float> values(std::size_t(width) * std::size_t(height) * std::size_t(components));
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureSubImage(texture, 0, 0, 0, layer, width, height, 1, format, GL_FLOAT,
                         GLsizei(values.size() * sizeof(float)), values.data());
    return values;
}

std::vector<std::uint8_t> read_rgba8(GLuint texture, int layer, int width, int height) {
    std::vector<std::uint8_t> values(std::size_t(width) * std::size_t(height) * 4);
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glGetTextureSubImage(texture, 0, 0, 0, layer, width, height, 1, GL_RGBA, GL_UNSIGNED_BYTE,
                         GLsizei(values.size()), values.data());
    return values;
}

}  // namespace

Renderer::Renderer(const Scene& scene, const RenderSettings& settings, const ShaderLoader& loader)
    : state_(std::make_unique<RendererState>(scene, settings, loader)) {
    validate(settings);
    RendererState& state = *state_;
    state.scene_gpu = upload_scene(state.scene);
    state.empty_vertex_array = gl::create_vertex_array();
    state.frame_constants = gl::create_buffer();
    glNamedBufferStorage(state.frame_constants.get(), sizeof(FrameConstants), nullptr,
                         GL_DYNAMIC_STORAGE_BIT);
    state.timer = PassTimer(wants_cpu_clock(settings.timing));
    allocate_passes(state);
}

Renderer::~Renderer() = default;

void Renderer::render(const Camera& camera) {
    render_frame(*state_, camera);
}

void Renderer::set_settings(const RenderSettings& settings) {
    validate(settings);
    RendererState& state = *state_;
    const bool reallocate = settings.width != state.settings.width ||
                            settings.height != state.settings.height ||
                            settings.guard_band_fraction != state.settings.guard_band_fraction ||
                            settings.shadow_map_size != state.settings.shadow_map_size ||
                            settings.ao.max_mip_level != state.settings.ao.max_mip_level;
    const bool retime = settings.timing != state.settings.timing;
    state.settings = settings;
    if (reallocate) allocate_passes(state);
    if (retime) state.timer = PassTimer(wants_cpu_clock(settings.timing));
}

const RenderSettings& Renderer::settings() const {
    return state_->settings;
}
FrameLayout Renderer::layout() const {
    return frame_layout(state_->settings);
}
const std::vector<PassTiming>& Renderer::last_timings() const {
    return state_->timer.timings();
}
bool Renderer::timing_uses_cpu_clock() const {
    return state_->timer.uses_cpu_clock();
}
GLuint Renderer::output_texture() const {
    return state_->tonemap.colour.get();
}

std::vector<std::uint8_t> Renderer::read_output_rgba8() const {
    return read_rgba8(state_->tonemap.colour.get(), 0, state_->settings.width,
                      state_->settings.height);
}

std::vector<std::string> Renderer::pass_output_names() const {
    std::vector<std::string> names = {
        "shadow-depth",
        "gbuffer-depth-layer0",
        "gbuffer-depth-layer1",
        "gbuffer-normal-layer0",
        "gbuffer-normal-layer1",
        "gbuffer-albedo-layer0",
        "gbuffer-albedo-layer1",
        "gbuffer-emissive-layer0",
        "gbuffer-motion-layer0",
        "direct_light-radiance-layer0",
        "direct_light-radiance-layer1",
        "compose-radiance",
        state_->settings.view == DebugView::final_image ? "tonemap-colour" : "debug_view-colour"};
    for (auto& name : deep_sao_output_names(state_->depth_pyramid))
        names.push_back(std::move(name));
    return names;
}

FloatImage Renderer::read_pass_output(const std::string& name) const {
    const RendererState& state = *state_;
    const FrameLayout layout = frame_layout(state.settings);
    const int w = layout.internal_width;
    const int h = layout.internal_height;
    const std::size_t pixels = std::size_t(w) * std::size_t(h);
    const float near_plane = state.previous_camera ? state.previous_camera->near_plane : 0.05f;
    FloatImage image;
    image.width = w;
    image.height = h;
    auto layer_of = [&](std::string_view prefix) -> int {
        if (name == std::string(prefix) + "0") return 0;
        if (name == std::string(prefix) + "1") return 1;
        return -1;
    };

    if (name == "shadow-depth") {
        image.width = image.height = state.shadow.size;
        image.channels = 1;
        glTextureParameteri(state.shadow.depth.get(), GL_TEXTURE_COMPARE_MODE, GL_NONE);
        image.pixels = read_layer(state.shadow.depth.get(), 0, image.width, image.height,
                                  GL_DEPTH_COMPONENT, 1);
        glTextureParameteri(state.shadow.depth.get(), GL_TEXTURE_COMPARE_MODE,
                            GL_COMPARE_REF_TO_TEXTURE);
        return image;
    }
    if (int layer = layer_of("gbuffer-depth-layer"); layer >= 0) {
        image.channels = 1;
        image.pixels =
            read_layer(state.gbuffer.targets.depth.get(), layer, w, h, GL_DEPTH_COMPONENT, 1);
        // Linear camera depth in metres; 0 where nothing was hit.
        for (float& value : image.pixels) value = value > 0.0f ? near_plane / value : 0.0f;
        return image;
    }
    if (int layer = layer_of("gbuffer-normal-layer"); layer >= 0) {
        const auto encoded = read_layer(state.gbuffer.targets.normal.get(), layer, w, h, GL_RG, 2);
        const auto depth =
            read_layer(state.gbuffer.targets.depth.get(), layer, w, h, GL_DEPTH_COMPONENT, 1);
        image.channels = 3;
        image.pixels.assign(pixels * 3, 0.0f);
        for (std::size_t i = 0; i < pixels; ++i) {
            if (depth[i] <= 0.0f) continue;
            const glm::vec3 n = decode_octahedral_normal(encoded[2 * i], encoded[2 * i + 1]);
            image.pixels[3 * i] = n.x;
            image.pixels[3 * i + 1] = n.y;
            image.pixels[3 * i + 2] = n.z;
        }
        return image;
    }
    if (int layer = layer_of("gbuffer-albedo-layer"); layer >= 0) {
        const auto encoded = read_rgba8(state.gbuffer.targets.albedo.get(), layer, w, h);
        image.channels = 3;
        image.pixels.resize(pixels * 3);
        for (std::size_t i = 0; i < pixels; ++i) {
            for (int c = 0; c < 3; ++c)
                image.pixels[3 * i + std::size_t(c)] =
                    srgb_decode(float(encoded[4 * i + std::size_t(c)]) / 255.0f);
        }
        return image;
    }
    if (name == "gbuffer-emissive-layer0") {
        image.channels = 3;
        image.pixels = read_layer(state.gbuffer.targets.emissive.get(), 0, w, h, GL_RGB, 3);
        return image;
    }
    if (name == "gbuffer-motion-layer0") {
        const auto motion = read_layer(state.gbuffer.targets.motion.get(), 0, w, h, GL_RG, 2);
        image.channels = 3;
        image.pixels.assign(pixels * 3, 0.0f);
        for (std::size_t i = 0; i < pixels; ++i) {
            image.pixels[3 * i] = motion[2 * i];
            image.pixels[3 * i + 1] = motion[2 * i + 1];
        }
        return image;
    }
    if (int layer = layer_of("direct_light-radiance-layer"); layer >= 0) {
        image.channels = 3;
        image.pixels = read_layer(state.direct_light.radiance.get(), layer, w, h, GL_RGB, 3);
        return image;
    }
    if (name == "compose-radiance") {
        image.channels = 3;
        image.pixels = read_layer(state.compose.radiance.get(), 0, w, h, GL_RGB, 3);
        return image;
    }
    if (name == "tonemap-colour" || name == "debug_view-colour") {
        const auto bytes = read_output_rgba8();
        image.width = state.settings.width;
        image.height = state.settings.height;
        image.channels = 3;
        const std::size_t count = std::size_t(image.width) * std::size_t(image.height);
        image.pixels.resize(count * 3);
        for (std::size_t i = 0; i < count; ++i) {
            for (int c = 0; c < 3; ++c)
                image.pixels[3 * i + std::size_t(c)] =
                    float(bytes[4 * i + std::size_t(c)]) / 255.0f;
        }
        return image;
    }
    if (auto deep_sao = read_deep_sao_output(state.depth_pyramid, state.sao, state.ao_blur, name))
        return std::move(*deep_sao);
    throw InputError(fmt::format("no pass output named '{}'", name));
}

void Renderer::dump_pass_outputs(const fs::path& directory) const {
    // The whole set appears at once or not at all (a previous dump, holding
    // only .pfm files, is replaced whole); a failure names the file and errno.
    spiral::fileio::AtomicDirectory dump(directory, ".pfm");
    for (const auto& name : pass_output_names()) {
        const std::vector<std::uint8_t> bytes = encode_pfm(read_pass_output(name));
        dump.write_file(name + ".pfm", bytes.data(), bytes.size());
    }
    dump.commit();
}

}  // namespace deepgi
