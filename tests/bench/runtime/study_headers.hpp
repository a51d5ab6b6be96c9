#pragma once
// Tap headers for the deep SAO pass written at run time, so the benchmark and
// the noise study can run the production shader with patterns other than the
// build's ao_taps.glsl. The SAO shader finds them through a ShaderLoader that
// searches the folder before the generated headers.
#include "deepgi/shader_loader.hpp"

#include <spiral/codegen.hpp>

#include <fmt/format.h>

#include <atomic>
#include <cmath>
#include <filesystem>
#include <string>
#include <unistd.h>
#include <vector>

namespace deepgi::study {

class ScratchFolder {
public:
    ScratchFolder() {
        static std::atomic<int> counter{0};
        path_ = std::filesystem::temp_directory_path() /
                fmt::format("deepgi-sao-study-{}-{}", ::getpid(), counter++);
        std::filesystem::create_directories(path_);
    }
    ~ScratchFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    ScratchFolder(const ScratchFolder&) = delete;
    ScratchFolder& operator=(const ScratchFolder&) = delete;
    const std::filesystem::path& path() const { return path_; }

private:
    std::filesystem::path path_;
};

inline ShaderLoader loader_with_override(const std::filesystem::path& folder) {
    auto dirs = ShaderLoader::from_build_configuration().include_dirs();
    dirs.insert(dirs.begin() + 1, folder);
    return ShaderLoader(dirs);
}

// The build's header format (same symbols) for any list of taps; `turns` is
// informational only (the golden-angle spiral has no integer tau).
inline std::string format_ao_header(const std::vector<spiral::codegen::Tap>& taps, int turns,
                                    const std::string& what) {
    std::string text =
        fmt::format("// Study pattern: {}. Written at run time by a benchmark program.\n", what);
    text +=
        fmt::format("#define AO_NUM_TAPS {}\n#define AO_NUM_SPIRAL_TURNS {}\n", taps.size(), turns);
    text += "const vec2 AO_TAP_OFFSETS[AO_NUM_TAPS] = vec2[](\n";
    for (std::size_t i = 0; i < taps.size(); ++i) {
        text += fmt::format("    vec2({:.9g}, {:.9g}){}\n", taps[i].x, taps[i].y,
                            i + 1 < taps.size() ? "," : "");
    }
    text += ");\nconst float AO_TAP_ALPHAS[AO_NUM_TAPS] = float[](\n";
    for (std::size_t i = 0; i < taps.size(); ++i) {
        text += fmt::format("    {:.9g}{}\n", taps[i].alpha, i + 1 < taps.size() ? "," : "");
    }
    return text + ");\n";
}

// Every tap turned by `angle` radians (the same as adding `angle` to phi).
inline std::vector<spiral::codegen::Tap> rotated(const std::vector<spiral::codegen::Tap>& taps,
                                                 double angle) {
    std::vector<spiral::codegen::Tap> result;
    const double c = std::cos(angle);
    const double s = std::sin(angle);
    for (const auto& tap : taps) {
        result.push_back({tap.alpha, float(c * tap.x - s * tap.y), float(s * tap.x + c * tap.y)});
    }
    return result;
}

// Radii as in the spiral, angles stepping by the golden angle 2*pi*(2 - phi).
inline std::vector<spiral::codegen::Tap> golden_angle_taps(int n) {
    const double golden_angle = 3.141592653589793 * (3.0 - std::sqrt(5.0));
    std::vector<spiral::codegen::Tap> taps;
    for (int i = 0; i < n; ++i) {
        const double alpha = (i + 0.5) / n;
        taps.push_back({float(alpha), float(alpha * std::cos(golden_angle * i)),
                        float(alpha * std::sin(golden_angle * i))});
    }
    return taps;
}

}  // namespace deepgi::study
