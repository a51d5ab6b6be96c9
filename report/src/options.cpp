// The report's options, checked before anything is rendered: one line naming
// the bad option (InputError), as every command of deepgi does.
#include "deepgi/errors.hpp"
#include "deepgi/report.hpp"
#include "deepgi/settings.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <filesystem>

namespace fs = std::filesystem;

namespace deepgi::report {

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
    if (options.repeats < 1 || options.repeats > 16)
        throw InputError(fmt::format("--repeats {} is out of range (1 to 16)", options.repeats));
    if (options.float_max_n < 1 || options.float_max_n > 4096)
        throw InputError(
            fmt::format("--float-max-n {} is out of range (1 to 4096)", options.float_max_n));
    if (options.radiosity_frames < 0 || options.radiosity_frames > 1024)
        throw InputError(fmt::format("--radiosity-frames {} is out of range (0 to 1024; 0: skip)",
                                     options.radiosity_frames));
    validate(options.estimators);
    validate(options.reflections);
    validate(options.ties);
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

int repeat_offset(const ReportOptions& options, int repeat) {
    // 9: the static frames after a cut that the accumulated columns need
    // (kAccumulatedFrames in scene_rows.cpp); the radiosity section's still
    // run renders radiosity_frames. Rounded up to a power of two, so
    // that every repeat starts the Sobol sequence where a run of that many
    // frames is a net again (temporal_sequence.h): repeat r's frames are
    // stratified as repeat 0's are, instead of straddling two runs.
    // At the option limits (16 repeats, 2001 frames: 2048 per repeat) this
    // stays far below limits::max_temporal_offset.
    const int frames = std::max({9, 1 + options.warmup + options.frames, options.radiosity_frames});
    return int(std::bit_ceil(unsigned(frames))) * repeat;
}

int repeat_rotation_seed(int repeat) {
    // Repeat 0 keeps the shipped field, so its rows are the plain renderer's.
    return repeat;
}

}  // namespace deepgi::report
