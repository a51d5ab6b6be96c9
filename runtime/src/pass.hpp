#pragma once
// The pass interface. A pass builds its programs once (constructor), owns its
// render targets ((re)allocated by resize() without recompiling anything),
// declares which of the frame's named textures it reads and writes, runs
// against FrameResources, and lists the outputs --dump can write. The frame
// (frame.cpp) holds the list of passes in the order they run, checks the
// declarations before the first frame and binds every declared read before
// the pass runs.
#include "deepgi/gl_objects.hpp"
#include "deepgi/image_io.hpp"
#include "deepgi/renderer.hpp"
#include "frame_resources.hpp"

#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace deepgi {

// How an output texture becomes the float pixels of a dump.
enum class OutputDecode {
    floats,             // the texture's channels as stored (`channels` of R, RG or RGB)
    floats_rg_as_rgb,   // RG floats, written as RGB with blue 0 (motion, depth pyramid)
    floats_ba_as_rgb,   // BA floats, written as RGB with blue 0 (the pyramid's back faces)
    depth_to_metres,    // reversed-Z depth: near / stored, 0 where nothing was hit
    octahedral_normal,  // RG octahedral unit vector -> xyz, 0 where `mask_depth` is empty
    srgb_to_linear,     // RGBA8 sRGB-encoded -> linear RGB
    unorm_rgb,          // RGBA8 -> RGB in [0, 1]
    shadow_depth,       // depth with compare mode, switched off while reading
    alpha,              // the A channel of an RGBA float texture (radiosity confidence)
};

struct PassOutput {
    std::string name;  // file name in --dump, e.g. "gbuffer-depth-layer1"
    GLuint texture = 0;
    int layer = 0;  // array layer (2-D array textures), else 0
    int level = 0;  // MIP level
    int width = 0;
    int height = 0;
    int channels = 3;  // for OutputDecode::floats: 1 or 3
    OutputDecode decode = OutputDecode::floats;
    GLuint mask_depth = 0;  // for octahedral_normal: depth array of the same layer
};

// One named texture of the frame that a pass samples: the frame binds it to
// texture unit `binding` (the sampler's layout(binding) in the pass's shader)
// before run(). Textures the pass owns itself (its history, intermediates)
// are not reads: the pass binds those.
struct PassRead {
    // A read the pass uses by name only (a copy, say): checked, not bound.
    static constexpr GLuint unbound = ~GLuint(0);
    GLuint binding = unbound;
    std::string_view texture;  // the name an earlier pass writes, e.g. "gbuffer.normal"
};

// A value one pass gives the others from a setting it owns, named
// "<pass>.<setting>" (e.g. "depth_pyramid.q", "sao.radius"). A pass reads
// another pass's setting only this way: the settings rows it does not own
// stay out of its code (tests/runtime/settings_owner_test.cpp).
struct PassValue {
    std::string name;
    float value = 0.0f;
};

// What a pass reads and writes under given settings. Every read must be
// written by an enabled pass earlier in the list; every write must be
// published during run(), and nothing else may be. Values come from the
// settings, so they are known before any pass runs: a value read must be
// written by some enabled pass, earlier or later in the list.
struct PassDeclaration {
    std::vector<PassRead> reads;
    std::vector<std::string> writes;  // names published with frame.publish()
    // Most passes have none: default-initialised, so they may leave both out.
    std::vector<std::string> value_reads = {};  // other passes' values, read with frame.value()
    std::vector<PassValue> value_writes = {};   // this pass's, named "<this pass>.<setting>"
};

// What a settings change costs a pass (Pass::settings_change).
struct SettingsChange {
    bool reallocate = false;   // its render targets are sized by a changed value
    std::string drop_history;  // non-empty: why its history must go
};

class Pass {
public:
    virtual ~Pass() = default;
    // Names the timer entry, the GL debug group and the object labels.
    virtual std::string_view name() const = 0;
    // (Re)allocates render targets for frame.settings and frame.layout.
    virtual void resize(FrameResources& frame) = 0;
    // Whether the pass runs (and lists outputs) with these settings.
    virtual bool enabled(const RenderSettings&) const { return true; }
    // The frame's textures it reads and writes with these settings.
    virtual PassDeclaration declaration(const RenderSettings&) const = 0;
    virtual void run(FrameResources& frame) = 0;
    virtual std::vector<PassOutput> outputs(const FrameResources&) const { return {}; }
    // Which of its settings reallocate it and which drop history: by default
    // what the rows of numeric_settings() naming this pass as owner say (their
    // SettingEffect); a pass overrides it for settings that are no such row.
    virtual SettingsChange settings_change(const RenderSettings& before,
                                           const RenderSettings& after) const;
};

// The passes of a frame in the order they run (frame.cpp). Tests may run a
// different list through Renderer's constructor.
const std::vector<PassFactory>& default_pass_list();

// Reads `output` back and decodes it (pass_output.cpp). `near_plane` turns
// reversed-Z depth into metres.
FloatImage read_pass_output(const PassOutput& output, float near_plane);

// ---- helpers shared by the passes ----

// What the numeric settings rows whose owner `owns` accepts say a change
// from `before` to `after` costs; the reason names the first row that drops
// history.
SettingsChange rows_settings_change(const RenderSettings& before, const RenderSettings& after,
                                    const std::function<bool(std::string_view owner)>& owns);

// Checks the declarations of the enabled passes in list order and returns
// them, one per pass (empty for a disabled one), for the frame to bind and
// enforce until the settings change; throws GraphicsError with one line
// naming the pass and the texture or value when a pass reads a texture no
// earlier enabled pass writes or a value no enabled pass writes, two passes
// write one name, or a pass writes a value not named after itself.
std::vector<PassDeclaration> check_pass_declarations(
    const std::vector<std::unique_ptr<Pass>>& passes, const RenderSettings& settings);

// A program of fullscreen.vert and one fragment shader.
gl::Program build_fullscreen_program(const ShaderLoader& loader, const std::string& fragment,
                                     const std::string& defines = {});
// Fixed-function state every fullscreen pass wants, viewport and target bound.
void begin_fullscreen(GLuint framebuffer, int width, int height);
// Draws the fullscreen triangle into the bound framebuffer.
void draw_fullscreen_triangle(GLuint empty_vertex_array);
// Draws `program`'s fullscreen triangle into the frame's display image (the
// viewport-sized RGBA8 the last pass writes), the whole of it.
void draw_into_display(FrameResources& frame, const gl::Program& program);
// The display image as the output `name` of --dump (8-bit RGB).
PassOutput display_output(const FrameResources& frame, std::string name);
// A framebuffer whose colour attachment 0 is level 0 of `texture` (2-D).
gl::Framebuffer framebuffer_for(const gl::Texture& texture, const char* what);
// Names a texture for captures: "<pass> <what>".
void label_texture(const gl::Texture& texture, std::string_view pass, std::string_view what);

}  // namespace deepgi
