#pragma once
// The renderer's settings vocabulary, in one place: every enum with its name
// table (used by the CLI, the ImGui panel and the docs), every limit, and the
// one validation. Front ends parse text into these types and call validate();
// they hold no limits or names of their own.
#include "shared_enums.h"

#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace deepgi {

// Enum values come from shaders/shared_enums.h, so C++ and GLSL cannot disagree.
enum class Generator {
    peel = DEEPGI_GENERATOR_PEEL,
    previous = DEEPGI_GENERATOR_PREVIOUS,
    reproject = DEEPGI_GENERATOR_REPROJECT,
    // One pass that also rasterises the scene with the next frame's camera
    // into a third depth layer, the layer 0 the next frame's layer 1 peels
    // against: delay is given that camera, predict extrapolates it.
    delay = DEEPGI_GENERATOR_DELAY,
    predict = DEEPGI_GENERATOR_PREDICT,
};

// Delay and predict keep a third G-buffer layer (the prediction).
constexpr bool generator_predicts_next_frame(Generator generator) {
    return generator == Generator::delay || generator == Generator::predict;
}

enum class DebugView {
    final_image = DEEPGI_VIEW_FINAL,
    normal_layer0 = DEEPGI_VIEW_NORMAL_LAYER0,
    normal_layer1 = DEEPGI_VIEW_NORMAL_LAYER1,
    albedo_layer0 = DEEPGI_VIEW_ALBEDO_LAYER0,
    albedo_layer1 = DEEPGI_VIEW_ALBEDO_LAYER1,
    emissive = DEEPGI_VIEW_EMISSIVE,
    motion = DEEPGI_VIEW_MOTION,
    depth_layer0 = DEEPGI_VIEW_DEPTH_LAYER0,
    depth_layer1 = DEEPGI_VIEW_DEPTH_LAYER1,
    direct_layer0 = DEEPGI_VIEW_DIRECT_LAYER0,
    direct_layer1 = DEEPGI_VIEW_DIRECT_LAYER1,
    ao_raw = DEEPGI_VIEW_AO_RAW,            // deep SAO visibility before the bilateral blur
    ao_temporal = DEEPGI_VIEW_AO_TEMPORAL,  // after the temporal filter, before the blur
    ao_blurred = DEEPGI_VIEW_AO_BLURRED,    // after it: what the compose pass multiplies in
    radiosity_prepared = DEEPGI_VIEW_RADIOSITY_PREPARED,  // B of layer 0 that the gather reads
    radiosity_layer0 = DEEPGI_VIEW_RADIOSITY_LAYER0,      // gathered E of layer 0, tonemapped
    radiosity_layer1 = DEEPGI_VIEW_RADIOSITY_LAYER1,      // gathered E of layer 1, tonemapped
    radiosity_blurred = DEEPGI_VIEW_RADIOSITY_BLURRED,    // layer 0's E after the bilateral blur
    radiosity_confidence = DEEPGI_VIEW_RADIOSITY_CONFIDENCE,  // hemisphere covered (or taps used)
    reflection_hit_layer = DEEPGI_VIEW_REFLECTION_HIT_LAYER,  // which layer each mirror ray hit
};

enum class TimingMode { automatic, cpu, gpu };

// Deep SAO estimators (docs/deep-sao.md).
enum class AoMethod {
    published = DEEPGI_AO_METHOD_PUBLISHED,      // 1 - sqrt(...), kept for comparison
    solid_angle = DEEPGI_AO_METHOD_SOLID_ANGLE,  // the reference's integral over the seen surface
    march = DEEPGI_AO_METHOD_MARCH,  // the reference's rays through slabs behind both layers
    // the spiral taps' solids (front to back face), unioned in a hemisphere bitmask
    spiral_thick = DEEPGI_AO_METHOD_SPIRAL_THICK,
    gtao = DEEPGI_AO_METHOD_GTAO,  // horizons per screen-space slice (Jimenez et al. 2016)
    // 32 sectors per slice, each sample a constant-thickness occluder (Therrien et al. 2023)
    bitmask = DEEPGI_AO_METHOD_BITMASK,
};

// Deep radiosity estimators (docs/radiosity.md).
enum class RadiosityMethod {
    published = DEEPGI_RADIOSITY_METHOD_PUBLISHED,  // 2 pi / M * sum B cos, kept for comparison
    area = DEEPGI_RADIOSITY_METHOD_AREA,  // the reference's integral over the seen surface
};

// One row of an enum's name table.
template <class Enum>
struct EnumName {
    Enum value;
    std::string_view name;
};

// The name tables, in display order.
std::span<const EnumName<Generator>> enum_names(Generator);
std::span<const EnumName<DebugView>> enum_names(DebugView);
std::span<const EnumName<TimingMode>> enum_names(TimingMode);
std::span<const EnumName<AoMethod>> enum_names(AoMethod);
std::span<const EnumName<RadiosityMethod>> enum_names(RadiosityMethod);

// "?" for a value outside the table.
template <class Enum>
std::string_view to_string(Enum value) {
    for (const auto& row : enum_names(Enum{}))
        if (row.value == value) return row.name;
    return "?";
}
template <class Enum>
std::optional<Enum> parse_enum(std::string_view text) {
    for (const auto& row : enum_names(Enum{}))
        if (row.name == text) return row.value;
    return std::nullopt;
}
// "peel, previous, reproject, delay, predict"
template <class Enum>
std::string enum_name_list() {
    std::string list;
    for (const auto& row : enum_names(Enum{})) {
        if (!list.empty()) list += ", ";
        list += row.name;
    }
    return list;
}
// Throws InputError "<option> '<text>' is not one of <names>".
Generator parse_generator(std::string_view option, std::string_view text);
DebugView parse_debug_view(std::string_view option, std::string_view text);
TimingMode parse_timing_mode(std::string_view option, std::string_view text);
AoMethod parse_ao_method(std::string_view option, std::string_view text);
RadiosityMethod parse_radiosity_method(std::string_view option, std::string_view text);

// Limits the validation enforces, exported so the CLI help and the ImGui
// sliders show the same ranges.
namespace limits {
inline constexpr int max_image_side = 16384;
// Viewport plus guard band: the GL_MAX_TEXTURE_SIZE every implementation we
// target guarantees (checked by check_frame_limits in frame_limits.hpp).
inline constexpr int max_internal_side = 16384;
inline constexpr int min_shadow_map_size = 16;
inline constexpr int max_shadow_map_size = 8192;
inline constexpr float max_guard_band_fraction = 1.0f;
inline constexpr int max_pyramid_mip_level = 15;
inline constexpr float min_pyramid_q = 1.0f;
inline constexpr int max_ao_layers = DEEPGI_LAYER_COUNT;
inline constexpr int max_ao_slices = 8;  // gtao and bitmask (ao-slices)
inline constexpr int max_ao_steps = 32;  // gtao and bitmask, per slice side (ao-steps)
inline constexpr int max_radiosity_layers = DEEPGI_LAYER_COUNT;
inline constexpr int max_radiosity_visibility_steps = 32;
inline constexpr int max_reflection_layers = DEEPGI_LAYER_COUNT;
inline constexpr int max_reflection_steps = 1024;
// temporal-offset: every value, and the next one past it, is exact in the
// float the settings rows carry.
inline constexpr int max_temporal_offset = 1 << 20;
inline constexpr int max_rotation_seed = 1 << 20;
}  // namespace limits

// The bias each estimator was derived or tuned with. Solid-angle needs none:
// a coplanar point's term is of the second order in its reconstruction error
// (sao.frag), and every centimetre of threshold drops real occluders next to
// creases. The march adds it to its own margin against self-hits (sao.frag).
// The published method subtracts its bias and keeps the 1 cm it was
// tuned with. AoSettings{} holds the march's; front ends that switch method
// without an explicit bias take this one.
constexpr float default_ao_bias(AoMethod method) {
    return method == AoMethod::published ? 0.01f : 0.0f;
}

// Whether the estimator reads the spiral tap header (ao_taps.glsl): the march
// casts DEEPGI_AO_MARCH_RAYS rays of its own instead, gtao and bitmask march
// ao-slices screen-space slices of ao-steps samples per side.
constexpr bool ao_method_gathers_taps(AoMethod method) {
    return method != AoMethod::march && method != AoMethod::gtao && method != AoMethod::bitmask;
}

// Whether the estimator marches screen-space slices (ao-slices, ao-steps).
constexpr bool ao_method_marches_slices(AoMethod method) {
    return method == AoMethod::gtao || method == AoMethod::bitmask;
}

// Whether the estimator ends each stored surface's solid at its back face
// (the backface_depth pass runs only then).
constexpr bool ao_method_reads_back_faces(AoMethod method) {
    return method == AoMethod::march || method == AoMethod::spiral_thick;
}

// Deep SAO (docs/design.md, section 5.6; docs/deep-sao.md). Tap count and spiral turns
// come from the generated ao_taps.glsl, not from here.
struct AoSettings {
    float radius = 0.5f;     // world-space gather radius r (m)
    float bias = 0.0f;       // beta (m): see default_ao_bias()
    float intensity = 1.0f;  // exponent applied to the visibility
    int layers = 2;          // 1: layer 0 only, 2: both deep G-buffer layers
    // The march is the one estimator that meets the accuracy targets against
    // the ray-traced reference on every scene; solid-angle is the fast spiral
    // gather, about 5x cheaper on llvmpipe; the thick spiral reads the spiral
    // and the layers' solids but does not yet reach the march's accuracy
    // (docs/deep-sao.md, "Choosing an estimator").
    AoMethod method = AoMethod::march;
    // March only: the scene is taken as solid this deep (m) behind a stored
    // surface with no back face behind it (an open mesh: a floor or wall
    // plane); behind any other the solid ends at the back face (the
    // backface_depth pass). 0.1 to 1 m move warehouse's bias by less than
    // .001 (docs/deep-sao.md, "The march").
    // The bitmask estimator takes every sample as this thick (its constant
    // thickness, Therrien et al. 2023), back face or not.
    float thickness = 0.2f;
    // gtao and bitmask only: screen-space slices per pixel and samples per
    // slice side (docs/deep-sao.md, "Slice estimators").
    int slices = 2;
    int steps = 8;
    // Temporal filter: weight of the history where the point moves on
    // screen; a still point keeps the running mean of up to
    // DEEPGI_TEMPORAL_CAP frames (0: the raw SAO result of each frame); see
    // docs/radiosity.md.
    float alpha = 0.85f;
    // false: compose takes the visibility as 1 (the passes still run, so the
    // AO debug views keep working); for showing what AO adds.
    bool enabled = true;
};

// Deep radiosity (docs/design.md, sections 5.8 and 5.9; docs/radiosity.md). Tap count
// and spiral turns come from the generated radiosity_taps.glsl.
struct RadiositySettings {
    float radius = 1.0f;  // world-space gather radius (m)
    float boost = 0.0f;   // 0: boost(rho) = 1 (energy conserving); 1: the saturation boost
    // Largest contribution of one sample, per channel: B(Y) cos(theta_X) times
    // the sample's area weight (area method) or alone (published method).
    // 256: a bound on the heavy tail that keeps the raw E, at most
    // 4 pi times the clamp, finite in its RGBA16F target, and that measured
    // the same as no clamp on the reference scenes; 16, the value before,
    // cut the crease's light at the scene-derived radius (ref-crease 9% too
    // dark; docs/radiosity.md, "The clamp").
    float tap_clamp = 256.0f;
    float rho_prop = 0.5f;  // share of last frame's indirect light fed into the next gather
    float alpha = 0.85f;    // temporal filter: history weight where the point moves (0: raw gather)
    int layers = 2;         // 1: layer 0 only, 2: both deep G-buffer layers
    RadiosityMethod method = RadiosityMethod::area;
    // Points marched from X to each sample to test that no stored surface
    // hides it (radiosity_visibility.glsl); 0: no test, every sample that
    // faces X within the radius counts (docs/radiosity.md).
    int visibility_steps = 0;
    // Deepest MIP level of the depth pyramid and the prepared arrays a tap
    // reads, below the pyramid's own (SAO keeps reading the pyramid's): a
    // level-m tap reads the position and normal of the one level-0 pixel of
    // its 2^m block the rotated grid keeps (and, without `prefilter`, its
    // radiance), a lattice fixed in the image that frames do not average away
    // (docs/radiosity.md, "The taps' MIP levels").
    int max_mip_level = limits::max_pyramid_mip_level;
    // 1: a coarse level's radiance is the mean over its block's pixels on the
    // surface of the pixel the rotated grid keeps, so a tap reads the light
    // of the area it stands for; 0: that one pixel's (docs/radiosity.md,
    // "Prefiltered levels").
    int prefilter = 1;
    // false: compose takes E and its confidence as 0, so the environment term
    // fills everywhere (the passes still run for their debug views).
    bool enabled = true;
};

// The bilateral blur's edge weights (docs/deep-sao.md, "bilateral blur"); its
// radius and Gaussian weights are generated at build time (BLUR_RADIUS).
struct BlurSettings {
    float depth_tolerance = 0.1f;   // taps whose depth differs by this fraction weigh nothing
    float normal_power = 8.0f;      // weight * max(dot(n_tap, n_centre), 0)^power
    float plane_tolerance = 0.02f;  // distance from the centre's tangent plane that weighs nothing
    // World-space reach, as a fraction of the AO radius: a tap d metres from
    // the centre weighs (1 - d^2 / (extent r)^2), nothing beyond; 0: no limit.
    // AO changes over distances of the order of r, and a blur of fixed pixel
    // radius spans more metres the further and the more grazing the surface.
    float extent = 0.5f;
};

// The depth pyramid (depth_pyramid.comp): how deep it is built, and how the
// gathers that read it (SAO, radiosity) choose a level. The gathers read the
// level count the pass publishes and its value "depth_pyramid.q", never these
// settings.
struct DepthPyramidSettings {
    int max_mip_level = 5;  // deepest level built (fewer when the image is smaller)
    float q = 8.0f;         // screen-space radius (px) at which taps move one MIP level down
};

// Mirror reflections traced through both deep G-buffer layers (the paper's
// section 4.5; docs/reflections.md). Only pixels of mirror materials are
// traced: roughness at most `mirror_roughness` and metallic at least 0.5.
struct ReflectionSettings {
    bool enabled = true;  // false: the pass sits out and compose shades mirrors as diffuse
    int layers = 2;       // 1: layer 0 only, 2: both deep G-buffer layers
    int steps = 32;       // march steps along each reflected ray
    // How far (m) a reflected ray is marched; 0: auto, a fraction of the
    // scene's bounding radius (reflection_distance()).
    float distance = 0.0f;
};

struct RenderSettings {
    int width = 1280;
    int height = 720;
    float guard_band_fraction = 0.1f;  // of the height, on every side
    Generator generator = Generator::peel;
    float min_separation = 0.5f;  // camera-space metres between layer 0 and layer 1
    // Multiplier before the tonemap; auto_length: measured each frame from the
    // lit image's log-average luminance (the frame_statistics pass). The
    // library keeps 1, which the tests and the report were recorded with.
    float exposure = 1.0f;
    // false: compose adds no environment irradiance where the radiosity's
    // confidence is low (with radiosity and AO off too: direct light only).
    bool environment = true;
    DebugView view = DebugView::final_image;
    int shadow_map_size = 4096;
    int antialias = 1;  // 1: the anti-aliasing pass filters the final image; 0: off
    // The temporal sequence's index on the first frame after history is
    // dropped (frame.cpp): frame k after it uses Sobol point temporal_offset + k.
    // 0 is the shipped sequence; the report repeats rows with other offsets
    // to measure its run-to-run spread (docs/report.md).
    int temporal_offset = 0;
    // Picks the field of per-pixel hashed angles every gather turns its
    // pattern by (pixel_rotation_hash.h); 0 is the shipped field. The report
    // gives repeat r seed r beside its temporal offset, so its spread also
    // covers how a pattern meets one particular field (docs/report.md).
    int rotation_seed = 0;
    TimingMode timing = TimingMode::automatic;
    // Installs a KHR_debug callback: a GL error raised inside a pass becomes a
    // GraphicsError naming the pass (costs a synchronous debug context).
    bool gl_debug = false;
    DepthPyramidSettings depth_pyramid;
    AoSettings ao;
    RadiositySettings radiosity;
    BlurSettings blur;  // one blur filters AO and radiosity E with the same weights
    ReflectionSettings reflection;
    // A material is a mirror when its roughness is at most this and its
    // metallic factor at least 0.5 (glTF's metallic-roughness factors).
    float mirror_roughness = 0.1f;
};

// The share of the scene's bounding radius a reflected ray is marched when
// ReflectionSettings::distance is 0 (auto).
inline constexpr float auto_reflection_distance_fraction = 1.0f;
// The march distance (m) for these settings and a scene of this bounding radius.
float reflection_distance(const RenderSettings& settings, float scene_bounding_radius);

// `--exposure auto` (the frame_statistics pass; docs/deepgi.md, "Exposure"):
// key / log-average luminance of the lit image, clamped to [min, max], and
// moved `smoothing` of the way (in log space) from last frame's value.
inline constexpr float auto_exposure_key = 0.0923f;
inline constexpr float auto_exposure_min = 1.0f / 16.0f;
inline constexpr float auto_exposure_max = 16.0f;
inline constexpr float auto_exposure_smoothing = 0.1f;

// An image size given as WIDTHxHEIGHT, each side 1 to limits::max_image_side.
struct ImageSize {
    int width = 0;
    int height = 0;
};
// The one parser of WIDTHxHEIGHT for every command and benchmark; throws
// InputError naming `option` (e.g. "--size") for a malformed or out-of-range
// size.
ImageSize parse_size(std::string_view option, std::string_view text);

// Every check of every setting, enum values included; throws InputError with
// one line naming the setting by its command-line option.
void validate(const RenderSettings& settings);

// What changing a setting costs the renderer (Renderer::set_settings).
enum class SettingEffect {
    none,          // read every frame: history stays
    drop_history,  // history of the old value would take cycles to fade
    reallocate,    // the owning pass's render targets are sized by it
};

// One numeric setting: the single row the command line, the window's panel,
// its --script `set` command and validate() all read. The hard limits are
// validate()'s; the slider range is only the panel's convenience (a typed-in
// or scripted value outside it is accepted when valid).
struct NumericSetting {
    std::string_view name;   // the command-line option without "--", e.g. "ao-radius"
    std::string_view label;  // the panel's label
    std::string_view group;  // the panel section: "frame", "ao", "radiosity" or "blur"
    // The pass that reads it ("frame": the frame itself, e.g. the guard band
    // that sizes every pass). Another pass that needs it reads the value the
    // owner declares (PassValue, runtime/src/pass.hpp), never the row.
    std::string_view owner;
    std::string_view help;  // the command line's help, without default or range
    std::string_view unit;  // in words, for help and messages ("metres", "pixels"), or ""
    bool integer = false;
    float minimum = 0.0f;  // lower limit
    bool minimum_inclusive = true;
    float maximum = 0.0f;  // upper limit; infinity: none
    bool maximum_inclusive = true;
    float slider_min = 0.0f;
    float slider_max = 1.0f;
    bool logarithmic = false;
    SettingEffect effect = SettingEffect::none;
    // The RenderSettings member it is, e.g. "ao.radius" (what its owner's
    // code reads; tests/runtime/settings_owner_test.cpp looks for it).
    std::string_view field;
    float (*get)(const RenderSettings&) = nullptr;
    void (*set)(RenderSettings&, float) = nullptr;
    // > 0: the row is a length that accepts `auto` (auto_length in the
    // settings), meaning this fraction of the scene's bounding radius; the
    // renderer resolves it for the scene it draws (resolve_auto_lengths).
    float scene_fraction = 0.0f;
    // > 0: `auto` is also at most this fraction of the scene's smallest
    // extent (SceneScale), so a long, low interior is not reached across.
    float extent_fraction = 0.0f;
    // The row accepts `auto` (auto_length in the settings), which the
    // renderer measures each frame instead of resolving it from the scene
    // (exposure: Renderer::exposure_in_use()).
    bool auto_measured = false;
};
// In panel order.
std::span<const NumericSetting> numeric_settings();
// nullptr for an unknown name.
const NumericSetting* find_numeric_setting(std::string_view name);
// "a finite number of metres > 0", "a number in [0, 1)", "1 or 2": what the
// row accepts, in words, for help texts and messages.
std::string describe_limits(const NumericSetting& setting);
// Throws InputError "--NAME must be <describe_limits>" (", got V" for an
// integer) when `value` is outside the row's limits. A number only: `auto`
// is never a number (parse_setting_value).
void check_setting(const NumericSetting& setting, double value);

// The value a length row holds for `auto`. Negative, so no valid length is
// taken for it; validate() accepts it only in rows that accept_auto().
inline constexpr float auto_length = -1.0f;
// A length that follows the scene: `auto` is a fraction of its size.
inline bool is_scene_length(const NumericSetting& setting) {
    return setting.scene_fraction > 0.0f;
}
inline bool accepts_auto(const NumericSetting& setting) {
    return is_scene_length(setting) || setting.auto_measured;
}
// What the command line, --script `set` and the panel accept for a row:
// "auto" where accepts_auto() (returns auto_length), or a number within the
// row's limits (check_setting). Throws InputError naming --NAME otherwise.
float parse_setting_value(const NumericSetting& setting, std::string_view text);
// The sizes of a scene that `auto` lengths follow, in scene units
// (scene_scale in renderer.hpp measures them).
struct SceneScale {
    // Half the diagonal of the bounding box.
    float bounding_radius = 1.0f;
    // The bounding box's shortest side (an interior's height, say).
    float smallest_extent = 2.0f;
};
// What a scene-length row's `auto` is for a scene of this scale: the row's
// fraction of the bounding radius, and, for a row with an extent_fraction,
// at most that fraction of the smallest extent (a flat scene's extent counts
// as at least 0.2 bounding radii, so the length stays > 0).
float auto_length_value(const NumericSetting& setting, const SceneScale& scale);
// `settings` with every scene-length row set to `auto`, as the deepgi
// command line leaves them unless given.
RenderSettings with_auto_lengths(RenderSettings settings);
// Every `auto` length replaced by auto_length_value; explicit numbers are
// kept.
RenderSettings resolve_auto_lengths(RenderSettings settings, const SceneScale& scale);
// One line per `auto` row of `given`, with the value `in_use` holds:
// "ao-radius auto = 0.412 scene units (0.24 x bounding radius 1.72)". Empty
// when no row of `given` is auto.
std::vector<std::string> describe_auto_lengths(const RenderSettings& given,
                                               const RenderSettings& in_use,
                                               const SceneScale& scale);

}  // namespace deepgi
