// The interactive window under Xvfb, moved by a script as a user would move
// it (a right-button drag, held W and D keys, a window resize), and each
// screenshot checked against a headless EGL render of the camera it wrote
// to camera.txt, at the same size. Without xvfb-run the test exits 77.
#include "deepgi/image_io.hpp"
#include "deepgi/scene.hpp"
#include "support/process.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

namespace fs = std::filesystem;

namespace {

int run(const std::string& command) {
    const int raw = std::system(command.c_str());
    return WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
}

std::string first_line(const fs::path& path) {
    const std::string text = spiral::test::read_file(path);
    return text.substr(0, text.find('\n'));
}

// The largest difference of any channel of any pixel.
float max_difference(const deepgi::FloatImage& a, const deepgi::FloatImage& b) {
    REQUIRE(a.width == b.width);
    REQUIRE(a.height == b.height);
    REQUIRE(a.pixels.size() == b.pixels.size());
    float largest = 0.0f;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        largest = std::max(largest, std::abs(a.pixels[i] - b.pixels[i]));
    return largest;
}

// The share of values differing by more than `threshold`.
double share_above(const deepgi::FloatImage& a, const deepgi::FloatImage& b, float threshold) {
    std::size_t count = 0;
    for (std::size_t i = 0; i < a.pixels.size(); ++i)
        count += std::abs(a.pixels[i] - b.pixels[i]) > threshold;
    return double(count) / double(a.pixels.size());
}

// Headless render of `pose` at `size` after `frames` frames, into dir/name.png
// and dir/name/ (the pass outputs).
void render_headless(const fs::path& dir, const std::string& name, const std::string& size,
                     const std::string& pose, int frames) {
    REQUIRE(run(fmt::format(
                "'{}' --headless --scene cornell --exposure 1 --size {} --camera '{}' --frames {} "
                "--output '{}/{}.png' --dump '{}/{}' > /dev/null",
                DEEPGI_EXECUTABLE, size, pose, frames, dir.string(), name, dir.string(), name)) ==
            0);
}

}  // namespace

TEST_CASE("window: mouse-look, held keys and a resize give the camera a headless render shows",
          "[runtime][window][xvfb]") {
    spiral::test::skip_unless_executable(DEEPGI_XVFB_RUN);
    const fs::path dir = spiral::test::make_scratch_dir("deepgi-window-camera");
    const fs::path script = dir / "script.txt";
    // Frames count from 0; commands of frame N take effect from frame N+1.
    // The drag turns the camera at frame 2; W is held for frames 3-5 and D for
    // 3-4, so frames 5 and 6 share a pose. The resize makes frame 7 the first
    // of a new history at 128x72.
    std::ofstream(script) << fmt::format(
        "frame 1 drag 40 -15\n"
        "frame 2 hold W 3\n"
        "frame 2 hold D 2\n"
        "frame 6 screenshot {0}/moved\n"
        "frame 6 resize 128 72\n"
        "frame 9 screenshot {0}/resized\n"
        "frame 9 key F1\n"
        "frame 10 capture {0}/window.png\n"
        "frame 10 screenshot {0}/shown\n"
        "frame 10 quit\n",
        dir.string());
    const int status =
        // A fixed exposure on both sides: auto exposure smooths over the
        // poses the window passed through, as the temporal filters do.
        run(fmt::format(
            "'{}' -a '{}' --scene cornell --exposure 1 --size 160x90 --script '{}' > '{}/out.txt' "
            "2>&1",
            DEEPGI_XVFB_RUN, DEEPGI_EXECUTABLE, script.string(), dir.string()));
    INFO(spiral::test::read_file(dir / "out.txt"));
    REQUIRE(status == 0);

    // The camera moved as the commands say, computed here from the default
    // camera: yaw and pitch by 0.004 rad a pixel (the drag's -15 looks up),
    // then 2 steps along forward + right and one along forward, each step a
    // quarter of the scene's diagonal per second for 1/30 s.
    const deepgi::Scene scene = deepgi::make_builtin_scene("cornell");
    const deepgi::Camera start = scene.default_camera;
    const deepgi::Camera moved = deepgi::parse_camera_pose(first_line(dir / "moved/camera.txt"));
    CHECK(moved.yaw == Approx(start.yaw + 40 * 0.004f).margin(1e-6));
    CHECK(moved.pitch == Approx(start.pitch + 15 * 0.004f).margin(1e-6));
    const glm::vec3 forward(std::cos(moved.pitch) * std::sin(moved.yaw), std::sin(moved.pitch),
                            -std::cos(moved.pitch) * std::cos(moved.yaw));
    const glm::vec3 right = glm::normalize(glm::vec3(-forward.z, 0.0f, forward.x));
    const float step = 0.25f * glm::length(scene.bounds.max - scene.bounds.min) / 30.0f;
    const glm::vec3 expected =
        start.position + 2.0f * step * glm::normalize(forward + right) + step * forward;
    INFO("moved to " << first_line(dir / "moved/camera.txt"));
    CHECK(glm::length(moved.position - expected) < 1e-5f);

    // Moved: the camera is reproduced exactly, so the G-buffer, which keeps
    // no history, matches headless bit for bit. The final image does not:
    // the window's temporal filters carry history from the poses on the way.
    const std::string moved_pose = first_line(dir / "moved/camera.txt");
    render_headless(dir, "h-moved", "160x90", moved_pose, 7);
    using deepgi::read_pfm;
    for (const char* name : {"gbuffer-depth-layer0", "gbuffer-normal-layer0",
                             "gbuffer-depth-layer1", "gbuffer-albedo-layer0"}) {
        INFO(name);
        CHECK(read_pfm(dir / "moved" / (std::string(name) + ".pfm")).pixels ==
              read_pfm(dir / "h-moved" / (std::string(name) + ".pfm")).pixels);
    }
    const auto window_final = read_pfm(dir / "moved/antialias-colour.pfm");
    const auto headless_final = read_pfm(dir / "h-moved/antialias-colour.pfm");
    const float largest = max_difference(window_final, headless_final);
    const double above_8 = share_above(window_final, headless_final, 8.5f / 255.0f);
    double mean = 0.0;
    for (std::size_t i = 0; i < window_final.pixels.size(); ++i)
        mean += std::abs(window_final.pixels[i] - headless_final.pixels[i]);
    mean /= double(window_final.pixels.size());
    // The stated tolerance for the moved view, in levels of 255 of the
    // displayed image (measured on llvmpipe with the Sobol frame sequence:
    // largest 51, 1.86% of the channels above 8, mean 0.99; with R2 before
    // it 34, 1.85% and 1.0: the one largest channel is the noisiest of the
    // three figures): no channel off by more than 72, at most 4% off by
    // more than 8, a mean difference of at most 2.
    INFO("largest difference " << largest * 255.0f << " of 255; share above 8: " << above_8
                               << "; mean " << mean * 255.0);
    CHECK(largest <= 72.0f / 255.0f);
    CHECK(above_8 <= 0.04);
    CHECK(mean * 255.0 <= 2.0);

    // Resized: the window drops its history, so three frames at 128x72 are
    // a fresh headless render of three frames, bit for bit.
    const std::string resized_pose = first_line(dir / "resized/camera.txt");
    CHECK(resized_pose == moved_pose);
    render_headless(dir, "h-resized", "128x72", resized_pose, 3);
    CHECK(spiral::test::read_file(dir / "resized/final.png") ==
          spiral::test::read_file(dir / "h-resized.png"));
    CHECK(read_pfm(dir / "resized/antialias-colour.pfm").width == 128);

    // With the panel hidden (F1) the window shows exactly the renderer's image.
    CHECK(spiral::test::read_file(dir / "window.png") ==
          spiral::test::read_file(dir / "shown/final.png"));
    fs::remove_all(dir);
}
