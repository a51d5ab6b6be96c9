// Name tables and the validation of every setting.
#include "deepgi/settings.hpp"

#include "deepgi/errors.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <string>

namespace deepgi {

namespace {

constexpr std::array<EnumName<Generator>, 3> generator_table = {{
    {Generator::peel, "peel"},
    {Generator::previous, "previous"},
    {Generator::reproject, "reproject"},
}};

constexpr std::array<EnumName<DebugView>, 19> view_table = {{
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
}};

constexpr std::array<EnumName<TimingMode>, 3> timing_table = {{
    {TimingMode::automatic, "auto"},
    {TimingMode::cpu, "cpu"},
    {TimingMode::gpu, "gpu"},
}};

constexpr std::array<EnumName<AoMethod>, 3> ao_method_table = {{
    {AoMethod::solid_angle, "solid-angle"},
    {AoMethod::march, "march"},
    {AoMethod::published, "published"},
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

bool finite_at_least(float value, float minimum) {
    return std::isfinite(value) && value >= minimum;
}
bool finite_positive(float value) {
    return std::isfinite(value) && value > 0.0f;
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
    if (!(settings.guard_band_fraction >= 0.0f &&
          settings.guard_band_fraction <= limits::max_guard_band_fraction)) {
        throw InputError(
            fmt::format("--guard-band must be in [0, {}]", limits::max_guard_band_fraction));
    }
    check_enum("--generator", settings.generator);
    check_enum("--view", settings.view);
    check_enum("--timing", settings.timing);
    check_enum("--ao-method", settings.ao.method);
    check_enum("--radiosity-method", settings.radiosity.method);
    if (!finite_at_least(settings.min_separation, 0.0f))
        throw InputError("--min-separation must be a finite number of metres >= 0");
    if (!finite_positive(settings.exposure))
        throw InputError("--exposure must be a finite number > 0");
    if (settings.shadow_map_size < limits::min_shadow_map_size ||
        settings.shadow_map_size > limits::max_shadow_map_size) {
        throw InputError(fmt::format("shadow map size must be in [{}, {}]",
                                     limits::min_shadow_map_size, limits::max_shadow_map_size));
    }
    const AoSettings& ao = settings.ao;
    if (!finite_positive(ao.radius))
        throw InputError("--ao-radius must be a finite number of metres > 0");
    if (!finite_at_least(ao.bias, 0.0f))
        throw InputError("--ao-bias must be a finite number of metres >= 0");
    if (!finite_positive(ao.intensity))
        throw InputError("--ao-intensity must be a finite number > 0");
    if (!finite_at_least(ao.q, limits::min_ao_q))
        throw InputError(
            fmt::format("--ao-q must be a finite number of pixels >= {}", limits::min_ao_q));
    if (ao.layers < 1 || ao.layers > limits::max_ao_layers) {
        throw InputError(
            fmt::format("--ao-layers must be 1 or {}, got {}", limits::max_ao_layers, ao.layers));
    }
    if (!finite_positive(ao.thickness))
        throw InputError("--ao-thickness must be a finite number of metres > 0");
    if (ao.max_mip_level < 0 || ao.max_mip_level > limits::max_ao_mip_level) {
        throw InputError(fmt::format("--ao-max-mip must be in [0, {}], got {}",
                                     limits::max_ao_mip_level, ao.max_mip_level));
    }
    const RadiositySettings& radiosity = settings.radiosity;
    auto unit_interval = [](float value) {
        return std::isfinite(value) && value >= 0.0f && value <= 1.0f;
    };
    if (!finite_positive(radiosity.radius))
        throw InputError("--radiosity-radius must be a finite number of metres > 0");
    if (!unit_interval(radiosity.boost))
        throw InputError("--radiosity-boost must be a number in [0, 1]");
    if (!finite_positive(radiosity.tap_clamp))
        throw InputError("--radiosity-clamp must be a finite number > 0");
    if (!std::isfinite(settings.ao.alpha) || settings.ao.alpha < 0.0f || settings.ao.alpha >= 1.0f)
        throw InputError("--ao-alpha must be a number in [0, 1)");
    if (!std::isfinite(radiosity.alpha) || radiosity.alpha < 0.0f || radiosity.alpha >= 1.0f)
        throw InputError("--radiosity-alpha must be a number in [0, 1)");
    const BlurSettings& blur = settings.blur;
    if (!finite_positive(blur.depth_tolerance))
        throw InputError("--blur-depth-tolerance must be a finite number > 0");
    if (!finite_positive(blur.normal_power))
        throw InputError("--blur-normal-power must be a finite number > 0");
    if (!finite_positive(blur.plane_tolerance))
        throw InputError("--blur-plane-tolerance must be a finite number > 0");
    if (!std::isfinite(blur.extent) || blur.extent < 0.0f)
        throw InputError("--blur-extent must be a finite number >= 0");
    if (!unit_interval(radiosity.rho_prop))
        throw InputError("--rho-prop must be a number in [0, 1]");
    if (radiosity.layers < 1 || radiosity.layers > limits::max_radiosity_layers) {
        throw InputError(fmt::format("--radiosity-layers must be 1 or {}, got {}",
                                     limits::max_radiosity_layers, radiosity.layers));
    }
}

namespace {

// A float field's accessors, as plain function pointers for the table.
#define DEEPGI_FLOAT_FIELD(member)                           \
    [](const RenderSettings& s) { return float(s.member); }, \
        [](RenderSettings& s, float value) { s.member = value; }
#define DEEPGI_INT_FIELD(member)                             \
    [](const RenderSettings& s) { return float(s.member); }, \
        [](RenderSettings& s, float value) { s.member = int(std::lround(value)); }

// Slider ranges sit inside validate()'s limits; where validate() has no upper
// limit the slider stops at what is still useful in the built-in scenes.
const std::array<NumericSetting, 22> numeric_table = {{
    {"min-separation", "min separation (m)", "frame", false, 0.0f, 2.0f, false,
     DEEPGI_FLOAT_FIELD(min_separation)},
    {"exposure", "exposure", "frame", false, 0.05f, 8.0f, true, DEEPGI_FLOAT_FIELD(exposure)},
    {"guard-band", "guard band (* height)", "frame", false, 0.0f, limits::max_guard_band_fraction,
     false, DEEPGI_FLOAT_FIELD(guard_band_fraction)},
    {"shadow-map-size", "shadow map size (px)", "frame", true, float(limits::min_shadow_map_size),
     4096.0f, true, DEEPGI_INT_FIELD(shadow_map_size)},
    {"ao-radius", "radius (m)", "ao", false, 0.01f, 10.0f, true, DEEPGI_FLOAT_FIELD(ao.radius)},
    {"ao-bias", "bias (m)", "ao", false, 0.0f, 0.5f, false, DEEPGI_FLOAT_FIELD(ao.bias)},
    {"ao-intensity", "intensity", "ao", false, 0.1f, 8.0f, true, DEEPGI_FLOAT_FIELD(ao.intensity)},
    {"ao-q", "q (px per MIP)", "ao", false, limits::min_ao_q, 64.0f, true,
     DEEPGI_FLOAT_FIELD(ao.q)},
    {"ao-layers", "layers", "ao", true, 1.0f, float(limits::max_ao_layers), false,
     DEEPGI_INT_FIELD(ao.layers)},
    {"ao-max-mip", "max MIP level", "ao", true, 0.0f, float(limits::max_ao_mip_level), false,
     DEEPGI_INT_FIELD(ao.max_mip_level)},
    {"ao-alpha", "temporal alpha", "ao", false, 0.0f, 0.99f, false, DEEPGI_FLOAT_FIELD(ao.alpha)},
    {"ao-thickness", "thickness (m, march)", "ao", false, 0.01f, 1.0f, true,
     DEEPGI_FLOAT_FIELD(ao.thickness)},
    {"radiosity-radius", "radius (m)", "radiosity", false, 0.05f, 10.0f, true,
     DEEPGI_FLOAT_FIELD(radiosity.radius)},
    {"radiosity-boost", "boost", "radiosity", false, 0.0f, 1.0f, false,
     DEEPGI_FLOAT_FIELD(radiosity.boost)},
    {"radiosity-clamp", "tap clamp", "radiosity", false, 0.1f, 100.0f, true,
     DEEPGI_FLOAT_FIELD(radiosity.tap_clamp)},
    {"rho-prop", "rho_prop (bounces)", "radiosity", false, 0.0f, 1.0f, false,
     DEEPGI_FLOAT_FIELD(radiosity.rho_prop)},
    {"radiosity-alpha", "temporal alpha", "radiosity", false, 0.0f, 0.99f, false,
     DEEPGI_FLOAT_FIELD(radiosity.alpha)},
    {"radiosity-layers", "layers", "radiosity", true, 1.0f, float(limits::max_radiosity_layers),
     false, DEEPGI_INT_FIELD(radiosity.layers)},
    {"blur-depth-tolerance", "depth tolerance", "blur", false, 0.005f, 1.0f, true,
     DEEPGI_FLOAT_FIELD(blur.depth_tolerance)},
    {"blur-normal-power", "normal power", "blur", false, 0.5f, 64.0f, true,
     DEEPGI_FLOAT_FIELD(blur.normal_power)},
    {"blur-plane-tolerance", "plane tolerance (m)", "blur", false, 0.001f, 1.0f, true,
     DEEPGI_FLOAT_FIELD(blur.plane_tolerance)},
    {"blur-extent", "extent (x AO radius, 0: none)", "blur", false, 0.0f, 4.0f, false,
     DEEPGI_FLOAT_FIELD(blur.extent)},
}};

#undef DEEPGI_FLOAT_FIELD
#undef DEEPGI_INT_FIELD

}  // namespace

std::span<const NumericSetting> numeric_settings() {
    return numeric_table;
}

const NumericSetting* find_numeric_setting(std::string_view name) {
    for (const auto& setting : numeric_table)
        if (setting.name == name) return &setting;
    return nullptr;
}

}  // namespace deepgi
