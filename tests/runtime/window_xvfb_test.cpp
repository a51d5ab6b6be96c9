// The interactive window under Xvfb, driven by --script: a slider changes
// between two screenshots, and each screenshot is checked against a headless
// EGL render of the same settings (the same llvmpipe, so the same bits).
#include "deepgi/image_io.hpp"
#include "support/process.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace {

int run(const std::string& command) {
    const int raw = std::system(command.c_str());
    return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

// Mean over the pixels that see a surface (layer-0 depth > 0).
double covered_mean(const deepgi::FloatImage& image, const deepgi::FloatImage& depth) {
    double sum = 0.0;
    int count = 0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (depth.at(x, y) > 0.0f) {
                sum += image.at(x, y);
                ++count;
            }
    REQUIRE(count > 0);
    return sum / count;
}

}  // namespace

TEST_CASE("window: a scripted run under Xvfb changes the AO radius and the screenshots show it",
          "[runtime][window][xvfb]") {
    spiral::test::skip_unless_executable(DEEPGI_XVFB_RUN);
    const fs::path dir = spiral::test::make_scratch_dir("deepgi-window");
    const fs::path script = dir / "script.txt";
    const fs::path dated = dir / "dated";
    fs::create_directory(dated);
    // Frames count from 0: "before" holds 4 frames at the default radius 0.5,
    // "after" 3 more at 2.0. F12 on the same frame goes to a dated folder.
    std::ofstream(script) << fmt::format(
        "frame 3 screenshot {0}/before\n"
        "frame 3 set ao-radius 2.0\n"
        "frame 6 screenshot {0}/after\n"
        "frame 6 key F12\n"
        "frame 6 quit\n",
        dir.string());
    const std::string size = "--scene cornell --size 160x90";
    const int status = run(fmt::format(
        "'{}' -a '{}' {} --script '{}' --screenshot-dir '{}' > '{}/out.txt' 2>&1", DEEPGI_XVFB_RUN,
        DEEPGI_EXECUTABLE, size, script.string(), dated.string(), dir.string()));
    INFO(spiral::test::read_file(dir / "out.txt"));
    REQUIRE(status == 0);

    // The oracle: headless EGL renders with the settings each screenshot had.
    REQUIRE(run(fmt::format("'{}' --headless {} --frames 4 --output '{}/h4.png' --dump '{}/h4'",
                            DEEPGI_EXECUTABLE, size, dir.string(), dir.string())) == 0);
    REQUIRE(run(fmt::format("'{}' --headless {} --frames 7 --ao-radius 2.0 --output '{}/h7.png' "
                            "--dump '{}/h7'",
                            DEEPGI_EXECUTABLE, size, dir.string(), dir.string())) == 0);

    using deepgi::read_pfm;
    // Before the change the window shows exactly what headless renders.
    CHECK(spiral::test::read_file(dir / "before/final.png") ==
          spiral::test::read_file(dir / "h4.png"));
    const auto before = read_pfm(dir / "before/ao-raw.pfm");
    const auto after = read_pfm(dir / "after/ao-raw.pfm");
    const auto depth = read_pfm(dir / "before/gbuffer-depth-layer0.pfm");
    CHECK(before.pixels == read_pfm(dir / "h4/ao-raw.pfm").pixels);
    // Deep SAO keeps no history, so after the slider moved its visibility is
    // a fresh render's at radius 2.0, bit for bit.
    CHECK(after.pixels == read_pfm(dir / "h7/ao-raw.pfm").pixels);

    // And it changed the way a larger radius should: more occluders found,
    // a darker mean visibility, and of the surface pixels that changed, most
    // got darker (measured: 7737 darker, 1216 lighter at 160x90; a wider
    // radius also reaches further, coarser MIP levels, which lightens some).
    const double mean_before = covered_mean(before, depth);
    const double mean_after = covered_mean(after, depth);
    INFO("mean visibility " << mean_before << " -> " << mean_after);
    CHECK(mean_after < mean_before - 0.02);
    int darker = 0;
    int lighter = 0;
    for (std::size_t i = 0; i < before.pixels.size(); ++i) {
        if (!(depth.pixels[i] > 0.0f)) continue;
        if (after.pixels[i] < before.pixels[i] - 1e-3f) ++darker;
        if (after.pixels[i] > before.pixels[i] + 1e-3f) ++lighter;
    }
    INFO("darker " << darker << ", lighter " << lighter);
    CHECK(darker > 4 * lighter);
    CHECK(spiral::test::read_file(dir / "after/final.png") !=
          spiral::test::read_file(dir / "before/final.png"));

    // F12 wrote one dated folder with the same frame as "after".
    std::vector<fs::path> folders;
    for (const auto& entry : fs::directory_iterator(dated)) folders.push_back(entry.path());
    REQUIRE(folders.size() == 1);
    CHECK(folders[0].filename().string().rfind("deepgi-", 0) == 0);
    CHECK(spiral::test::read_file(folders[0] / "final.png") ==
          spiral::test::read_file(dir / "after/final.png"));
    CHECK(fs::exists(folders[0] / "ao-raw.pfm"));
    fs::remove_all(dir);
}

TEST_CASE("window: a dropped file that is not glTF keeps the scene and reports why",
          "[runtime][window][xvfb]") {
    spiral::test::skip_unless_executable(DEEPGI_XVFB_RUN);
    const fs::path dir = spiral::test::make_scratch_dir("deepgi-window-drop");
    const fs::path script = dir / "script.txt";
    const fs::path junk = dir / "junk.gltf";
    std::ofstream(junk) << "not json at all";
    std::ofstream(script) << fmt::format(
        "frame 1 drop {0}\n"
        "frame 2 screenshot {1}/shot\n"
        "frame 2 quit\n",
        junk.string(), dir.string());
    const std::string size = "--scene cornell --size 96x54";
    const int status =
        run(fmt::format("'{}' -a '{}' {} --script '{}' 2> '{}/err.txt'", DEEPGI_XVFB_RUN,
                        DEEPGI_EXECUTABLE, size, script.string(), dir.string()));
    const std::string errors = spiral::test::read_file(dir / "err.txt");
    INFO(errors);
    REQUIRE(status == 0);
    CHECK(errors == fmt::format("deepgi: could not load '{}': scene file '{}' is not a glTF file "
                                "(neither GLB magic nor a JSON object)\n",
                                junk.string(), junk.string()));
    // The old scene is still shown: the frame equals a headless cornell frame 3.
    REQUIRE(run(fmt::format("'{}' --headless {} --frames 3 --output '{}/h3.png'", DEEPGI_EXECUTABLE,
                            size, dir.string())) == 0);
    CHECK(spiral::test::read_file(dir / "shot/final.png") ==
          spiral::test::read_file(dir / "h3.png"));
    fs::remove_all(dir);
}

TEST_CASE("window: with the delay generator the window renders what headless delay renders",
          "[runtime][window][xvfb]") {
    // The window runs delay one frame behind its fly camera; still, the
    // camera it shows and the next one are the same, so the image is headless
    // delay's. Frame 0 is peel; the change to delay drops history, so frames
    // 1 to 4 are four frames of delay from scratch, as headless --frames 4.
    const fs::path dir = spiral::test::make_scratch_dir("deepgi-window-delay");
    const fs::path script = dir / "script.txt";
    std::ofstream(script) << fmt::format(
        "frame 0 set generator delay\n"
        "frame 4 screenshot {0}/shot\n"
        "frame 4 quit\n",
        dir.string());
    const std::string size = "--scene cornell --size 160x90";
    const int status =
        run(fmt::format("'{}' -a '{}' {} --script '{}' > '{}/out.txt' 2>&1", DEEPGI_XVFB_RUN,
                        DEEPGI_EXECUTABLE, size, script.string(), dir.string()));
    INFO(spiral::test::read_file(dir / "out.txt"));
    REQUIRE(status == 0);
    REQUIRE(run(fmt::format("'{}' --headless {} --generator delay --frames 4 --output '{}/h4.png'",
                            DEEPGI_EXECUTABLE, size, dir.string())) == 0);
    CHECK(spiral::test::read_file(dir / "shot/final.png") ==
          spiral::test::read_file(dir / "h4.png"));
    // The screenshot holds the prediction layer, which only delay and predict have.
    CHECK(fs::exists(dir / "shot/gbuffer-depth-prediction.pfm"));
}
