// Image regression of the path users run: deepgi's command line at 96x54
// against small reference images in tests/runtime/golden/, compared pixel by
// pixel with a stated tolerance. A mismatch prints the largest differences and
// writes a difference image beside the run's outputs, so the failure shows its
// reason. The references record the GL renderer that made them; on another
// renderer the test says so and reports itself skipped instead of failing on
// every pixel.
//
// Cases: the default settings (default AO estimator and its back-face pass)
// and a moving camera (--camera-path) under the previous and reproject
// generators, whose second layers must differ from each other.
//
// Usage: deepgi_golden_images check|record <work folder>
//   check   renders every case and compares it with the references
//   record  renders every case and replaces the references (and renderer.txt);
//           tests/runtime/record_golden.sh runs it from the source tree
#include "../support/process.hpp"
#include "deepgi/context.hpp"
#include "deepgi/image_io.hpp"

#include <fmt/format.h>
#include <stb_image.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

// Tolerances, stated once: float outputs |a - b| <= 1e-3 + 1e-3 |b| per
// channel; the 8-bit final PNG 2 codes per channel. Non-finite values must
// match exactly. Same renderer, same build: the outputs are expected to be
// equal; the margin only absorbs compiler-level float differences.
constexpr double float_absolute = 1e-3, float_relative = 1e-3;
constexpr int png_codes = 2;
constexpr int skip_status = 77;  // ctest SKIP_RETURN_CODE (tests/runtime/golden.cmake)

struct Case {
    std::string name;
    std::string arguments;
    std::vector<std::string> outputs;  // "final.png" or a --dump PFM name
};

const std::vector<Case>& cases() {
    static const std::vector<Case> all = {
        // Defaults throughout: the default estimator and generator, and the
        // back-face pass the default estimator reads.
        {"cornell-default",
         "--scene cornell --frames 3",
         {"final.png", "ao-blurred.pfm", "backface-depth-layer0.pfm", "gbuffer-depth-layer1.pfm"}},
        // A moving camera, so layer 1 comes from history that must be moved:
        // previous and reproject differ here (checked below).
        {"warehouse-path-previous",
         "--scene warehouse --camera-path --generator previous --frames 4",
         {"final.png", "gbuffer-depth-layer1.pfm", "ao-temporal.pfm", "gbuffer-motion-layer0.pfm"}},
        {"warehouse-path-reproject",
         "--scene warehouse --camera-path --generator reproject --frames 4",
         {"final.png", "gbuffer-depth-layer1.pfm", "ao-temporal.pfm"}},
    };
    return all;
}

fs::path golden_dir() {
    return fs::path(DEEPGI_GOLDEN_DIR);
}

// The renderer as the references record it: GL_RENDERER and GL_VERSION.
std::string renderer_string() {
    deepgi::HeadlessContext context;
    const deepgi::ContextInfo info = deepgi::query_context_info();
    return info.renderer + "\n" + info.version + "\n";
}

bool render(const Case& c, const fs::path& dir) {
    fs::create_directories(dir);
    const std::string command =
        fmt::format("'{}' --headless --size 96x54 {} --output '{}' --dump '{}'", DEEPGI_EXECUTABLE,
                    c.arguments, (dir / "final.png").string(), (dir / "dump").string());
    const auto result = spiral::test::run_command(command);
    if (result.status != 0) {
        std::printf("%s: deepgi exited %d: %s\n", c.name.c_str(), result.status,
                    result.err.c_str());
        return false;
    }
    return true;
}

fs::path produced(const fs::path& dir, const std::string& output) {
    return output == "final.png" ? dir / output : dir / "dump" / output;
}

// An image as floats: PFMs as stored, PNGs as their 8-bit codes (RGB).
deepgi::FloatImage load(const fs::path& path) {
    if (path.extension() == ".pfm") return deepgi::read_pfm(path);
    int width = 0, height = 0, channels = 0;
    unsigned char* data = stbi_load(path.string().c_str(), &width, &height, &channels, 3);
    if (!data) throw std::runtime_error("cannot read " + path.string());
    deepgi::FloatImage image{width, height, 3, {}};
    image.pixels.assign(data, data + std::size_t(width) * height * 3);
    stbi_image_free(data);
    return image;
}

struct Difference {
    int x = 0, y = 0, channel = 0;
    float expected = 0.0f, actual = 0.0f;
    double excess = 0.0;  // how far beyond the tolerance
};

bool within(float expected, float actual, bool png, double& excess) {
    if (!std::isfinite(expected) || !std::isfinite(actual)) {
        const bool same = (std::isnan(expected) && std::isnan(actual)) || expected == actual;
        excess = same ? 0.0 : INFINITY;
        return same;
    }
    const double tolerance =
        png ? double(png_codes) : float_absolute + float_relative * std::abs(double(expected));
    excess = std::abs(double(actual) - double(expected)) - tolerance;
    return excess <= 0.0;
}

// Compares one output; on a mismatch prints the largest differences and
// writes <output>-diff.pfm (|actual - expected|, largest channel) and a
// <output>-diff.png scaled to the largest difference. Returns the number of
// values beyond the tolerance.
long long compare(const std::string& label, const fs::path& expected_path,
                  const fs::path& actual_path, const fs::path& diff_dir) {
    if (!fs::exists(expected_path)) {
        std::printf("%s: no reference %s (record the references)\n", label.c_str(),
                    expected_path.string().c_str());
        return 1;
    }
    if (!fs::exists(actual_path)) {
        std::printf("%s: deepgi wrote no %s\n", label.c_str(), actual_path.string().c_str());
        return 1;
    }
    const deepgi::FloatImage expected = load(expected_path);
    const deepgi::FloatImage actual = load(actual_path);
    if (expected.width != actual.width || expected.height != actual.height ||
        expected.channels != actual.channels) {
        std::printf("%s: %dx%dx%d, the reference is %dx%dx%d\n", label.c_str(), actual.width,
                    actual.height, actual.channels, expected.width, expected.height,
                    expected.channels);
        return 1;
    }
    const bool png = expected_path.extension() == ".png";
    std::vector<Difference> beyond;
    deepgi::FloatImage diff{expected.width, expected.height, 1, {}};
    diff.pixels.assign(std::size_t(expected.width) * expected.height, 0.0f);
    for (int y = 0; y < expected.height; ++y) {
        for (int x = 0; x < expected.width; ++x) {
            for (int c = 0; c < expected.channels; ++c) {
                const float e = expected.at(x, y, c), a = actual.at(x, y, c);
                double excess = 0.0;
                float& d = diff.pixels[std::size_t(y) * expected.width + x];
                const float magnitude = std::isfinite(a - e) ? std::abs(a - e) : INFINITY;
                d = std::max(d, magnitude);
                if (!within(e, a, png, excess)) beyond.push_back({x, y, c, e, a, excess});
            }
        }
    }
    if (beyond.empty()) return 0;
    std::sort(beyond.begin(), beyond.end(),
              [](const Difference& l, const Difference& r) { return l.excess > r.excess; });
    std::printf("%s: %zu of %zu values beyond the tolerance (%s); largest:\n", label.c_str(),
                beyond.size(), expected.pixels.size(),
                png ? fmt::format("{} codes", png_codes).c_str()
                    : fmt::format("{} + {} |expected|", float_absolute, float_relative).c_str());
    // PNG rows are top to bottom, PFM rows bottom to top: name pixels as stored.
    for (std::size_t i = 0; i < std::min<std::size_t>(beyond.size(), 8); ++i) {
        const Difference& d = beyond[i];
        std::printf("  (%d, %d) channel %d: expected %.6g, got %.6g\n", d.x, d.y, d.channel,
                    double(d.expected), double(d.actual));
    }
    fs::create_directories(diff_dir);
    const std::string stem = fs::path(label).filename().stem().string();
    deepgi::write_pfm(diff_dir / (stem + "-diff.pfm"), diff);
    float largest = 0.0f;
    for (float v : diff.pixels)
        if (std::isfinite(v)) largest = std::max(largest, v);
    std::vector<std::uint8_t> rgba(diff.pixels.size() * 4, 255);
    for (int y = 0; y < diff.height; ++y) {
        for (int x = 0; x < diff.width; ++x) {
            const float v = diff.pixels[std::size_t(y) * diff.width + x];
            const auto code = std::uint8_t(
                std::isfinite(v) && largest > 0.0f ? std::lround(255.0f * v / largest) : 255);
            // write_png takes rows bottom to top; a PNG's own rows are top to bottom.
            const int row = png ? diff.height - 1 - y : y;
            std::uint8_t* p = &rgba[(std::size_t(row) * diff.width + x) * 4];
            p[0] = p[1] = p[2] = code;
        }
    }
    deepgi::write_png(diff_dir / (stem + "-diff.png"), diff.width, diff.height, rgba);
    std::printf("  difference images: %s-diff.{pfm,png} in %s (white = %.6g)\n", stem.c_str(),
                diff_dir.string().c_str(), double(largest));
    return (long long)beyond.size();
}

// Layer 1 of previous and reproject under the moving camera: if they were
// equal, the moving-camera cases would not tell the generators apart.
int generators_differ(const fs::path& work) {
    const auto a =
        deepgi::read_pfm(work / "warehouse-path-previous" / "dump" / "gbuffer-depth-layer1.pfm");
    const auto b =
        deepgi::read_pfm(work / "warehouse-path-reproject" / "dump" / "gbuffer-depth-layer1.pfm");
    long long differing = 0;
    for (std::size_t i = 0; i < std::min(a.pixels.size(), b.pixels.size()); ++i)
        differing += a.pixels[i] != b.pixels[i];
    std::printf("moving camera: layer-1 depth of previous and reproject differs in %lld pixels\n",
                differing);
    if (differing < 50) {
        std::printf("the moving-camera cases no longer tell previous from reproject\n");
        return 1;
    }
    return 0;
}

int record(const fs::path& work) {
    for (const Case& c : cases()) {
        const fs::path dir = work / c.name;
        if (!render(c, dir)) return 1;
        const fs::path target = golden_dir() / c.name;
        fs::remove_all(target);
        fs::create_directories(target);
        for (const std::string& output : c.outputs)
            fs::copy_file(produced(dir, output), target / output);
    }
    if (generators_differ(work) != 0) return 1;
    const std::string renderer = renderer_string();
    std::FILE* file = std::fopen((golden_dir() / "renderer.txt").c_str(), "w");
    if (!file) return 1;
    std::fputs(renderer.c_str(), file);
    std::fclose(file);
    std::printf("recorded %zu cases in %s on\n%s", cases().size(), golden_dir().c_str(),
                renderer.c_str());
    return 0;
}

int check(const fs::path& work) {
    const std::string recorded = spiral::test::read_file(golden_dir() / "renderer.txt");
    const std::string current = renderer_string();
    long long failures = 0;
    for (const Case& c : cases()) {
        const fs::path dir = work / c.name;
        if (!render(c, dir)) return 1;
        for (const std::string& output : c.outputs)
            failures += compare(c.name + "/" + output, golden_dir() / c.name / output,
                                produced(dir, output), dir / "diff");
    }
    const int differ = generators_differ(work);
    if (recorded != current) {
        std::printf(
            "the references were recorded on\n%sthis renderer is\n%sso the pixels above are not "
            "compared as a failure; re-record with tests/runtime/record_golden.sh\n",
            recorded.c_str(), current.c_str());
        return differ != 0 ? 1 : skip_status;
    }
    if (failures > 0) {
        std::printf(
            "%lld values beyond the tolerance; if the change is meant to alter pixels, "
            "look at the difference images and re-record with "
            "tests/runtime/record_golden.sh\n",
            failures);
        return 1;
    }
    std::printf("every case matches its references (renderer: %s)\n",
                current.substr(0, current.find('\n')).c_str());
    return differ;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 3 || (std::string(argv[1]) != "check" && std::string(argv[1]) != "record")) {
        std::fprintf(stderr, "usage: deepgi_golden_images check|record <work folder>\n");
        return 2;
    }
    try {
        const fs::path work(argv[2]);
        fs::remove_all(work);
        fs::create_directories(work);
        return std::string(argv[1]) == "record" ? record(work) : check(work);
    } catch (const std::exception& error) {
        std::printf("deepgi_golden_images: %s\n", error.what());
        return 1;
    }
}
