// The report's stability table: renders the numerical hard cases of
// deepgi/hard_cases.hpp and turns each check of tests/runtime/stability_test.cpp
// into a row with its measured value and bound, so the report states them
// instead of only failing a test.
#include "deepgi/renderer.hpp"
#include "deepgi/report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace deepgi::report {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

using Frame = hard_cases::AoFrame;

Frame render(const Scene& scene, const RenderSettings& settings, const ShaderLoader& loader) {
    return hard_cases::render_ao(scene, settings, loader);
}

// Pixels of an AO image that are no visibility: non-finite or above 1. The
// solid-angle estimate is signed until compose clamps it (sao.frag), so a
// value below 0 is a valid estimate, as in the stability test.
long long invalid_visibility(const FloatImage& image) {
    long long count = 0;
    for (float v : image.pixels) count += !(v <= 1.0f);
    return count;
}

long long non_finite(const FloatImage& image) {
    long long count = 0;
    for (float v : image.pixels) count += !std::isfinite(v);
    return count;
}

long long invalid_pixels(const Frame& frame) {
    return invalid_visibility(frame.raw) + invalid_visibility(frame.blurred) +
           non_finite(frame.depth);
}

// Largest |a - b| over all pixels; NaN when a pixel of either is not finite,
// so a broken image can never look like agreement.
double worst_difference(const FloatImage& a, const FloatImage& b) {
    if (a.pixels.size() != b.pixels.size()) return kNaN;
    double worst = 0.0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i) {
        if (!std::isfinite(a.pixels[i]) || !std::isfinite(b.pixels[i])) return kNaN;
        worst = std::max(worst, double(std::abs(a.pixels[i] - b.pixels[i])));
    }
    return worst;
}

// hard_cases::lowest_on_surfaces, and NaN when any AV or depth pixel is invalid.
double valid_lowest_on_surfaces(const Frame& frame, int guard, long long* surface_pixels) {
    if (invalid_pixels(frame) > 0) {
        *surface_pixels = 0;
        return kNaN;
    }
    return hard_cases::lowest_on_surfaces(frame, guard, surface_pixels);
}

std::string number(double value) {
    return fmt::format("{:g}", value);
}

// A scale factor as a reader knows it: 2^-10 rather than 0.000976562.
std::string scale_label(float s) {
    const int exponent = int(std::lround(std::log2(s)));
    if (std::abs(exponent) >= 4 && std::exp2(float(exponent)) == s)
        return fmt::format("2^{}", exponent);
    return number(s);
}

class Table {
public:
    explicit Table(const std::function<void(const std::string&)>& log) : log_(log) {}

    // The estimator the rows that follow were rendered with.
    void set_method(AoMethod method) { method_ = std::string(to_string(method)); }

    void at_most(const std::string& name, const std::string& quantity, double value,
                 double tolerance) {
        add(name, quantity, value, "<=", tolerance, value <= tolerance);
    }
    void at_least(const std::string& name, const std::string& quantity, double value,
                  double tolerance) {
        add(name, quantity, value, ">=", tolerance, value >= tolerance);
    }
    std::vector<StabilityRow> take() { return std::move(rows_); }

private:
    void add(const std::string& name, const std::string& quantity, double value, const char* test,
             double tolerance, bool pass) {
        // NaN compares false either way, so it fails.
        rows_.push_back({method_, name, quantity, value, test, tolerance, pass});
        if (log_)
            log_(fmt::format("stability ({}): {}: {} = {} ({} {}) {}", method_, name, quantity,
                             number(value), test, number(tolerance), pass ? "pass" : "FAIL"));
    }

    const std::function<void(const std::string&)>& log_;
    std::string method_;
    std::vector<StabilityRow> rows_;
};

// Every case with one estimator: `base` holds it.
void run_cases(const hard_cases::Parameters& cases, const RenderSettings& base,
               const ShaderLoader& loader, Table& table) {
    namespace hc = hard_cases;
    const int guard = frame_layout(base).guard;

    // The same scene at very different scales, every length scaled along.
    for (const std::string& name : cases.scaled_scenes) {
        const Scene scene = make_reference_scene(name);
        const Frame unit = render(scene, base, loader);
        for (float s : cases.scales) {
            const Frame scaled =
                render(hc::scaled_scene(scene, s), hc::scaled_settings(base, s), loader);
            const std::string id = fmt::format("scale {} x{}", name, scale_label(s));
            // A power of two scales every float exactly: nothing may move.
            const bool exact = std::exp2(std::round(std::log2(s))) == s;
            // AV above 1, a non-finite AV or a non-finite depth fails the case too.
            const bool valid = invalid_pixels(scaled) == 0;
            table.at_most(id, "max |AV - unscaled AV|, raw",
                          valid ? worst_difference(scaled.raw, unit.raw) : kNaN,
                          exact ? 0.0 : cases.scale_tolerance);
            table.at_most(id, "max |AV - unscaled AV|, blurred",
                          valid ? worst_difference(scaled.blurred, unit.blurred) : kNaN,
                          cases.scale_tolerance);
        }
    }

    // An open floor 1 km away through a 1 mm near plane.
    for (float pitch : cases.far_pitches) {
        const Scene scene = hc::far_floor(pitch);
        for (float radius : cases.far_radii) {
            RenderSettings settings = base;
            settings.ao.radius = radius;
            long long surface = 0;
            const double lowest =
                valid_lowest_on_surfaces(render(scene, settings, loader), guard, &surface);
            const std::string id = fmt::format("far floor at 1 km, near 1 mm, pitch {}, radius {}",
                                               number(pitch), number(radius));
            table.at_least(id, "lowest AV on floor pixels", lowest,
                           cases.open_surface_min_visibility);
            table.at_least(id, "floor pixels / viewport pixels",
                           double(surface) / double(cases.width * cases.height), 0.5);
        }
    }

    // An open floor at grazing angles.
    for (float pitch : cases.grazing_pitches) {
        const Scene scene = hc::grazing_floor(pitch);
        for (int layers : cases.layers) {
            RenderSettings settings = base;
            settings.ao.layers = layers;
            long long surface = 0;
            double lowest =
                valid_lowest_on_surfaces(render(scene, settings, loader), guard, &surface);
            if (surface == 0) lowest = kNaN;  // nothing seen: the case did not happen
            table.at_least(
                fmt::format("grazing floor, pitch {}, {} layer(s)", number(pitch), layers),
                "lowest AV on floor pixels", lowest, cases.open_surface_min_visibility);
        }
    }

    // A depth discontinuity inside the guard band.
    for (int column : hc::guard_edge_columns(base)) {
        const Scene scene = hc::guard_edge(base, column);
        for (int layers : cases.layers) {
            for (float radius : cases.guard_radii) {
                RenderSettings settings = base;
                settings.ao.layers = layers;
                settings.ao.radius = radius;
                const Frame frame = render(scene, settings, loader);
                const std::string id =
                    fmt::format("guard-band edge at column {}, {} layer(s), radius {}", column,
                                layers, number(radius));
                table.at_most(id, "AV pixels non-finite or above 1", double(invalid_pixels(frame)),
                              0.0);
                if (layers == cases.layers.front() && radius == cases.guard_radii.front()) {
                    // That the discontinuity is really there: depth at the two
                    // ends of the middle row, far wall over near wall (50 / 0.3).
                    const int y = frame.depth.height / 2;
                    const double left = frame.depth.at(0, y, 0);
                    const double right = frame.depth.at(frame.depth.width - 1, y, 0);
                    table.at_least(fmt::format("guard-band edge at column {}", column),
                                   "depth ratio across the middle row (far / near)",
                                   left > 0.0 ? right / left : kNaN, 100.0);
                }
            }
        }
    }

    // Degenerate image sizes: every output of the frame.
    for (auto [width, height] : cases.tiny_sizes) {
        for (const std::string& name : cases.tiny_scenes) {
            const Scene scene = make_builtin_scene(name);
            RenderSettings settings = base;
            settings.width = width;
            settings.height = height;
            Renderer renderer(scene, settings, loader);
            renderer.render(scene.default_camera);
            long long invalid = 0;
            for (const std::string& output : renderer.pass_output_names())
                invalid += non_finite(renderer.read_pass_output(output));
            invalid += invalid_visibility(renderer.read_pass_output("ao-raw"));
            table.at_most(fmt::format("{}x{} image of {}", width, height, name),
                          "non-finite pixels in any output, or AV above 1", double(invalid), 0.0);
        }
    }
}

}  // namespace

std::vector<StabilityRow> run_stability_cases(const hard_cases::Parameters& cases,
                                              std::span<const AoMethod> methods,
                                              const std::function<void(const std::string&)>& log) {
    // The shipped tap pattern: the cases are about the build, not a pattern.
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    Table table(log);
    for (AoMethod method : methods) {
        RenderSettings base = hard_cases::base_settings(cases.width, cases.height);
        base.ao.method = method;
        base.ao.bias = default_ao_bias(method);
        table.set_method(method);
        run_cases(cases, base, loader, table);
    }
    return table.take();
}

std::string csv_field(std::string_view text) {
    if (text.find_first_of(",\"\r\n") == std::string_view::npos) return std::string(text);
    std::string quoted = "\"";
    for (char c : text) {
        if (c == '"') quoted += '"';
        quoted += c;
    }
    return quoted + "\"";
}

std::string format_stability_csv(const std::vector<StabilityRow>& rows) {
    std::string text = "ao_method,case,quantity,value,test,tolerance,pass\n";
    for (const StabilityRow& row : rows) {
        text += fmt::format("{},{},{},{},{},{},{}\n", row.ao_method, csv_field(row.case_name),
                            csv_field(row.quantity), row.value, row.test, row.tolerance,
                            row.pass ? 1 : 0);
    }
    return text;
}

std::string format_float_csv(const std::vector<spiral_float::Choice>& choices) {
    std::string text =
        "n,exact_tau,exact_K,float_tau,float_tau_exact_K,denominator,differs,exact_tie\n";
    for (const spiral_float::Choice& c : choices) {
        text +=
            fmt::format("{},{},{},{},{},{},{},{}\n", c.n, c.exact_tau, c.exact_k, c.float_tau,
                        c.float_tau_exact_k, c.denominator, c.differs() ? 1 : 0, c.tie() ? 1 : 0);
    }
    return text;
}

}  // namespace deepgi::report
