// The report's measurement loop, its error statistics and its file formats.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/reference.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/report.hpp"
#include "deepgi/settings.hpp"

#include <spiral/fileio.hpp>

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

namespace fs = std::filesystem;

namespace deepgi::report {

namespace {

// A temporal AO pass, when the build has one, publishes its accumulated
// visibility under this name; the report then fills the ref_temporal_*
// columns after a whole rotation cycle (kAccumulatedFrames).
constexpr const char* kTemporalAoOutput = "ao-temporal";
// The temporally filtered layer-0 irradiance (radiosity pass).
constexpr const char* kTemporalIrradianceOutput = "radiosity-irradiance-layer0";

// Static frames after a cut until the accumulated columns are read: the
// temporal filters then hold the mean of every rotation of the cycle
// (frame.cpp), what a still camera converges to.
constexpr int kAccumulatedFrames = 1 + DEEPGI_TEMPORAL_CYCLE;

// The ray-traced one-bounce irradiance that the radiosity gather estimates
// (viewport layout as ambient_visibility); empty when it was not traced.
std::optional<FloatImage> reference_irradiance(const ReferenceImages& images) {
    if (images.irradiance.pixels.empty()) return std::nullopt;
    return images.irradiance;
}

class ScratchFolder {
public:
    ScratchFolder() {
        static std::atomic<int> counter{0};
        path_ =
            fs::temp_directory_path() / fmt::format("deepgi-report-{}-{}", ::getpid(), counter++);
        fs::create_directories(path_);
    }
    ~ScratchFolder() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;
    const fs::path& path() const { return path_; }

private:
    fs::path path_;
};

// The build's shader folders with the scratch folder searched right after
// the top-level shader folder, so its headers win over the generated ones.
ShaderLoader loader_with_override(const fs::path& folder) {
    auto dirs = ShaderLoader::from_build_configuration().include_dirs();
    dirs.insert(dirs.begin() + 1, folder);
    return ShaderLoader(dirs);
}

void write_text(const fs::path& path, std::string_view text) {
    spiral::fileio::AtomicFile file(path);
    file.write(text);
    file.commit();
}

// Writes the AO and radiosity tap headers for a pattern at n taps.
void write_headers(const fs::path& folder, const std::string& pattern, int n) {
    const Turns turns = pattern_turns(pattern, n);
    const auto taps = spiral::codegen::spiral_taps(n, turns.p, turns.m);
    const std::string what = fmt::format("{}, {} taps, {}/{} turns", pattern, n, turns.p, turns.m);
    write_text(folder / "ao_taps.glsl", format_taps_header("AO", taps, turns, what));
    write_text(folder / "radiosity_taps.glsl", format_taps_header("RADIOSITY", taps, turns, what));
}

double median(std::vector<double> values) {
    if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
    std::sort(values.begin(), values.end());
    const std::size_t middle = values.size() / 2;
    return values.size() % 2 == 1 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

std::optional<double> finite(double value) {
    if (std::isfinite(value)) return value;
    return std::nullopt;
}

std::string file_stem(const std::string& scene) {
    std::string stem = fs::path(scene).stem().string();
    for (char& c : stem) {
        if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-') c = '-';
    }
    return stem.empty() ? "scene" : stem;
}

// What one rendered frame gives the report.
struct Frame {
    FloatImage depth;  // rasterised layer-0 depth
    FloatImage ao_raw;
    FloatImage ao_blurred;
    FloatImage radiosity_raw;
    FloatImage radiosity_blurred;
};

// The blurred AV as compose uses it: the solid-angle estimate is signed up
// to there (sao.frag) and compose clamps it to [0, 1], as
// deepgi_compare_reference does. Raw and temporal AV stay signed: they are
// the estimator's stages, whose bias the report measures.
FloatImage clamped_visibility(FloatImage image) {
    for (float& v : image.pixels) v = std::clamp(v, 0.0f, 1.0f);
    return image;
}

Frame read_frame(const Renderer& renderer) {
    return {renderer.read_pass_output("gbuffer-depth-layer0"), renderer.read_pass_output("ao-raw"),
            clamped_visibility(renderer.read_pass_output("ao-blurred")),
            renderer.read_pass_output("radiosity-raw-layer0"),
            renderer.read_pass_output("radiosity-blurred")};
}

bool has_output(const Renderer& renderer, const std::string& name) {
    const auto names = renderer.pass_output_names();
    return std::find(names.begin(), names.end(), name) != names.end();
}

// Pixels inside the viewport (the guard band excluded) where `keep` holds.
template <class Keep>
std::vector<std::uint8_t> viewport_mask(int width, int height, int guard, Keep keep) {
    std::vector<std::uint8_t> mask(std::size_t(width) * std::size_t(height), 0);
    for (int y = guard; y < height - guard; ++y) {
        for (int x = guard; x < width - guard; ++x) {
            mask[std::size_t(y) * std::size_t(width) + std::size_t(x)] = keep(x, y) ? 1 : 0;
        }
    }
    return mask;
}

double masked_mean(const FloatImage& image, const std::vector<std::uint8_t>& mask) {
    const ErrorStats stats =
        compare_images(image,
                       FloatImage{image.width, image.height, image.channels,
                                  std::vector<float>(image.pixels.size(), 0.0f)},
                       mask);
    return stats.bias;
}

// Relative to the mean of the converged image: irradiance has no natural
// unit, and the scenes differ in brightness by orders of magnitude.
ErrorStats relative(ErrorStats stats, double scale) {
    if (!(scale > 0.0)) scale = std::numeric_limits<double>::quiet_NaN();
    stats.mae /= scale;
    stats.rmse /= scale;
    stats.bias /= scale;
    return stats;
}

FloatImage crop(const FloatImage& image, int guard, const std::vector<std::uint8_t>& mask) {
    FloatImage out;
    out.width = image.width - 2 * guard;
    out.height = image.height - 2 * guard;
    out.channels = 1;
    out.pixels.resize(std::size_t(out.width) * std::size_t(out.height));
    for (int y = 0; y < out.height; ++y) {
        for (int x = 0; x < out.width; ++x) {
            const std::size_t source =
                std::size_t(y + guard) * std::size_t(image.width) + std::size_t(x + guard);
            out.pixels[std::size_t(y) * std::size_t(out.width) + std::size_t(x)] =
                mask[source] ? image.pixels[source * std::size_t(image.channels)]
                             : std::numeric_limits<float>::quiet_NaN();
        }
    }
    return out;
}

// The open-surface target (docs/deep-sao.md): pixels with nothing within r
// in the truth (AV >= 0.9999) must keep an estimate of at least 0.99.
bool is_open(const FloatImage& truth, std::size_t i) {
    return truth.pixels[i * std::size_t(truth.channels)] >= 0.9999f;
}

// The open pixels whose neighbours within `reach` pixels (a square) are open
// too; reach 0: every open pixel. The target counts reach 1 before the blur,
// where the truth's own Monte Carlo estimate reads 1 next to occluded pixels
// when an occluder's reach ends inside the pixel, and the blur's radius after
// it, which rightly averages neighbours' occlusion in, as a blur of the truth
// would (docs/deep-sao.md, "Current figures").
std::vector<std::uint8_t> open_region(const FloatImage& truth, int reach) {
    const int w = truth.width, h = truth.height;
    std::vector<std::uint8_t> region(std::size_t(w) * std::size_t(h), 0);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            bool open = true;
            for (int v = std::max(0, y - reach); open && v <= std::min(h - 1, y + reach); ++v) {
                for (int u = std::max(0, x - reach); open && u <= std::min(w - 1, x + reach); ++u)
                    open = is_open(truth, std::size_t(v) * std::size_t(w) + std::size_t(u));
            }
            region[std::size_t(y) * std::size_t(w) + std::size_t(x)] = open ? 1 : 0;
        }
    }
    return region;
}

// Pixels of mask and region, and of those, the ones whose estimate is below 0.99.
struct OpenCount {
    long long pixels = 0;
    long long below = 0;
};
OpenCount count_open(const FloatImage& estimate, const std::vector<std::uint8_t>& mask,
                     const std::vector<std::uint8_t>& region) {
    OpenCount count;
    for (std::size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i] || !region[i]) continue;
        ++count.pixels;
        count.below += estimate.pixels[i * std::size_t(estimate.channels)] < 0.99f;
    }
    return count;
}

int nearest(const std::vector<int>& values, int target) {
    int best = values.front();
    for (int v : values) {
        if (std::abs(v - target) < std::abs(best - target)) best = v;
    }
    return best;
}

}  // namespace

// ---------------------------------------------------------------------------

ErrorStats compare_images(const FloatImage& estimate, const FloatImage& truth,
                          const std::vector<std::uint8_t>& mask) {
    if (estimate.width != truth.width || estimate.height != truth.height)
        throw std::invalid_argument(fmt::format("images differ in size: {}x{} and {}x{}",
                                                estimate.width, estimate.height, truth.width,
                                                truth.height));
    const std::size_t count = std::size_t(truth.width) * std::size_t(truth.height);
    if (mask.size() != count)
        throw std::invalid_argument(
            fmt::format("mask has {} values for {} pixels", mask.size(), count));
    const int estimate_channels = std::min(estimate.channels, 3);
    const int truth_channels = std::min(truth.channels, 3);
    auto value = [](const FloatImage& image, int channels, std::size_t i) {
        double sum = 0.0;
        for (int c = 0; c < channels; ++c) sum += image.pixels[i * std::size_t(image.channels) + c];
        return sum / channels;
    };
    ErrorStats stats;
    double sum_abs = 0.0, sum_squares = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
        if (!mask[i]) continue;
        const double error =
            value(estimate, estimate_channels, i) - value(truth, truth_channels, i);
        sum_abs += std::abs(error);
        sum_squares += error * error;
        sum += error;
        ++stats.pixels;
    }
    if (stats.pixels == 0) {
        stats.mae = stats.rmse = stats.bias = std::numeric_limits<double>::quiet_NaN();
        return stats;
    }
    const double n = double(stats.pixels);
    stats.mae = sum_abs / n;
    stats.rmse = std::sqrt(sum_squares / n);
    stats.bias = sum / n;
    return stats;
}

// The frame's passes the report times, by the names the frame's timer gives
// them; each becomes the column "<pass>_ms". A name the frame does not time
// stops the report where a row is filled rather than leaving a column empty.
const std::vector<std::string>& timed_passes() {
    static const std::vector<std::string> passes = {"sao", "blur", "radiosity"};
    return passes;
}

const std::vector<std::string>& value_columns() {
    static const std::vector<std::string> columns = [] {
        std::vector<std::string> names = {"discrepancy", "turns"};
        for (const auto& pass : timed_passes()) names.push_back(pass + "_ms");
        for (const char* name : {
                 "conv_raw_mae",
                 "conv_raw_rmse",
                 "conv_blur_mae",
                 "conv_blur_rmse",
                 "ref_raw_mae",
                 "ref_raw_rmse",
                 "ref_raw_bias",
                 "ref_blur_mae",
                 "ref_blur_rmse",
                 "ref_blur_bias",
                 "ref_temporal_mae",
                 "ref_temporal_rmse",
                 "ref_temporal_bias",
                 "ref_accum_mae",
                 "ref_accum_rmse",
                 "ref_accum_bias",
                 "ref_pixels",
                 "ref_open_pixels",
                 "ref_open_raw_below",
                 "ref_open_blur_below",
                 "ref_open_accum_below",
                 "ref_open_core_raw_below",
                 "ref_open_core_blur_below",
                 "ref_open_core_accum_below",
                 "rad_conv_raw_rel_mae",
                 "rad_conv_raw_rel_rmse",
                 "rad_conv_blur_rel_mae",
                 "rad_conv_blur_rel_rmse",
                 "rad_ref_raw_rel_mae",
                 "rad_ref_raw_rel_rmse",
                 "rad_ref_raw_rel_bias",
                 "rad_ref_blur_rel_mae",
                 "rad_ref_blur_rel_rmse",
                 "rad_ref_blur_rel_bias",
                 "rad_ref_temporal_rel_mae",
                 "rad_ref_temporal_rel_rmse",
                 "rad_ref_temporal_rel_bias",
                 "rad_ref_accum_rel_mae",
                 "rad_ref_accum_rel_rmse",
                 "rad_ref_accum_rel_bias",
             })
            names.push_back(name);
        return names;
    }();
    return columns;
}

std::optional<double> Row::get(std::string_view column) const {
    for (const Value& v : values)
        if (v.column == column) return v.value;
    return std::nullopt;
}

std::string format_csv(const std::vector<Row>& rows) {
    std::string text = "scene,pattern,taps,layers,ao_method,device";
    for (const std::string& column : value_columns()) text += "," + column;
    text += "\n";
    for (const Row& row : rows) {
        text += fmt::format("{},{},{},{},{},{}", csv_field(row.scene), csv_field(row.pattern),
                            row.taps, row.layers, csv_field(row.ao_method), csv_field(row.device));
        for (const std::string& column : value_columns()) {
            const auto value = row.get(column);
            text += value ? fmt::format(",{}", *value) : ",";
        }
        text += "\n";
    }
    return text;
}

namespace {
std::string json_string(std::string_view text) {
    std::string out = "\"";
    for (char c : text) {
        if (c == '"' || c == '\\') {
            out += '\\';
            out += c;
        } else if (static_cast<unsigned char>(c) < 0x20) {
            out += fmt::format("\\u{:04x}", int(c));
        } else {
            out += c;
        }
    }
    return out + "\"";
}
}  // namespace

namespace {
std::string json_number(double value) {
    return std::isfinite(value) ? fmt::format("{}", value) : "null";
}
}  // namespace

std::string format_json(const std::vector<Row>& rows, const ReportInfo& info,
                        const std::vector<StabilityRow>& stability,
                        const std::vector<spiral_float::Choice>& float_choices) {
    std::string text = "{\"info\":{";
    text += fmt::format(
        "\"renderer\":{},\"vendor\":{},\"timing\":{},\"width\":{},\"height\":{},"
        "\"guard\":{},\"rays\":{},\"converged_taps\":{},\"warmup\":{},\"frames\":{},"
        "\"image_pattern\":{},\"image_taps\":{},\"seconds\":{}",
        json_string(info.renderer), json_string(info.vendor),
        json_string(info.cpu_clock ? "CPU clock around glFinish" : "GL timer queries"), info.width,
        info.height, info.guard, info.rays, info.converged_taps, info.warmup, info.frames,
        json_string(info.image_pattern), info.image_taps, info.seconds);
    text += "},\n\"rows\":[\n";
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const Row& row = rows[r];
        text += fmt::format(
            "{{\"scene\":{},\"pattern\":{},\"taps\":{},\"layers\":{},\"ao_method\":{},"
            "\"device\":{}",
            json_string(row.scene), json_string(row.pattern), row.taps, row.layers,
            json_string(row.ao_method), json_string(row.device));
        for (const std::string& column : value_columns()) {
            const auto value = row.get(column);
            text += fmt::format(",\"{}\":{}", column, value ? json_number(*value) : "null");
        }
        text += r + 1 < rows.size() ? "},\n" : "}\n";
    }
    text += "],\n\"stability\":[\n";
    for (std::size_t r = 0; r < stability.size(); ++r) {
        const StabilityRow& row = stability[r];
        text += fmt::format(
            "{{\"ao_method\":{},\"case\":{},\"quantity\":{},\"value\":{},\"test\":{},"
            "\"tolerance\":{},\"pass\":{}}}{}",
            json_string(row.ao_method), json_string(row.case_name), json_string(row.quantity),
            json_number(row.value), json_string(row.test), json_number(row.tolerance),
            row.pass ? "true" : "false", r + 1 < stability.size() ? ",\n" : "\n");
    }
    // Only the n where the choices differ; float_vs_exact.csv has every n.
    int differing = 0, larger_k = 0;
    std::string listed;
    for (const spiral_float::Choice& c : float_choices) {
        if (!c.differs()) continue;
        ++differing;
        larger_k += !c.tie();
        listed += fmt::format(
            "{}{{\"n\":{},\"exact_tau\":{},\"exact_K\":{},\"float_tau\":{},"
            "\"float_tau_exact_K\":{},\"denominator\":{}}}",
            listed.empty() ? "" : ",\n", c.n, c.exact_tau, c.exact_k, c.float_tau,
            c.float_tau_exact_k, c.denominator);
    }
    text += fmt::format(
        "],\n\"float_vs_exact\":{{\"max_n\":{},\"differing\":{},\"larger_K\":{},"
        "\"rows\":[\n{}{}]}}}}\n",
        float_choices.size(), differing, larger_k, listed, listed.empty() ? "" : "\n");
    return text;
}

void validate(const ReportOptions& options) {
    if (options.scenes.empty()) throw InputError("--scenes needs at least one scene");
    if (options.taps.empty()) throw InputError("--taps needs at least one tap count");
    for (int n : options.taps) {
        if (n < 1 || n > 1024)
            throw InputError(fmt::format("--taps {} is out of range (1 to 1024)", n));
    }
    if (options.patterns.empty()) throw InputError("--patterns needs at least one pattern");
    for (const std::string& name : options.patterns) {
        if (!is_pattern_name(name))
            throw InputError(
                fmt::format("--patterns '{}' is not one of optimal, tau1, golden, "
                            "m2, m4, m8",
                            name));
    }
    if (options.layers.empty()) throw InputError("--layers needs at least one layer count");
    if (options.ao_methods.empty()) throw InputError("--ao-methods needs at least one method");
    for (std::size_t i = 0; i < options.ao_methods.size(); ++i) {
        for (std::size_t j = 0; j < i; ++j) {
            if (options.ao_methods[i] == options.ao_methods[j])
                throw InputError(
                    fmt::format("--ao-methods names '{}' twice", to_string(options.ao_methods[i])));
        }
    }
    for (int layers : options.layers) {
        if (layers < 1 || layers > limits::max_ao_layers)
            throw InputError(fmt::format("--layers {} is out of range (1 to {})", layers,
                                         limits::max_ao_layers));
    }
    if (options.width < 8 || options.height < 8 || options.width > 4096 || options.height > 4096)
        throw InputError(fmt::format("--size {}x{} is out of range (8 to 4096 per side)",
                                     options.width, options.height));
    if (options.rays < 0 || options.rays > 1 << 20)
        throw InputError(fmt::format("--rays {} is out of range (0 to 1048576)", options.rays));
    if (options.converged_taps < 1 || options.converged_taps > 1024)
        throw InputError(
            fmt::format("--converged-taps {} is out of range (1 to 1024)", options.converged_taps));
    if (options.frames < 1 || options.frames > 1000)
        throw InputError(fmt::format("--frames {} is out of range (1 to 1000)", options.frames));
    if (options.warmup < 0 || options.warmup > 1000)
        throw InputError(fmt::format("--warmup {} is out of range (0 to 1000)", options.warmup));
    if (options.threads < 0 || options.threads > 1024)
        throw InputError(
            fmt::format("--threads {} must lie in [0, 1024] (0: all)", options.threads));
    if (options.float_max_n < 0 || options.float_max_n > 4096)
        throw InputError(
            fmt::format("--float-max-n {} is out of range (0 to 4096)", options.float_max_n));
    if (options.output.empty()) throw InputError("report needs --output DIR");
    if (fs::exists(options.output) && !fs::is_directory(options.output))
        throw InputError(fmt::format("--output '{}' is not a directory", options.output.string()));
    const fs::path parent =
        options.output.has_parent_path() ? options.output.parent_path() : fs::path(".");
    if (!fs::is_directory(parent))
        throw InputError(fmt::format("--output '{}': directory '{}' does not exist",
                                     options.output.string(), parent.string()));
    // Scenes last: loading a file can be slow, and a bad name is then found
    // before anything is rendered.
    for (const std::string& scene : options.scenes) (void)load_scene(scene);
}

ReportResult run_report(const ReportOptions& options) {
    validate(options);
    const auto start = std::chrono::steady_clock::now();
    auto log = [&](const std::string& line) {
        if (options.log) options.log(line);
    };

    RenderSettings settings;
    settings.width = options.width;
    settings.height = options.height;
    // One bounce: the truth is one-bounce irradiance, and after the cycle of
    // static frames the history would otherwise also hold the bounces that
    // rho_prop feeds back. A first frame has no history, and the gather does
    // the same work either way, so no other column moves.
    settings.radiosity.rho_prop = 0.0f;
    deepgi::validate(settings);
    const FrameLayout layout = frame_layout(settings);
    const int guard = layout.guard;
    const int internal_width = layout.internal_width;
    const int internal_height = layout.internal_height;

    ScratchFolder headers;
    const ShaderLoader loader = loader_with_override(headers.path());
    const int image_taps = nearest(options.taps, options.image_taps);
    const std::string image_pattern = std::find(options.patterns.begin(), options.patterns.end(),
                                                options.image_pattern) != options.patterns.end()
                                          ? options.image_pattern
                                          : options.patterns.front();
    const int image_layers = *std::max_element(options.layers.begin(), options.layers.end());

    fs::create_directories(options.output / "images");
    write_text(options.output / "discrepancy.csv", format_discrepancy_csv(options.patterns, 64));

    ReportResult result;
    const ContextInfo context = query_context_info();
    result.info.renderer = context.renderer;
    result.info.vendor = context.vendor;
    result.info.width = options.width;
    result.info.height = options.height;
    result.info.guard = guard;
    result.info.rays = options.rays;
    result.info.converged_taps = options.converged_taps;
    result.info.warmup = options.warmup;
    result.info.frames = options.frames;
    result.info.image_pattern = image_pattern;
    result.info.image_taps = image_taps;

    for (const std::string& scene_name : options.scenes) {
        const Scene scene = load_scene(scene_name);
        const Camera& camera = scene.default_camera;

        // The ray-traced truth on the same pixel grid.
        ReferenceSettings reference;
        reference.render = settings;
        // A fixed ray count per pixel, or with --rays 0 the budgets of
        // `deepgi reference` (rays until the standard error is below their
        // targets), so that the truth's own noise stays out of the error.
        if (options.rays > 0) {
            reference.rays.min_rays = options.rays;
            reference.rays.max_rays = options.rays;
            reference.rays.target_error = 0.0;
            reference.irradiance_rays.min_rays = options.rays;
            reference.irradiance_rays.max_rays = options.rays;
            reference.irradiance_rays.ceiling_max_rays = options.rays;
            reference.irradiance_rays.target_relative_error = 0.0;
            reference.irradiance_rays.target_absolute_error = 0.0;
        }
        // One-bounce irradiance within the gather's radius: the rows compare
        // the first frame after a cut, which has no bounce history, so one
        // bounce is what it estimates.
        reference.irradiance = true;
        reference.radiosity_radius = settings.radiosity.radius;
        reference.seed = options.seed;
        reference.threads = options.threads;
        const auto reference_start = std::chrono::steady_clock::now();
        const RayScene rays(scene);
        const ReferenceImages truth = render_reference(rays, camera, reference);
        const std::optional<FloatImage> truth_irradiance = reference_irradiance(truth);
        // Open pixels: all of them, and those the target counts before and
        // after the blur. They depend on the truth alone.
        const auto open_pixels = open_region(truth.ambient_visibility, 0);
        const auto raw_open_region = open_region(truth.ambient_visibility, 1);
        const auto blur_open_region =
            open_region(truth.ambient_visibility, DEEPGI_REPORT_BLUR_RADIUS);
        log(fmt::format(
            "{}: reference, {} rays per pixel, {:.1f} s", scene_name,
            options.rays > 0 ? std::to_string(options.rays) : std::string("adaptive"),
            std::chrono::duration<double>(std::chrono::steady_clock::now() - reference_start)
                .count()));

        // The converged screen-space result, one per layer count: AO and
        // radiosity at many taps. Radiosity does not depend on the AO method,
        // so a method that gathers no AO taps (it has no converged AO: it would
        // equal itself) keeps the previous method's frames for its radiosity.
        std::map<int, Frame> converged;
        for (std::size_t method_index = 0; method_index < options.ao_methods.size();
             ++method_index) {
            const AoMethod method = options.ao_methods[method_index];
            const std::string method_name(to_string(method));
            RenderSettings method_settings = settings;
            method_settings.ao.method = method;
            method_settings.ao.bias = default_ao_bias(method);
            // The AO and the radiosity gather at the row's layer count.
            auto with_layers = [&](int layers) {
                RenderSettings s = method_settings;
                s.ao.layers = layers;
                s.radiosity.layers = layers;
                return s;
            };
            // The first method compares the patterns; the others are curves
            // (or, for the march, one point) beside it (ReportOptions).
            const bool gathers_taps = ao_method_gathers_taps(method);
            const std::vector<std::string> patterns =
                method_index == 0 ? options.patterns : std::vector<std::string>{image_pattern};
            const std::vector<int> tap_counts =
                gathers_taps ? options.taps : std::vector<int>{image_taps};

            if (gathers_taps || converged.empty()) {
                write_headers(headers.path(), "optimal", options.converged_taps);
                Renderer renderer(scene, method_settings, loader);
                for (int layers : options.layers) {
                    renderer.set_settings(with_layers(layers));
                    renderer.render(camera, CameraMotion::cut);
                    converged[layers] = read_frame(renderer);
                }
            }

            for (const std::string& pattern : patterns) {
                for (int n : tap_counts) {
                    write_headers(headers.path(), pattern, n);
                    const Turns turns = pattern_turns(pattern, n);
                    const double discrepancy = spiral::discrepancy(n, turns.p, turns.m).value();
                    Renderer renderer(scene, method_settings, loader);
                    result.info.cpu_clock = renderer.timing_uses_cpu_clock();
                    for (int layers : options.layers) {
                        renderer.set_settings(with_layers(layers));
                        // Errors from the first frame after a cut: no history in it.
                        renderer.render(camera, CameraMotion::cut);
                        const Frame frame = read_frame(renderer);
                        const Frame& reference_frame = converged.at(layers);

                        const auto surface = viewport_mask(
                            internal_width, internal_height, guard,
                            [&](int x, int y) { return frame.depth.at(x, y) > 0.0f; });
                        // Only where raster and ray tracer see the same surface:
                        // silhouette pixels would compare different points.
                        const auto agreed = viewport_mask(
                            internal_width, internal_height, guard, [&](int x, int y) {
                                const float a = frame.depth.at(x, y);
                                const float b = truth.depth_layer0.at(x, y);
                                return a > 0.0f && b > 0.0f && std::abs(a - b) <= 1e-3f * b;
                            });

                        const ErrorStats conv_raw =
                            compare_images(frame.ao_raw, reference_frame.ao_raw, surface);
                        const ErrorStats conv_blur =
                            compare_images(frame.ao_blurred, reference_frame.ao_blurred, surface);
                        const ErrorStats ref_raw =
                            compare_images(frame.ao_raw, truth.ambient_visibility, agreed);
                        const ErrorStats ref_blur =
                            compare_images(frame.ao_blurred, truth.ambient_visibility, agreed);
                        const double radiosity_scale =
                            masked_mean(reference_frame.radiosity_raw, surface);
                        const double radiosity_blur_scale =
                            masked_mean(reference_frame.radiosity_blurred, surface);
                        const ErrorStats rad_raw =
                            relative(compare_images(frame.radiosity_raw,
                                                    reference_frame.radiosity_raw, surface),
                                     radiosity_scale);
                        const ErrorStats rad_blur =
                            relative(compare_images(frame.radiosity_blurred,
                                                    reference_frame.radiosity_blurred, surface),
                                     radiosity_blur_scale);
                        // Radiosity against the truth, relative to the truth's mean
                        // over the compared pixels (the same for every stage).
                        const double truth_irradiance_mean =
                            truth_irradiance ? masked_mean(*truth_irradiance, agreed) : 0.0;
                        auto against_irradiance =
                            [&](const FloatImage& estimate) -> std::optional<ErrorStats> {
                            if (!truth_irradiance) return std::nullopt;
                            return relative(compare_images(estimate, *truth_irradiance, agreed),
                                            truth_irradiance_mean);
                        };
                        const std::optional<ErrorStats> rad_ref_raw =
                            against_irradiance(frame.radiosity_raw);
                        const std::optional<ErrorStats> rad_ref_blur =
                            against_irradiance(frame.radiosity_blurred);

                        if (pattern == image_pattern && n == image_taps && layers == image_layers) {
                            const std::string stem = file_stem(scene_name);
                            write_pfm(options.output / "images" / (stem + "-truth.pfm"),
                                      crop(truth.ambient_visibility, guard, agreed));
                            write_pfm(options.output / "images" /
                                          (stem + "-estimate-" + method_name + ".pfm"),
                                      crop(frame.ao_blurred, guard, agreed));
                        }

                        // Continuous static frames after the cut: the timed ones
                        // (so history-based passes do what they do in an
                        // animation), and at least the rest of a rotation cycle,
                        // after which the accumulated errors are read.
                        std::map<std::string, std::vector<double>> samples;
                        const int timed_end = options.warmup + options.frames;
                        std::optional<ErrorStats> ref_temporal, ref_accum, rad_ref_temporal,
                            rad_ref_accum;
                        std::optional<double> open_accum, open_core_accum;
                        for (int i = 0; i < std::max(timed_end, kAccumulatedFrames - 1); ++i) {
                            renderer.render(camera);
                            if (i >= options.warmup && i < timed_end) {
                                for (const auto& timing : renderer.last_timings())
                                    samples[timing.pass].push_back(timing.milliseconds);
                            }
                            if (i + 2 != kAccumulatedFrames) continue;  // the cut was frame 1
                            if (has_output(renderer, kTemporalAoOutput)) {
                                ref_temporal =
                                    compare_images(renderer.read_pass_output(kTemporalAoOutput),
                                                   truth.ambient_visibility, agreed);
                            }
                            const FloatImage accumulated =
                                clamped_visibility(renderer.read_pass_output("ao-blurred"));
                            ref_accum =
                                compare_images(accumulated, truth.ambient_visibility, agreed);
                            open_accum = double(count_open(accumulated, agreed, open_pixels).below);
                            open_core_accum =
                                double(count_open(accumulated, agreed, blur_open_region).below);
                            if (has_output(renderer, kTemporalIrradianceOutput)) {
                                rad_ref_temporal = against_irradiance(
                                    renderer.read_pass_output(kTemporalIrradianceOutput));
                            }
                            rad_ref_accum =
                                against_irradiance(renderer.read_pass_output("radiosity-blurred"));
                        }

                        Row row;
                        row.scene = scene_name;
                        row.pattern = pattern;
                        row.taps = n;
                        row.layers = layers;
                        row.ao_method = method_name;
                        row.device = result.info.renderer;
                        auto add = [&](const std::string& column, std::optional<double> value) {
                            row.values.push_back({column, value ? finite(*value) : std::nullopt});
                        };
                        auto ms = [&](const std::string& pass) -> std::optional<double> {
                            const auto it = samples.find(pass);
                            if (it == samples.end()) return std::nullopt;
                            return median(it->second);
                        };
                        auto field = [](const std::optional<ErrorStats>& s,
                                        double ErrorStats::*member) -> std::optional<double> {
                            if (!s) return std::nullopt;
                            return (*s).*member;
                        };
                        add("discrepancy", discrepancy);
                        add("turns", turns.value());
                        for (const auto& pass : timed_passes()) {
                            if (samples.find(pass) == samples.end())
                                throw std::runtime_error(
                                    fmt::format("the frame timed no pass named '{}' (column {}_ms)",
                                                pass, pass));
                            add(pass + "_ms", ms(pass));
                        }
                        auto if_gathers = [&](double value) -> std::optional<double> {
                            if (!gathers_taps) return std::nullopt;
                            return value;
                        };
                        add("conv_raw_mae", if_gathers(conv_raw.mae));
                        add("conv_raw_rmse", if_gathers(conv_raw.rmse));
                        add("conv_blur_mae", if_gathers(conv_blur.mae));
                        add("conv_blur_rmse", if_gathers(conv_blur.rmse));
                        // MAE, RMSE and bias of one comparison; empty cells where
                        // the build or the reference cannot measure it.
                        auto add_stats = [&](const std::string& prefix,
                                             const std::optional<ErrorStats>& stats) {
                            add(prefix + "_mae", field(stats, &ErrorStats::mae));
                            add(prefix + "_rmse", field(stats, &ErrorStats::rmse));
                            add(prefix + "_bias", field(stats, &ErrorStats::bias));
                        };
                        add_stats("ref_raw", ref_raw);
                        add_stats("ref_blur", ref_blur);
                        add_stats("ref_temporal", ref_temporal);
                        add_stats("ref_accum", ref_accum);
                        add("ref_pixels", double(ref_blur.pixels));
                        const OpenCount open_raw = count_open(frame.ao_raw, agreed, open_pixels);
                        add("ref_open_pixels", double(open_raw.pixels));
                        add("ref_open_raw_below", double(open_raw.below));
                        add("ref_open_blur_below",
                            double(count_open(frame.ao_blurred, agreed, open_pixels).below));
                        add("ref_open_accum_below", open_accum);
                        add("ref_open_core_raw_below",
                            double(count_open(frame.ao_raw, agreed, raw_open_region).below));
                        add("ref_open_core_blur_below",
                            double(count_open(frame.ao_blurred, agreed, blur_open_region).below));
                        add("ref_open_core_accum_below", open_core_accum);
                        add("rad_conv_raw_rel_mae", rad_raw.mae);
                        add("rad_conv_raw_rel_rmse", rad_raw.rmse);
                        add("rad_conv_blur_rel_mae", rad_blur.mae);
                        add("rad_conv_blur_rel_rmse", rad_blur.rmse);
                        add_stats("rad_ref_raw_rel", rad_ref_raw);
                        add_stats("rad_ref_blur_rel", rad_ref_blur);
                        add_stats("rad_ref_temporal_rel", rad_ref_temporal);
                        add_stats("rad_ref_accum_rel", rad_ref_accum);
                        log(fmt::format(
                            "{} {} {} n={} layers={}: sao {:.2f} ms, MAE vs converged {}, vs "
                            "reference {:.4f} raw {:.4f} blurred",
                            scene_name, method_name, pattern, n, layers, ms("sao").value_or(0.0),
                            gathers_taps ? fmt::format("{:.4f}", conv_raw.mae) : std::string("-"),
                            ref_raw.mae, ref_blur.mae));
                        result.rows.push_back(std::move(row));
                    }
                }
            }
        }
    }

    if (options.stability) {
        const auto stability_start = std::chrono::steady_clock::now();
        result.stability =
            run_stability_cases(hard_cases::Parameters{}, options.ao_methods, options.log);
        const auto passing = std::count_if(result.stability.begin(), result.stability.end(),
                                           [](const StabilityRow& row) { return row.pass; });
        log(fmt::format(
            "stability: {} of {} checks pass, {:.1f} s", passing, result.stability.size(),
            std::chrono::duration<double>(std::chrono::steady_clock::now() - stability_start)
                .count()));
        write_text(options.output / "stability.csv", format_stability_csv(result.stability));
    } else {
        // A skipped table must not be read from an earlier run into the same folder.
        fs::remove(options.output / "stability.csv");
    }
    if (options.float_max_n > 0) {
        const auto float_start = std::chrono::steady_clock::now();
        result.float_choices =
            spiral_float::compare_float_search(options.float_max_n, options.threads);
        const auto differing =
            std::count_if(result.float_choices.begin(), result.float_choices.end(),
                          [](const spiral_float::Choice& c) { return c.differs(); });
        log(fmt::format(
            "float vs exact: double picks another tau at {} of n = 1..{}, {:.1f} s", differing,
            options.float_max_n,
            std::chrono::duration<double>(std::chrono::steady_clock::now() - float_start).count()));
        write_text(options.output / "float_vs_exact.csv", format_float_csv(result.float_choices));
    } else {
        fs::remove(options.output / "float_vs_exact.csv");
    }

    result.info.seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    write_text(options.output / "report.csv", format_csv(result.rows));
    write_text(options.output / "report.json",
               format_json(result.rows, result.info, result.stability, result.float_choices));
    return result;
}

}  // namespace deepgi::report
