// The deepgi executable: bad input gives one line on stderr and exit status 2
// and writes nothing; the same command twice gives the same bytes; --dump
// writes finite PFM images.
#include "deepgi/image_io.hpp"
#include "ray_cast_oracle.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

struct RunResult {
    int status = -1;
    std::string stderr_text;
};

fs::path scratch() {
    const fs::path dir =
        fs::temp_directory_path() / ("deepgi_cli_test_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    return dir;
}

RunResult run_deepgi(const std::string& arguments) {
    const fs::path errors = scratch() / "stderr.txt";
    const std::string command =
        fmt::format("'{}' {} 2> '{}' > /dev/null", DEEPGI_EXECUTABLE, arguments, errors.string());
    const int raw = std::system(command.c_str());
    RunResult result;
    result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    std::ifstream stream(errors);
    result.stderr_text.assign(std::istreambuf_iterator<char>(stream),
                              std::istreambuf_iterator<char>());
    return result;
}

std::string read_bytes(const fs::path& path) {
    std::ifstream stream(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

void require_one_line_error(const std::string& arguments, const std::string& expected_text) {
    const fs::path output = scratch() / "must_not_exist.png";
    fs::remove(output);
    const RunResult result = run_deepgi(arguments + " --output '" + output.string() + "'");
    INFO(arguments << " -> " << result.stderr_text);
    REQUIRE(result.status == 2);
    REQUIRE(std::count(result.stderr_text.begin(), result.stderr_text.end(), '\n') == 1);
    REQUIRE(result.stderr_text.find(expected_text) != std::string::npos);
    REQUIRE_FALSE(fs::exists(output));
}

}  // namespace

TEST_CASE("cli: bad arguments give a one-line error and exit status 2", "[runtime][cli]") {
    require_one_line_error("--headless --size 0x90", "--size");
    require_one_line_error("--headless --size big", "--size");
    require_one_line_error("--headless --size 160x90 --generator delay", "--generator");
    require_one_line_error("--headless --size 160x90 --min-separation -1", "--min-separation");
    require_one_line_error("--headless --size 160x90 --frames 0", "--frames");
    require_one_line_error("--headless --size 160x90 --no-such-option", "no-such-option");
    require_one_line_error("--headless --size 160x90 --frames two", "--frames");
    require_one_line_error("--headless --size 160x90 --view sideways", "--view");
    require_one_line_error("--headless --size 160x90 --radiosity-method mean",
                           "--radiosity-method");
}

TEST_CASE("cli: bad scenes give a one-line error and exit status 2", "[runtime][cli]") {
    const fs::path dir = scratch();
    std::ofstream(dir / "broken.gltf") << "{ \"asset\": { \"version\": \"2.0\" }, \"meshes\": [ ";
    std::ofstream(dir / "empty.gltf") << R"({ "asset": { "version": "2.0" } })";
    std::ofstream(dir / "lines.gltf")
        << R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":24,"uri":"data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAA"}],)"
        << R"("bufferViews":[{"buffer":0,"byteLength":24}],"accessors":[{"bufferView":0,"componentType":5126,"count":2,"type":"VEC3","min":[0,0,0],"max":[1,0,0]}],)"
        << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"mode":1}]}],"nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}]})";
    std::ofstream(dir / "scene.obj") << "v 0 0 0\n";
    require_one_line_error("--headless --size 160x90 --scene no_such_scene", "unknown scene");
    require_one_line_error(
        fmt::format("--headless --size 160x90 --scene '{}'", (dir / "missing.gltf").string()),
        "does not exist");
    require_one_line_error(
        fmt::format("--headless --size 160x90 --scene '{}'", (dir / "broken.gltf").string()),
        "broken.gltf");
    require_one_line_error(
        fmt::format("--headless --size 160x90 --scene '{}'", (dir / "empty.gltf").string()),
        "no triangles");
    require_one_line_error(
        fmt::format("--headless --size 160x90 --scene '{}'", (dir / "lines.gltf").string()),
        "contains no triangles (only 1 point or line primitives)");
    require_one_line_error(
        fmt::format("--headless --size 160x90 --scene '{}'", (dir / "scene.obj").string()),
        "is not a glTF file");
}

TEST_CASE("cli: headless-only options and a non-PNG output are refused", "[runtime][cli]") {
    // Window mode: refused before any window opens, so no display is needed.
    require_one_line_error("--size 160x90 --dump d --frames 3",
                           "--output, --dump, --frames only apply with --headless");
    require_one_line_error("--size 160x90 --camera-path",
                           "--output, --camera-path only apply with --headless");
    require_one_line_error("--headless --size 160x90 --script s.txt",
                           "--script only applies to the window (leave out --headless)");
    {
        // --camera reaches the window too, and is checked before it opens
        // (so this needs no display).
        const RunResult window = run_deepgi("--size 160x90 --camera 0");
        INFO(window.stderr_text);
        REQUIRE(window.status == 2);
        REQUIRE(window.stderr_text ==
                "deepgi: error: --camera '0': scene 'cornell' has no such perspective camera "
                "(it has none)\n");
    }
    require_one_line_error("--headless --size 160x90 --camera 0",
                           "scene 'cornell' has no such perspective camera (it has none)");
    const fs::path jpeg = scratch() / "image.jpg";
    const RunResult result =
        run_deepgi("--headless --size 160x90 --output '" + jpeg.string() + "'");
    INFO(result.stderr_text);
    REQUIRE(result.status == 2);
    REQUIRE(result.stderr_text ==
            fmt::format("deepgi: error: --output '{}': only PNG is written; the name must end in "
                        ".png\n",
                        jpeg.string()));
    REQUIRE_FALSE(fs::exists(jpeg));
}

TEST_CASE("cli: --print-timings ends with the total of the passes it lists", "[runtime][cli]") {
    const fs::path dir = scratch();
    const fs::path timings = dir / "timings.txt";
    const std::string command =
        fmt::format("'{}' --headless --size 96x64 --print-timings --output '{}' > '{}'",
                    DEEPGI_EXECUTABLE, (dir / "timed.png").string(), timings.string());
    REQUIRE(std::system(command.c_str()) == 0);
    std::ifstream stream(timings);
    std::string line;
    std::vector<std::pair<std::string, double>> rows;
    while (std::getline(stream, line)) {
        char name[64] = {};
        double ms = 0.0;
        if (std::sscanf(line.c_str(), "%63s %lf ms", name, &ms) == 2) rows.emplace_back(name, ms);
    }
    REQUIRE(rows.size() >= 3);
    REQUIRE(rows.back().first == "total");
    double sum = 0.0;
    for (std::size_t i = 0; i + 1 < rows.size(); ++i) {
        REQUIRE(rows[i].first != "total");
        sum += rows[i].second;
    }
    // Each printed value is rounded to 0.001 ms.
    REQUIRE(std::abs(rows.back().second - sum) <= 0.0005 * double(rows.size()));
}

TEST_CASE("cli: an output directory that does not exist is an input error", "[runtime][cli]") {
    const RunResult result = run_deepgi("--headless --size 16x9 --output /nonexistent-dir/out.png");
    REQUIRE(result.status == 2);
    REQUIRE(result.stderr_text.find("does not exist") != std::string::npos);
}

TEST_CASE("cli: the same command twice writes identical images", "[runtime][cli]") {
    const fs::path dir = scratch();
    for (const char* generator : {"peel", "reproject"}) {
        const std::string common = fmt::format(
            "--headless --scene atrium --size 160x90 --frames 3 --camera-path --generator {}",
            generator);
        REQUIRE(run_deepgi(common + " --output '" + (dir / "first.png").string() + "'").status ==
                0);
        REQUIRE(run_deepgi(common + " --output '" + (dir / "second.png").string() + "'").status ==
                0);
        const std::string first = read_bytes(dir / "first.png");
        REQUIRE(first.size() > 100);
        REQUIRE(first == read_bytes(dir / "second.png"));
    }
}

TEST_CASE("cli: the dump option writes every pass output as finite PFM images", "[runtime][cli]") {
    const fs::path dir = scratch() / "dump";
    fs::remove_all(dir);
    const RunResult result = run_deepgi(
        fmt::format("--headless --scene cornell --size 161x91 --frames 2 --generator previous "
                    "--output '{}' --dump '{}'",
                    (scratch() / "dump.png").string(), dir.string()));
    REQUIRE(result.status == 0);
    int files = 0;
    for (const char* name :
         {"gbuffer-depth-layer0", "gbuffer-depth-layer1", "gbuffer-normal-layer0",
          "gbuffer-normal-layer1", "gbuffer-albedo-layer0", "gbuffer-albedo-layer1",
          "gbuffer-emissive-layer0", "gbuffer-motion-layer0", "shadow-depth",
          "direct_light-radiance-layer0", "direct_light-radiance-layer1", "compose-radiance",
          "tonemap-colour"}) {
        INFO(name);
        const deepgi::FloatImage image = deepgi::read_pfm(dir / (std::string(name) + ".pfm"));
        REQUIRE(deepgi::test::all_finite(image));
        ++files;
    }
    const deepgi::FloatImage colour = deepgi::read_pfm(dir / "tonemap-colour.pfm");
    REQUIRE(colour.width == 161);
    REQUIRE(colour.height == 91);
    REQUIRE(files == 13);
}

TEST_CASE("cli: a glTF file renders with its base colour factor and emissive",
          "[runtime][cli][gltf]") {
    const fs::path dir = scratch();
    // A 2 m square facing +z, no normals (flat normals are derived), one material.
    std::ofstream(dir / "square.gltf")
        << R"({"asset":{"version":"2.0"},"buffers":[{"byteLength":60,"uri":"data:application/octet-stream;base64,)"
        << R"(AACAvwAAgL8AAAAAAACAPwAAgL8AAAAAAACAPwAAgD8AAAAAAACAvwAAgD8AAAAAAAABAAIAAAACAAMA"}],)"
        << R"("bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":12}],)"
        << R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[-1,-1,0],"max":[1,1,0]},)"
        << R"({"bufferView":1,"componentType":5123,"count":6,"type":"SCALAR"}],)"
        << R"("materials":[{"pbrMetallicRoughness":{"baseColorFactor":[0.2,0.4,0.6,1]},"emissiveFactor":[0.5,0.25,0]}],)"
        << R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"material":0}]}],)"
        << R"("nodes":[{"mesh":0}],"scenes":[{"nodes":[0]}],"scene":0})";
    const fs::path dump = dir / "gltf_dump";
    fs::remove_all(dump);
    const RunResult result = run_deepgi(
        fmt::format("--headless --scene '{}' --size 64x48 --output '{}' --dump '{}'",
                    (dir / "square.gltf").string(), (dir / "square.png").string(), dump.string()));
    INFO(result.stderr_text);
    REQUIRE(result.status == 0);
    const deepgi::FloatImage albedo = deepgi::read_pfm(dump / "gbuffer-albedo-layer0.pfm");
    const deepgi::FloatImage emissive = deepgi::read_pfm(dump / "gbuffer-emissive-layer0.pfm");
    const deepgi::FloatImage normal = deepgi::read_pfm(dump / "gbuffer-normal-layer0.pfm");
    const int x = albedo.width / 2;
    const int y = albedo.height / 2;
    // 8-bit sRGB storage: within half a code step.
    REQUIRE(albedo.at(x, y, 0) == Approx(0.2).epsilon(0.02));
    REQUIRE(albedo.at(x, y, 1) == Approx(0.4).epsilon(0.02));
    REQUIRE(albedo.at(x, y, 2) == Approx(0.6).epsilon(0.02));
    REQUIRE(emissive.at(x, y, 0) == Approx(0.5).epsilon(0.02));
    REQUIRE(emissive.at(x, y, 1) == Approx(0.25).epsilon(0.02));
    // The fitted three-quarter view looks 35 degrees round and 30 down: the
    // square's +z normal meets the view axis at cos 30 * cos 35.
    REQUIRE(normal.at(x, y, 2) ==
            Approx(std::cos(glm::radians(30.0)) * std::cos(glm::radians(35.0))).margin(0.02));
}
