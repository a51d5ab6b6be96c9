// Name tables and the validation of every setting.
#include "deepgi/settings.hpp"

#include "deepgi/errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <charconv>
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
    // Digits, 'x', digits: no sign, no spaces, no other base. A side too large
    // for any allowed size is out of range, not malformed.
    const std::size_t cross = text.find('x');
    auto digits_only = [](std::string_view digits) {
        return !digits.empty() && std::all_of(digits.begin(), digits.end(),
                                              [](char c) { return c >= '0' && c <= '9'; });
    };
    if (cross == std::string_view::npos || !digits_only(text.substr(0, cross)) ||
        !digits_only(text.substr(cross + 1))) {
        throw InputError(
            fmt::format("{} '{}' is not WIDTHxHEIGHT (for example 1280x720)", option, text));
    }
    // Digits only, so from_chars fails only past the int range: out of range too.
    auto side = [](std::string_view digits) {
        int value = 0;
        const auto [end, error] =
            std::from_chars(digits.data(), digits.data() + digits.size(), value);
        return error == std::errc() ? value : limits::max_image_side + 1;
    };
    const ImageSize size{side(text.substr(0, cross)), side(text.substr(cross + 1))};
    if (size.width < 1 || size.height < 1 || size.width > limits::max_image_side ||
        size.height > limits::max_image_side) {
        throw InputError(fmt::format("{} {} is out of range (1 to {} per side)", option, text,
                                     limits::max_image_side));
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

float reflection_distance(const RenderSettings& settings, float scene_bounding_radius) {
    if (settings.reflection.distance > 0.0f) return settings.reflection.distance;
    return std::max(auto_reflection_distance_fraction * scene_bounding_radius, 1e-3f);
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

namespace {

// Settings hold floats: a finite double past the largest float would become
// infinite once stored.
bool past_float(double value) {
    return std::isfinite(value) && std::abs(value) > double(std::numeric_limits<float>::max());
}

bool within_limits(const NumericSetting& setting, double value) {
    const bool above =
        setting.minimum_inclusive ? value >= setting.minimum : value > setting.minimum;
    const bool below =
        setting.maximum_inclusive ? value <= setting.maximum : value < setting.maximum;
    const bool whole = !setting.integer || value == std::round(value);
    return std::isfinite(value) && !past_float(value) && above && below && whole;
}

// Why a finite number that meets the row's limits on paper is refused.
const char* float_range_hint(double value) {
    return past_float(value) ? " (past the largest float, 3.4e38)" : "";
}

}  // namespace

void check_setting(const NumericSetting& setting, double value) {
    if (within_limits(setting, value)) return;
    if (setting.integer)
        throw InputError(fmt::format("--{} must be {}, got {}{}", setting.name,
                                     describe_limits(setting), value, float_range_hint(value)));
    throw InputError(fmt::format("--{} must be {}{}", setting.name, describe_limits(setting),
                                 float_range_hint(value)));
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
    // The message quotes the text as given, whatever was wrong with it.
    if (copy.empty() || used != copy.size() || hex || !within_limits(setting, value)) {
        const bool number = used == copy.size() && !hex;
        throw InputError(fmt::format("--{} must be {}, got '{}'{}", setting.name,
                                     describe_limits(setting), text,
                                     number ? float_range_hint(value) : ""));
    }
    return float(value);
}

float auto_length_value(const NumericSetting& setting, const SceneScale& scale) {
    const float length = setting.scene_fraction * scale.bounding_radius;
    if (setting.extent_fraction <= 0.0f) return length;
    // A single quad has no thickness; its extent is taken as 0.2 R.
    constexpr float flat_extent_fraction = 0.2f;
    const float extent =
        std::max(scale.smallest_extent, flat_extent_fraction * scale.bounding_radius);
    return std::min(length, setting.extent_fraction * extent);
}

RenderSettings with_auto_lengths(RenderSettings settings) {
    for (const NumericSetting& setting : numeric_settings())
        if (is_scene_length(setting)) setting.set(settings, auto_length);
    return settings;
}

RenderSettings resolve_auto_lengths(RenderSettings settings, const SceneScale& scale) {
    for (const NumericSetting& setting : numeric_settings()) {
        if (is_scene_length(setting) && setting.get(settings) == auto_length)
            setting.set(settings, auto_length_value(setting, scale));
    }
    return settings;
}

std::vector<std::string> describe_auto_lengths(const RenderSettings& given,
                                               const RenderSettings& in_use,
                                               const SceneScale& scale) {
    std::vector<std::string> lines;
    for (const NumericSetting& setting : numeric_settings()) {
        if (!is_scene_length(setting) || setting.get(given) != auto_length) continue;
        std::string rule = fmt::format("{} x bounding radius {:.4g}", setting.scene_fraction,
                                       scale.bounding_radius);
        if (setting.extent_fraction > 0.0f)
            rule = fmt::format("{}, at most {} x smallest extent {:.4g}", rule,
                               setting.extent_fraction, scale.smallest_extent);
        lines.push_back(fmt::format("{} auto = {:.4g} scene units ({})", setting.name,
                                    setting.get(in_use), rule));
    }
    return lines;
}

}  // namespace deepgi
