// Name tables and the validation of every setting.
#include "deepgi/settings.hpp"

#include "deepgi/errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

namespace deepgi {

namespace {

constexpr std::array<EnumName<Generator>, 5> generator_table = {{
    {Generator::peel, "peel"},
    {Generator::previous, "previous"},
    {Generator::reproject, "reproject"},
    {Generator::delay, "delay"},
    {Generator::predict, "predict"},
}};

constexpr std::array<EnumName<DebugView>, 20> view_table = {{
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
    {DebugView::ao_temporal, "ao-temporal"},
    {DebugView::ao_blurred, "ao-blurred"},
    {DebugView::radiosity_prepared, "radiosity-prepared"},
    {DebugView::radiosity_layer0, "radiosity-layer0"},
    {DebugView::radiosity_layer1, "radiosity-layer1"},
    {DebugView::radiosity_blurred, "radiosity-blurred"},
    {DebugView::radiosity_confidence, "radiosity-confidence"},
    {DebugView::reflection_hit_layer, "reflection-hit-layer"},
}};

constexpr std::array<EnumName<TimingMode>, 3> timing_table = {{
    {TimingMode::automatic, "auto"},
    {TimingMode::cpu, "cpu"},
    {TimingMode::gpu, "gpu"},
}};

constexpr std::array<EnumName<AoMethod>, 6> ao_method_table = {{
    {AoMethod::spiral_thick, "spiral-thick"},
    {AoMethod::solid_angle, "solid-angle"},
    {AoMethod::march, "march"},
    {AoMethod::published, "published"},
    {AoMethod::gtao, "gtao"},
    {AoMethod::bitmask, "bitmask"},
}};

constexpr std::array<EnumName<RadiosityMethod>, 2> radiosity_method_table = {{
    {RadiosityMethod::area, "area"},
    {RadiosityMethod::published, "published"},
}};

template <class Enum>
Enum parse_or_throw(std::string_view option, std::string_view text) {
    if (auto value = parse_enum<Enum>(text)) return *value;
    throw InputError(fmt::format("{} '{}' is not one of {}", option, text, enum_name_list<Enum>()));
}

// The one place an enum value outside its table is rejected.
template <class Enum>
void check_enum(std::string_view option, Enum value) {
    if (to_string(value) == "?") {
        throw InputError(fmt::format("{} value {} is not one of {}", option,
                                     static_cast<int>(value), enum_name_list<Enum>()));
    }
}

}  // namespace

std::span<const EnumName<Generator>> enum_names(Generator) {
    return generator_table;
}
std::span<const EnumName<DebugView>> enum_names(DebugView) {
    return view_table;
}
std::span<const EnumName<TimingMode>> enum_names(TimingMode) {
    return timing_table;
}
std::span<const EnumName<AoMethod>> enum_names(AoMethod) {
    return ao_method_table;
}
std::span<const EnumName<RadiosityMethod>> enum_names(RadiosityMethod) {
    return radiosity_method_table;
}

Generator parse_generator(std::string_view option, std::string_view text) {
    return parse_or_throw<Generator>(option, text);
}
DebugView parse_debug_view(std::string_view option, std::string_view text) {
    return parse_or_throw<DebugView>(option, text);
}
TimingMode parse_timing_mode(std::string_view option, std::string_view text) {
    return parse_or_throw<TimingMode>(option, text);
}
AoMethod parse_ao_method(std::string_view option, std::string_view text) {
    return parse_or_throw<AoMethod>(option, text);
}
RadiosityMethod parse_radiosity_method(std::string_view option, std::string_view text) {
    return parse_or_throw<RadiosityMethod>(option, text);
}

ImageSize parse_size(std::string_view option, std::string_view text) {
    // Digits, 'x', digits: no sign, no spaces, no other base (from_chars
    // accepts none of them for an int).
    const std::size_t cross = text.find('x');
    ImageSize size;
    auto parse_side = [](std::string_view digits, int& side) {
        if (digits.empty() || digits.size() > 5) return false;
        for (char c : digits)
            if (c < '0' || c > '9') return false;
        side = std::stoi(std::string(digits));
        return true;
    };
    if (cross == std::string_view::npos || !parse_side(text.substr(0, cross), size.width) ||
        !parse_side(text.substr(cross + 1), size.height)) {
        throw InputError(
            fmt::format("{} '{}' is not WIDTHxHEIGHT (for example 1280x720)", option, text));
    }
    if (size.width < 1 || size.height < 1 || size.width > limits::max_image_side ||
        size.height > limits::max_image_side) {
        throw InputError(fmt::format("{} {}x{} is out of range (1 to {} per side)", option,
                                     size.width, size.height, limits::max_image_side));
    }
    return size;
}

void validate(const RenderSettings& settings) {
    if (settings.width < 1 || settings.height < 1 || settings.width > limits::max_image_side ||
        settings.height > limits::max_image_side) {
        throw InputError(fmt::format("--size {}x{} is out of range (1 to {} per side)",
                                     settings.width, settings.height, limits::max_image_side));
    }
    check_enum("--generator", settings.generator);
    check_enum("--view", settings.view);
    check_enum("--timing", settings.timing);
    check_enum("--ao-method", settings.ao.method);
    check_enum("--radiosity-method", settings.radiosity.method);
    // Every numeric setting from its row, in panel order.
    for (const NumericSetting& setting : numeric_settings()) {
        const float value = setting.get(settings);
        if (accepts_auto(setting) && value == auto_length) continue;
        check_setting(setting, value);
    }
}

namespace {

// A float field's accessors, as plain function pointers for the table.
#define DEEPGI_FLOAT_FIELD(member)                                                    \
    .field = #member, .get = [](const RenderSettings& s) { return float(s.member); }, \
    .set = [](RenderSettings& s, float value) { s.member = value; }
#define DEEPGI_INT_FIELD(member)                                                      \
    .field = #member, .get = [](const RenderSettings& s) { return float(s.member); }, \
    .set = [](RenderSettings& s, float value) { s.member = int(std::lround(value)); }

constexpr float unlimited = std::numeric_limits<float>::infinity();

// `auto` lengths as fractions of the scene's bounding radius (half its box
// diagonal); docs/deepgi.md, "Scene scale", says how they were chosen.
constexpr float kAoRadiusFraction = 0.1f;
constexpr float kThicknessFraction = 0.04f;
constexpr float kRadiosityRadiusFraction = 0.6f;
constexpr float kMinSeparationFraction = 0.1f;
constexpr SettingEffect reallocate = SettingEffect::reallocate;
constexpr SettingEffect drop_history = SettingEffect::drop_history;

// Designated initializers leave the fields a row does not name at their
// defaults (no unit, inclusive limits, no effect); GCC warns about exactly that.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
// One row per numeric setting. Slider ranges sit inside the limits; where a
// setting has no upper limit the slider stops at what is still useful in the
// built-in scenes.
const std::array<NumericSetting, 29> numeric_table = {{
    {.name = "min-separation",
     .label = "min separation (m)",
     .group = "frame",
     .owner = "gbuffer",
     .help = "Minimum camera-space distance of layer 1 behind layer 0",
     .unit = "metres",
     .minimum = 0.0f,
     .maximum = unlimited,
     .slider_min = 0.0f,
     .slider_max = 2.0f,
     DEEPGI_FLOAT_FIELD(min_separation),
     .scene_fraction = kMinSeparationFraction},
    {.name = "exposure",
     .label = "exposure",
     .group = "frame",
     .owner = "frame_statistics",  // resolves auto; tonemap and debug_view read its result
     .help = "Exposure multiplier before the tonemap; auto: 0.0923 / the lit image's "
             "log-average luminance, clamped to [1/16, 16], smoothed over frames",
     .minimum = 0.0f,
     .minimum_inclusive = false,
     .maximum = unlimited,
     .slider_min = 0.05f,
     .slider_max = 16.0f,
     .logarithmic = true,
     DEEPGI_FLOAT_FIELD(exposure),
     .auto_measured = true},
    {.name = "guard-band",
     .label = "guard band (* height)",
     .group = "frame",
     .owner = "frame",
     .help = "Guard band on every side, as a fraction of the height",
     .minimum = 0.0f,
     .maximum = limits::max_guard_band_fraction,
     .slider_min = 0.0f,
     .slider_max = limits::max_guard_band_fraction,
     .effect = reallocate,
     DEEPGI_FLOAT_FIELD(guard_band_fraction)},
    {.name = "shadow-map-size",
     .label = "shadow map size (px)",
     .group = "frame",
     .owner = "shadow",
     .help = "Shadow map side",
     .unit = "pixels",
     .integer = true,
     .minimum = float(limits::min_shadow_map_size),
     .maximum = float(limits::max_shadow_map_size),
     .slider_min = float(limits::min_shadow_map_size),
     .slider_max = 4096.0f,
     .logarithmic = true,
     .effect = reallocate,
     DEEPGI_INT_FIELD(shadow_map_size)},
    {.name = "antialias",
     .label = "anti-aliasing",
     .group = "frame",
     .owner = "antialias",
     .help = "Anti-aliasing of the final image after the tonemap, FXAA-like (1: on, 0: off)",
     .integer = true,
     .minimum = 0.0f,
     .maximum = 1.0f,
     .slider_min = 0.0f,
     .slider_max = 1.0f,
     DEEPGI_INT_FIELD(antialias)},
    {.name = "ao-radius",
     .label = "radius (m)",
     .group = "ao",
     .owner = "sao",
     .help = "Deep SAO: world-space gather radius",
     .unit = "metres",
     .minimum = 0.0f,
     .minimum_inclusive = false,
     .maximum = unlimited,
     .slider_min = 0.01f,
     .slider_max = 10.0f,
     .logarithmic = true,
     DEEPGI_FLOAT_FIELD(ao.radius),
     .scene_fraction = kAoRadiusFraction},
    {.name = "ao-bias",
     .label = "bias (m)",
     .group = "ao",
     .owner = "sao",
     .help = "Deep SAO: occluders closer than this to the tangent plane are ignored; default "
             "0 with march and solid-angle, 0.01 with published",
     .unit = "metres",
     .minimum = 0.0f,
     .maximum = unlimited,
     .slider_min = 0.0f,
     .slider_max = 0.5f,
     DEEPGI_FLOAT_FIELD(ao.bias)},
    {.name = "ao-intensity",
     .label = "intensity",
     .group = "ao",
     .owner = "sao",
     .help = "Deep SAO: exponent on the visibility",
     .minimum = 0.0f,
     .minimum_inclusive = false,
     .maximum = unlimited,
     .slider_min = 0.1f,
     .slider_max = 8.0f,
     .logarithmic = true,
     DEEPGI_FLOAT_FIELD(ao.intensity)},
    {.name = "ao-layers",
     .label = "layers",
     .group = "ao",
     .owner = "sao",
     .help = "Deep SAO: G-buffer layers the taps test",
     .integer = true,
     .minimum = 1.0f,
     .maximum = float(limits::max_ao_layers),
     .slider_min = 1.0f,
     .slider_max = float(limits::max_ao_layers),
     DEEPGI_INT_FIELD(ao.layers)},
    {.name = "pyramid-q",
     .label = "pyramid q (px per MIP)",
     .group = "ao",
     .owner = "depth_pyramid",
     .help = "Depth pyramid: tap radius per MIP level step of the gathers that read it (deep "
             "SAO and radiosity)",
     .unit = "pixels",
     .minimum = limits::min_pyramid_q,
     .maximum = unlimited,
     .slider_min = limits::min_pyramid_q,
     .slider_max = 64.0f,
     .logarithmic = true,
     DEEPGI_FLOAT_FIELD(depth_pyramid.q)},
    {.name = "pyramid-max-mip",
     .label = "pyramid max MIP level",
     .group = "ao",
     .owner = "depth_pyramid",
     .help = "Depth pyramid: deepest level built, and read by the gathers",
     .integer = true,
     .minimum = 0.0f,
     .maximum = float(limits::max_pyramid_mip_level),
     .slider_min = 0.0f,
     .slider_max = float(limits::max_pyramid_mip_level),
     .effect = reallocate,
     DEEPGI_INT_FIELD(depth_pyramid.max_mip_level)},
    {.name = "ao-alpha",
     .label = "temporal alpha",
     .group = "ao",
     .owner = "ao_temporal",
     .help = "AO temporal filter's history weight where the point moves on screen; a still "
             "point keeps the running mean of up to 256 frames (0: raw SAO of each frame)",
     .minimum = 0.0f,
     .maximum = 1.0f,
     .maximum_inclusive = false,
     .slider_min = 0.0f,
     .slider_max = 0.99f,
     DEEPGI_FLOAT_FIELD(ao.alpha)},
    {.name = "ao-thickness",
     .label = "thickness (m, march, spiral-thick, bitmask)",
     .group = "ao",
     .owner = "sao",
     .help = "Deep SAO, march and spiral-thick: the scene is taken as solid this deep behind a "
             "stored surface with no back face behind it; bitmask: every sample's constant "
             "thickness",
     .unit = "metres",
     .minimum = 0.0f,
     .minimum_inclusive = false,
     .maximum = unlimited,
     .slider_min = 0.01f,
     .slider_max = 1.0f,
     .logarithmic = true,
     DEEPGI_FLOAT_FIELD(ao.thickness),
     .scene_fraction = kThicknessFraction},
    {.name = "ao-slices",
     .label = "slices (gtao, bitmask)",
     .group = "ao",
     .owner = "sao",
     .help = "Deep SAO, gtao and bitmask: screen-space slices per pixel",
     .integer = true,
     .minimum = 1.0f,
     .maximum = float(limits::max_ao_slices),
     .slider_min = 1.0f,
     .slider_max = float(limits::max_ao_slices),
     DEEPGI_INT_FIELD(ao.slices)},
    {.name = "ao-steps",
     .label = "steps (gtao, bitmask)",
     .group = "ao",
     .owner = "sao",
     .help = "Deep SAO, gtao and bitmask: samples per slice side, out to the radius",
     .integer = true,
     .minimum = 1.0f,
     .maximum = float(limits::max_ao_steps),
     .slider_min = 1.0f,
     .slider_max = float(limits::max_ao_steps),
     DEEPGI_INT_FIELD(ao.steps)},
    {.name = "radiosity-radius",
     .label = "radius (m)",
     .group = "radiosity",
     .owner = "radiosity",
     .help = "Deep radiosity: world-space gather radius",
     .unit = "metres",
     .minimum = 0.0f,
     .minimum_inclusive = false,
     .maximum = unlimited,
     .slider_min = 0.05f,
     .slider_max = 10.0f,
     .logarithmic = true,
     DEEPGI_FLOAT_FIELD(radiosity.radius),
     .scene_fraction = kRadiosityRadiusFraction},
    {.name = "radiosity-boost",
     .label = "boost",
     .group = "radiosity",
     .owner = "radiosity_prepare",
     .help = "Deep radiosity: colour boost (0: energy conserving)",
     .minimum = 0.0f,
     .maximum = 1.0f,
     .slider_min = 0.0f,
     .slider_max = 1.0f,
     DEEPGI_FLOAT_FIELD(radiosity.boost)},
    {.name = "radiosity-clamp",
     .label = "tap clamp",
     .group = "radiosity",
     .owner = "radiosity",
     .help = "Deep radiosity: largest contribution of one sample, per channel",
     .minimum = 0.0f,
     .minimum_inclusive = false,
     .maximum = unlimited,
     .slider_min = 0.1f,
     .slider_max = 100.0f,
     .logarithmic = true,
     DEEPGI_FLOAT_FIELD(radiosity.tap_clamp)},
    {.name = "rho-prop",
     .label = "rho_prop (bounces)",
     .group = "radiosity",
     .owner = "radiosity_prepare",
     .help = "Deep radiosity: share of last frame's indirect light in the next gather "
             "(multiple bounces)",
     .minimum = 0.0f,
     .maximum = 1.0f,
     .slider_min = 0.0f,
     .slider_max = 1.0f,
     DEEPGI_FLOAT_FIELD(radiosity.rho_prop)},
    {.name = "radiosity-alpha",
     .label = "temporal alpha",
     .group = "radiosity",
     .owner = "radiosity",
     .help = "Deep radiosity: temporal filter's history weight where the point moves on "
             "screen; a still point keeps the running mean of up to 256 frames (0: raw gather)",
     .minimum = 0.0f,
     .maximum = 1.0f,
     .maximum_inclusive = false,
     .slider_min = 0.0f,
     .slider_max = 0.99f,
     DEEPGI_FLOAT_FIELD(radiosity.alpha)},
    {.name = "radiosity-layers",
     .label = "layers",
     .group = "radiosity",
     .owner = "radiosity",
     .help = "Deep radiosity: G-buffer layers gathered",
     .integer = true,
     .minimum = 1.0f,
     .maximum = float(limits::max_radiosity_layers),
     .slider_min = 1.0f,
     .slider_max = float(limits::max_radiosity_layers),
     .effect = drop_history,
     DEEPGI_INT_FIELD(radiosity.layers)},
    {.name = "blur-depth-tolerance",
     .label = "depth tolerance",
     .group = "blur",
     .owner = "blur",
     .help = "Blur: relative depth difference at which a tap weighs nothing",
     .minimum = 0.0f,
     .minimum_inclusive = false,
     .maximum = unlimited,
     .slider_min = 0.005f,
     .slider_max = 1.0f,
     .logarithmic = true,
     DEEPGI_FLOAT_FIELD(blur.depth_tolerance)},
    {.name = "blur-normal-power",
     .label = "normal power",
     .group = "blur",
     .owner = "blur",
     .help = "Blur: exponent on the normal agreement max(dot(n_tap, n_centre), 0)",
     .minimum = 0.0f,
     .minimum_inclusive = false,
     .maximum = unlimited,
     .slider_min = 0.5f,
     .slider_max = 64.0f,
     .logarithmic = true,
     DEEPGI_FLOAT_FIELD(blur.normal_power)},
    {.name = "blur-plane-tolerance",
     .label = "plane tolerance",
     .group = "blur",
     .owner = "blur",
     .help = "Blur: distance from the centre's tangent plane, as a fraction of its depth, at "
             "which a tap weighs nothing",
     .minimum = 0.0f,
     .minimum_inclusive = false,
     .maximum = unlimited,
     .slider_min = 0.001f,
     .slider_max = 1.0f,
     .logarithmic = true,
     DEEPGI_FLOAT_FIELD(blur.plane_tolerance)},
    {.name = "blur-extent",
     .label = "extent (x AO radius, 0: none)",
     .group = "blur",
     .owner = "blur",
     .help = "Blur: world-space reach as a fraction of the AO radius; a tap that far from the "
             "centre weighs nothing (0: no limit)",
     .minimum = 0.0f,
     .maximum = unlimited,
     .slider_min = 0.0f,
     .slider_max = 4.0f,
     DEEPGI_FLOAT_FIELD(blur.extent)},
    {.name = "reflection-layers",
     .label = "layers",
     .group = "reflection",
     .owner = "reflection",
     .help = "Mirror reflections: G-buffer layers the reflected rays are marched against",
     .integer = true,
     .minimum = 1.0f,
     .maximum = float(limits::max_reflection_layers),
     .slider_min = 1.0f,
     .slider_max = float(limits::max_reflection_layers),
     DEEPGI_INT_FIELD(reflection.layers)},
    {.name = "reflection-steps",
     .label = "steps",
     .group = "reflection",
     .owner = "reflection",
     .help = "Mirror reflections: march steps along each reflected ray",
     .integer = true,
     .minimum = 1.0f,
     .maximum = float(limits::max_reflection_steps),
     .slider_min = 4.0f,
     .slider_max = 128.0f,
     DEEPGI_INT_FIELD(reflection.steps)},
    {.name = "reflection-distance",
     .label = "distance (m, 0: auto)",
     .group = "reflection",
     .owner = "reflection",
     .help = "Mirror reflections: how far each reflected ray is marched; auto (or 0): the "
             "scene's bounding radius",
     .unit = "metres",
     .minimum = 0.0f,
     .maximum = unlimited,
     .slider_min = 0.0f,
     .slider_max = 50.0f,
     DEEPGI_FLOAT_FIELD(reflection.distance),
     .scene_fraction = auto_reflection_distance_fraction},
    {.name = "mirror-roughness",
     .label = "mirror roughness",
     .group = "reflection",
     .owner = "gbuffer",
     .help = "A material with roughnessFactor at most this and metallicFactor at least 0.5 is "
             "a mirror",
     .minimum = 0.0f,
     .maximum = 1.0f,
     .slider_min = 0.0f,
     .slider_max = 1.0f,
     DEEPGI_FLOAT_FIELD(mirror_roughness)},
}};
#pragma GCC diagnostic pop

#undef DEEPGI_FLOAT_FIELD
#undef DEEPGI_INT_FIELD

}  // namespace

float reflection_distance(const RenderSettings& settings, float scene_bounding_radius) {
    if (settings.reflection.distance > 0.0f) return settings.reflection.distance;
    return std::max(auto_reflection_distance_fraction * scene_bounding_radius, 1e-3f);
}

std::span<const NumericSetting> numeric_settings() {
    return numeric_table;
}

const NumericSetting* find_numeric_setting(std::string_view name) {
    for (const auto& setting : numeric_table)
        if (setting.name == name) return &setting;
    return nullptr;
}

std::string describe_limits(const NumericSetting& setting) {
    if (accepts_auto(setting)) {
        NumericSetting number = setting;
        number.scene_fraction = 0.0f;
        number.auto_measured = false;
        return describe_limits(number) + ", or auto";
    }
    if (setting.integer) {
        if (setting.maximum == setting.minimum + 1.0f)
            return fmt::format("{} or {}", setting.minimum, setting.maximum);
        return fmt::format("an integer in [{}, {}]", setting.minimum, setting.maximum);
    }
    if (std::isinf(setting.maximum)) {
        return fmt::format("a finite number{}{} {} {}", setting.unit.empty() ? "" : " of ",
                           setting.unit, setting.minimum_inclusive ? ">=" : ">", setting.minimum);
    }
    return fmt::format("a number in {}{}, {}{}", setting.minimum_inclusive ? "[" : "(",
                       setting.minimum, setting.maximum, setting.maximum_inclusive ? "]" : ")");
}

void check_setting(const NumericSetting& setting, double value) {
    const bool above =
        setting.minimum_inclusive ? value >= setting.minimum : value > setting.minimum;
    const bool below =
        setting.maximum_inclusive ? value <= setting.maximum : value < setting.maximum;
    const bool whole = !setting.integer || value == std::round(value);
    if (std::isfinite(value) && above && below && whole) return;
    if (setting.integer)
        throw InputError(
            fmt::format("--{} must be {}, got {}", setting.name, describe_limits(setting), value));
    throw InputError(fmt::format("--{} must be {}", setting.name, describe_limits(setting)));
}

float parse_setting_value(const NumericSetting& setting, std::string_view text) {
    if (text == "auto") {
        if (accepts_auto(setting)) return auto_length;
        throw InputError(fmt::format("--{} must be {} (auto is not one of its values)",
                                     setting.name, describe_limits(setting)));
    }
    // The whole text must be one number: no trailing characters, no hex.
    const std::string copy(text);
    std::size_t used = 0;
    double value = 0.0;
    try {
        value = std::stod(copy, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    const bool hex = copy.find_first_of("xX") != std::string::npos;
    if (copy.empty() || used != copy.size() || hex || !std::isfinite(value)) {
        throw InputError(
            fmt::format("--{} must be {}, got '{}'", setting.name, describe_limits(setting), text));
    }
    check_setting(setting, value);
    return float(value);
}

RenderSettings resolve_auto_lengths(RenderSettings settings, float scene_radius) {
    for (const NumericSetting& setting : numeric_settings()) {
        if (is_scene_length(setting) && setting.get(settings) == auto_length)
            setting.set(settings, setting.scene_fraction * scene_radius);
    }
    return settings;
}

std::vector<std::string> describe_auto_lengths(const RenderSettings& given,
                                               const RenderSettings& in_use, float scene_radius) {
    std::vector<std::string> lines;
    for (const NumericSetting& setting : numeric_settings()) {
        if (!is_scene_length(setting) || setting.get(given) != auto_length) continue;
        lines.push_back(fmt::format("{} auto = {:.4g} scene units ({} x bounding radius {:.4g})",
                                    setting.name, setting.get(in_use), setting.scene_fraction,
                                    scene_radius));
    }
    return lines;
}

}  // namespace deepgi
