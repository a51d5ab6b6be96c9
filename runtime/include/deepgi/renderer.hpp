#pragma once
// The frame: shadow map, two-layer deep G-buffer, direct light, compose,
// tonemap. Later passes (depth pyramid, deep SAO, radiosity, blur) slot into
// render_frame() in frame.cpp, each as one host file and one shader file.
#include "deepgi/image_io.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/shader_loader.hpp"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace deepgi {

enum class Generator { peel, previous, reproject };

enum class DebugView {
    final_image,
    normal_layer0,
    normal_layer1,
    albedo_layer0,
    albedo_layer1,
    emissive,
    motion,
    depth_layer0,
    depth_layer1,
    direct_layer0,
    direct_layer1,
    ao_raw,      // deep SAO visibility before the bilateral blur
    ao_blurred,  // after it: what the compose pass multiplies in
};

enum class TimingMode { automatic, cpu, gpu };

std::string_view to_string(Generator generator);
std::optional<Generator> parse_generator(std::string_view text);
std::string_view to_string(DebugView view);
std::optional<DebugView> parse_debug_view(std::string_view text);
const std::vector<DebugView>& all_debug_views();

// Deep SAO (design.md 3, step 4; docs/deep-sao.md). Tap count and spiral turns
// come from the generated ao_taps.glsl, not from here.
struct AoSettings {
    float radius = 0.5f;     // world-space gather radius r (m)
    float bias = 0.01f;      // beta (m): ignores occluders closer than this to the tangent plane
    float intensity = 1.0f;  // exponent applied to the visibility
    float q = 8.0f;          // screen-space radius (px) at which taps move one MIP level down
    int layers = 2;          // 1: layer 0 only, 2: both deep G-buffer layers
    int max_mip_level = 5;   // deepest depth-pyramid level built and read
    // DEEPGI_AO_METHOD_* of shared_constants.h: 0 the published 1 - sqrt(...)
    // estimator, 1 the solid-angle estimator of the reference's integral.
    int method = 1;
};

struct RenderSettings {
    int width = 1280;
    int height = 720;
    float guard_band_fraction = 0.1f;  // of the height, on every side
    Generator generator = Generator::peel;
    float min_separation = 0.5f;  // camera-space metres between layer 0 and layer 1
    float exposure = 1.0f;
    DebugView view = DebugView::final_image;
    int shadow_map_size = 2048;
    TimingMode timing = TimingMode::automatic;
    AoSettings ao;
};

struct PassTiming {
    std::string pass;
    double milliseconds = 0.0;
};

// Guard band in pixels and the size of every internal buffer.
struct FrameLayout {
    int guard = 0;
    int internal_width = 0;
    int internal_height = 0;
};
FrameLayout frame_layout(const RenderSettings& settings);

// Projection for the guard-banded buffers: reversed Z, infinite far plane, so
// linear camera depth is near_plane / stored depth.
glm::mat4 guard_band_projection(const Camera& camera, const RenderSettings& settings);

struct RendererState;

class Renderer {
public:
    Renderer(const Scene& scene, const RenderSettings& settings, const ShaderLoader& loader);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Renders one frame. Single-pass generators compare against the previous
    // frame's layer-0 depth, so call this once per displayed frame.
    void render(const Camera& camera);

    // Changing size reallocates every buffer and forgets the previous frame.
    void set_settings(const RenderSettings& settings);
    const RenderSettings& settings() const;
    FrameLayout layout() const;

    const std::vector<PassTiming>& last_timings() const;
    bool timing_uses_cpu_clock() const;

    // The displayed image (tonemapped or debug view), viewport size, sRGB bytes,
    // rows bottom to top.
    std::vector<std::uint8_t> read_output_rgba8() const;
    GLuint output_texture() const;

    // Every pass output of the last frame, e.g. "gbuffer-depth-layer1"; see
    // docs/deepgi.md for the meaning of each.
    std::vector<std::string> pass_output_names() const;
    FloatImage read_pass_output(const std::string& name) const;
    void dump_pass_outputs(const std::filesystem::path& directory) const;

private:
    std::unique_ptr<RendererState> state_;
};

}  // namespace deepgi
