#pragma once
// The renderer: a list of passes (runtime/src/frame.cpp; docs/architecture.md)
// run once per frame over shared frame resources and history.
#include "deepgi/image_io.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/settings.hpp"
#include "deepgi/shader_loader.hpp"

#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace deepgi {

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

// Near and far linear camera depth (metres, scene units) of one G-buffer
// layer's valid texels over the viewport; both 0 when the layer is empty.
struct DepthRange {
    float near_depth = 0.0f;
    float far_depth = 0.0f;
};

// What the frame_statistics pass measured on the last frame.
struct FrameStatistics {
    float exposure = 1.0f;  // the multiplier the tonemap used
    // exp(mean(log(1e-4 + Y))) of the lit image before the tonemap, Y its
    // Rec. 709 luminance, over the viewport.
    float log_average_luminance = 0.0f;
    float auto_exposure_target = 0.0f;  // key / log-average, clamped, before smoothing
    std::array<DepthRange, 2> depth_ranges{};
};

struct RendererState;
class Pass;
class ShaderLoader;
// Makes one pass: builds its programs (runtime/src/pass.hpp).
using PassFactory = std::unique_ptr<Pass> (*)(const ShaderLoader& loader, const Scene& scene);

// `cut`: the camera jumped, so nothing of the previous frame applies
// (history is invalidated before the frame renders).
enum class CameraMotion { continuous, cut };

// The predict generator's next camera: constant velocity from `previous` to
// `current` in position, yaw and pitch, one more step (current + (current -
// previous)); yaw's step is taken the short way round.
Camera extrapolate_camera(const Camera& previous, const Camera& current);

// Half the diagonal of the scene's bounding box (scene units), what `auto`
// lengths are fractions of; 1 for an empty scene.
float scene_bounding_radius(const Scene& scene);
// The bounding radius and the bounding box's shortest side (at least 0), what
// resolve_auto_lengths takes.
SceneScale scene_scale(const Scene& scene);

class Renderer {
public:
    // The default pass list.
    Renderer(const Scene& scene, const RenderSettings& settings, const ShaderLoader& loader);
    // Any pass list, run in this order (tests add passes this way).
    Renderer(const Scene& scene, const RenderSettings& settings, const ShaderLoader& loader,
             const std::vector<PassFactory>& passes);
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Renders one frame. Single-pass generators compare against the previous
    // frame's layer-0 depth, so call this once per displayed frame.
    // Without a next camera the delay generator takes the camera as still
    // (next = camera).
    void render(const Camera& camera, CameraMotion motion = CameraMotion::continuous);
    // The delay generator's form: `next_camera` is the camera of the frame
    // after this one, so a caller that runs one frame behind its camera
    // source makes delay's layer 1 exact. The other generators ignore it.
    void render(const Camera& camera, const Camera& next_camera,
                CameraMotion motion = CameraMotion::continuous);

    // Changing size reallocates every render target (no shader is rebuilt)
    // and forgets the previous frame, as does changing the radiosity layer
    // count (the layer-1 history was not written while it was off). Every
    // other setting applies from the next frame with history kept.
    void set_settings(const RenderSettings& settings);
    // As given (lengths may be auto_length)...
    const RenderSettings& settings() const;
    // ...and as the passes read them: every `auto` length resolved against
    // this renderer's scene (resolve_auto_lengths, scene_scale).
    const RenderSettings& settings_in_use() const;
    // Edits the key light in place (the frame constants and the shadow
    // projection follow; nothing is reallocated or rebuilt). History is kept:
    // the temporal filter blends the new light in. Throws InputError for a
    // non-finite value, a negative intensity or colour, or a zero direction.
    void set_key_light(const KeyLight& light);
    const KeyLight& key_light() const;
    FrameLayout layout() const;

    const std::vector<PassTiming>& last_timings() const;

    // The last frame's statistics (frame_statistics pass). The frame itself
    // never reads them back (the tonemap reads the exposure on the GPU); the
    // first call after a frame reads 32 bytes, which waits for that frame's
    // statistics pass. Before any frame: the manual exposure (1 for auto)
    // and empty ranges.
    const FrameStatistics& frame_statistics() const;
    // The exposure the last frame was tonemapped with: the setting, or with
    // `auto` the measured and smoothed value.
    float exposure_in_use() const;
    // Each layer's depth range, which the depth debug views are scaled by.
    std::array<DepthRange, 2> depth_ranges() const;

    // Whether the last frame found the previous frame's history, and why
    // history was dropped each time it was ("new scene", "camera cut", ...).
    bool history_valid() const;
    const std::vector<std::string>& history_log() const;
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
