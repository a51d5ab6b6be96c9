// The frame's structure: resizing rebuilds no program, history is dropped
// exactly when it should be, the settings vocabulary round-trips and rejects
// bad values in one place, and a pass added from outside the runtime shows up
// in the dump without any other edit.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/settings.hpp"
#include "pass.hpp"
#include "passes/passes.hpp"
#include "shader_shared.hpp"
#include "support/runtime_support.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <cstring>
#include <fstream>
#include <iterator>
#include <set>

namespace fs = std::filesystem;
using namespace deepgi;

namespace {

RenderSettings settings_at(int width, int height, Generator generator = Generator::previous) {
    RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.generator = generator;
    settings.shadow_map_size = 512;
    return settings;
}

// Every pass output of the last frame, by name.
std::vector<std::pair<std::string, FloatImage>> all_outputs(const Renderer& renderer) {
    std::vector<std::pair<std::string, FloatImage>> outputs;
    for (const auto& name : renderer.pass_output_names())
        outputs.emplace_back(name, renderer.read_pass_output(name));
    return outputs;
}

bool any_nonzero(const FloatImage& image) {
    return std::any_of(image.pixels.begin(), image.pixels.end(),
                       [](float value) { return value != 0.0f; });
}

std::string last_line(const std::vector<std::string>& log) {
    return log.empty() ? std::string() : log.back();
}

std::string file_bytes(const fs::path& path) {
    std::ifstream stream(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(stream), std::istreambuf_iterator<char>()};
}

}  // namespace

TEST_CASE("passes: resizing compiles no program and renders what a fresh renderer renders",
          "[runtime][passes]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("atrium");
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    Renderer resized(scene, settings_at(200, 120), loader);
    const int built = loader.programs_built();
    REQUIRE(built > 0);
    resized.render(scene.default_camera);
    resized.set_settings(settings_at(320, 180));
    resized.render(scene.default_camera);
    resized.set_settings(settings_at(200, 120));
    resized.render(scene.default_camera);
    resized.render(scene.default_camera);
    CHECK(loader.programs_built() == built);

    // A fresh renderer compiles everything again (so the count above can move).
    Renderer fresh(scene, settings_at(200, 120), loader);
    CHECK(loader.programs_built() == 2 * built);
    fresh.render(scene.default_camera);
    fresh.render(scene.default_camera);
    CHECK(resized.read_output_rgba8() == fresh.read_output_rgba8());
    const auto expected = all_outputs(fresh);
    const auto actual = all_outputs(resized);
    REQUIRE(actual.size() == expected.size());
    for (std::size_t i = 0; i < actual.size(); ++i) {
        INFO(actual[i].first);
        CHECK(actual[i].first == expected[i].first);
        CHECK(actual[i].second.width == expected[i].second.width);
        CHECK(actual[i].second.pixels == expected[i].second.pixels);
    }
}

TEST_CASE("passes: history survives an unchanged frame and is dropped on resize and camera cut",
          "[runtime][passes]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    // Peel is exact and needs no history: the independent reference for layer 1.
    Renderer peel(scene, settings_at(160, 90, Generator::peel), loader);
    peel.render(scene.default_camera);
    const FloatImage truth = peel.read_pass_output("gbuffer-depth-layer1");
    REQUIRE(any_nonzero(truth));

    Renderer previous(scene, settings_at(160, 90), loader);
    CHECK_FALSE(previous.history_valid());
    CHECK(last_line(previous.history_log()).find("new scene") != std::string::npos);

    // Without history the single-pass generator has no layer 1 at all; with the
    // previous frame from the same camera it finds peel's layer 1, bit for bit
    // (both draw through the same vertex stage; docs/deepgi.md, "Generators").
    auto layer1_matches_truth = [&] {
        const FloatImage layer1 = previous.read_pass_output("gbuffer-depth-layer1");
        return layer1.pixels.size() == truth.pixels.size() &&
               std::memcmp(layer1.pixels.data(), truth.pixels.data(),
                           truth.pixels.size() * sizeof(float)) == 0;
    };
    previous.render(scene.default_camera);
    CHECK_FALSE(any_nonzero(previous.read_pass_output("gbuffer-depth-layer1")));
    CHECK(previous.history_valid());
    previous.render(scene.default_camera);
    CHECK(layer1_matches_truth());
    const std::size_t log_size = previous.history_log().size();

    SECTION("an unchanged frame keeps it") {
        previous.render(scene.default_camera);
        CHECK(previous.history_valid());
        CHECK(previous.history_log().size() == log_size);
        CHECK(layer1_matches_truth());
    }
    SECTION("a settings change that keeps the size keeps it") {
        RenderSettings brighter = previous.settings();
        brighter.exposure = 2.0f;
        previous.set_settings(brighter);
        CHECK(previous.history_valid());
        previous.render(scene.default_camera);
        CHECK(previous.history_log().size() == log_size);
        CHECK(layer1_matches_truth());
    }
    SECTION("a camera cut drops it") {
        previous.render(scene.default_camera, CameraMotion::cut);
        CHECK(last_line(previous.history_log()).find("camera cut") != std::string::npos);
        CHECK_FALSE(any_nonzero(previous.read_pass_output("gbuffer-depth-layer1")));
        previous.render(scene.default_camera);
        CHECK(layer1_matches_truth());
    }
    SECTION("a resize drops it") {
        previous.set_settings(settings_at(161, 91));
        CHECK_FALSE(previous.history_valid());
        CHECK(last_line(previous.history_log()).find("resize") != std::string::npos);
        previous.render(scene.default_camera);
        CHECK_FALSE(any_nonzero(previous.read_pass_output("gbuffer-depth-layer1")));
    }
}

namespace {

template <class Enum>
void check_round_trip(int expected_count) {
    const auto table = enum_names(Enum{});
    CHECK(int(table.size()) == expected_count);
    std::set<std::string_view> names;
    std::set<int> values;
    for (const auto& row : table) {
        INFO(row.name);
        names.insert(row.name);
        values.insert(static_cast<int>(row.value));
        CHECK(to_string(row.value) == row.name);
        CHECK(parse_enum<Enum>(row.name) == row.value);
    }
    CHECK(int(names.size()) == expected_count);
    CHECK(int(values.size()) == expected_count);
    CHECK_FALSE(parse_enum<Enum>("no-such-name").has_value());
}

}  // namespace

TEST_CASE("settings: every enum's name table round-trips", "[runtime][settings]") {
    check_round_trip<Generator>(5);
    check_round_trip<TimingMode>(3);
    // One row per DEEPGI_VIEW_* value, the shader's switch covers 0 to 18.
    check_round_trip<DebugView>(20);
    for (int value = DEEPGI_VIEW_FINAL; value <= DEEPGI_VIEW_RADIOSITY_PREPARED; ++value)
        CHECK(to_string(static_cast<DebugView>(value)) != "?");
    CHECK(enum_name_list<Generator>() == "peel, previous, reproject, delay, predict");
}

TEST_CASE("settings: an out-of-range value is rejected by validate() with one message",
          "[runtime][settings]") {
    RenderSettings settings = settings_at(64, 32);
    REQUIRE_NOTHROW(validate(settings));
    settings.generator = static_cast<Generator>(7);
    const std::string expected =
        "--generator value 7 is not one of peel, previous, reproject, delay, predict";
    CHECK_THROWS_WITH(validate(settings), expected);
    // The renderer rejects it through the same check, with the same words.
    HeadlessContext context;
    CHECK_THROWS_WITH(
        Renderer(make_builtin_scene("cornell"), settings, ShaderLoader::from_build_configuration()),
        expected);
    settings = settings_at(64, 32);
    settings.view = static_cast<DebugView>(-1);
    CHECK_THROWS_AS(validate(settings), InputError);
    settings = settings_at(64, 32);
    settings.depth_pyramid.max_mip_level = limits::max_pyramid_mip_level + 1;
    CHECK_THROWS_WITH(validate(settings), Catch::Contains("--pyramid-max-mip"));
    settings.depth_pyramid.max_mip_level = limits::max_pyramid_mip_level;
    CHECK_NOTHROW(validate(settings));
    CHECK_THROWS_WITH(
        parse_generator("--generator", "oracle"),
        "--generator 'oracle' is not one of peel, previous, reproject, delay, predict");
}

// The example pass (example_pass/ao_complement_pass.cpp); a pass of the
// runtime is declared by its line in passes/pass_list.hpp instead.
namespace deepgi {
std::unique_ptr<Pass> make_ao_complement_pass(const ShaderLoader& loader, const Scene& scene);
}

TEST_CASE("passes: a pass added to the list appears in the dump", "[runtime][passes]") {
    HeadlessContext context;
    std::vector<PassFactory> passes = default_pass_list();
    const auto blur = std::find(passes.begin(), passes.end(), &make_blur_pass);
    REQUIRE(blur != passes.end());
    passes.insert(blur + 1, make_ao_complement_pass);
    const Scene scene = make_builtin_scene("cornell");
    // Its shader is found beside it, after the build's shader folders.
    auto dirs = ShaderLoader::from_build_configuration().include_dirs();
    dirs.push_back(DEEPGI_EXAMPLE_PASS_DIR);
    Renderer renderer(scene, settings_at(96, 64), ShaderLoader(dirs), passes);
    renderer.render(scene.default_camera);
    const test::TemporaryFolder folder;
    const fs::path dump = folder.path() / "dump";
    renderer.dump_pass_outputs(dump);
    REQUIRE(fs::exists(dump / "ao_complement-occlusion.pfm"));
    // Oracle: one minus the blurred visibility the frame dumped, computed
    // here; the pass stores it as 16-bit floats (11-bit mantissa).
    const FloatImage visibility = read_pfm(dump / "ao-blurred.pfm");
    const FloatImage occlusion = read_pfm(dump / "ao_complement-occlusion.pfm");
    REQUIRE(occlusion.width == visibility.width);
    REQUIRE(occlusion.height == visibility.height);
    REQUIRE(occlusion.channels == visibility.channels);
    int occluded = 0;
    for (std::size_t i = 0; i < visibility.pixels.size(); ++i) {
        INFO("value " << i);
        REQUIRE(occlusion.pixels[i] == Approx(1.0f - visibility.pixels[i]).margin(1e-3));
        occluded += occlusion.pixels[i] > 0.01f;
    }
    CHECK(occluded > 0);  // the cornell box's corners are occluded
    const auto timings = renderer.last_timings();
    CHECK(std::any_of(timings.begin(), timings.end(),
                      [](const PassTiming& timing) { return timing.pass == "ao_complement"; }));
    const auto names = renderer.pass_output_names();
    CHECK(std::find(names.begin(), names.end(), "ao_complement-occlusion") != names.end());
}

namespace {

// Keeps history that an exposure change would spoil, and says so.
class ExposureHistoryPass final : public Pass {
public:
    std::string_view name() const override { return "exposure_history"; }
    PassDeclaration declaration(const RenderSettings&) const override { return {}; }
    void resize(FrameResources&) override {}
    void run(FrameResources&) override {}
    SettingsChange settings_change(const RenderSettings& before,
                                   const RenderSettings& after) const override {
        if (after.exposure == before.exposure) return {};
        return {.drop_history = "exposure_history: exposure changed"};
    }
};

std::unique_ptr<Pass> make_exposure_history_pass(const ShaderLoader&, const Scene&) {
    return std::make_unique<ExposureHistoryPass>();
}

}  // namespace

TEST_CASE("passes: a pass says which settings changes drop its history", "[runtime][passes]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    RenderSettings brighter = settings_at(64, 32);
    brighter.exposure = 2.0f;
    // Control: the default passes keep history over an exposure change.
    Renderer plain(scene, settings_at(64, 32), loader);
    plain.render(scene.default_camera);
    plain.set_settings(brighter);
    CHECK(plain.history_valid());

    std::vector<PassFactory> passes = default_pass_list();
    passes.push_back(make_exposure_history_pass);
    Renderer renderer(scene, settings_at(64, 32), loader, passes);
    renderer.render(scene.default_camera);
    REQUIRE(renderer.history_valid());
    renderer.set_settings(renderer.settings());
    CHECK(renderer.history_valid());
    renderer.set_settings(brighter);
    CHECK_FALSE(renderer.history_valid());
    CHECK(last_line(renderer.history_log()).find("exposure_history: exposure changed") !=
          std::string::npos);
}

namespace {

// Binds a texture name that does not exist: GL_INVALID_OPERATION.
class BrokenPass final : public Pass {
public:
    std::string_view name() const override { return "broken"; }
    PassDeclaration declaration(const RenderSettings&) const override { return {}; }
    void resize(FrameResources&) override {}
    void run(FrameResources&) override { glBindTextureUnit(0, 0x7fffffffu); }
};

std::unique_ptr<Pass> make_broken_pass(const ShaderLoader&, const Scene&) {
    return std::make_unique<BrokenPass>();
}

}  // namespace

TEST_CASE("passes: with gl_debug a GL error becomes an exception naming the pass",
          "[runtime][passes]") {
    HeadlessContext context;
    std::vector<PassFactory> passes = default_pass_list();
    passes.insert(passes.begin() + 2, make_broken_pass);
    const Scene scene = make_builtin_scene("cornell");
    RenderSettings settings = settings_at(64, 32);
    {
        // Control: without the callback the same frame renders.
        Renderer quiet(scene, settings, ShaderLoader::from_build_configuration(), passes);
        CHECK_NOTHROW(quiet.render(scene.default_camera));
        while (glGetError() != GL_NO_ERROR) {
        }
    }
    settings.gl_debug = true;
    Renderer checked(scene, settings, ShaderLoader::from_build_configuration(), passes);
    CHECK_THROWS_WITH(checked.render(scene.default_camera), Catch::Contains("pass 'broken'"));
    // The default passes raise no GL error at all.
    Renderer clean(scene, settings, ShaderLoader::from_build_configuration());
    CHECK_NOTHROW(clean.render(scene.default_camera));
}

namespace {

// Passes whose declarations disagree with the frame or with what they do.
class NeedyPass final : public Pass {
public:
    std::string_view name() const override { return "needy"; }
    PassDeclaration declaration(const RenderSettings&) const override {
        return {.reads = {{0, "nothing.here"}}, .writes = {}};
    }
    void resize(FrameResources&) override {}
    void run(FrameResources&) override {}
};

class SecretivePass final : public Pass {
public:
    std::string_view name() const override { return "secretive"; }
    PassDeclaration declaration(const RenderSettings&) const override {
        return {.reads = {}, .writes = {"secretive.declared"}};
    }
    void resize(FrameResources&) override {}
    void run(FrameResources& frame) override { frame.publish("secretive.undeclared", 0); }
};

class IdlePass final : public Pass {
public:
    std::string_view name() const override { return "idle"; }
    PassDeclaration declaration(const RenderSettings&) const override {
        return {.reads = {}, .writes = {"idle.promised"}};
    }
    void resize(FrameResources&) override {}
    void run(FrameResources&) override {}
};

template <class P>
std::unique_ptr<Pass> make_test_pass(const ShaderLoader&, const Scene&) {
    return std::make_unique<P>();
}

}  // namespace

TEST_CASE("passes: declarations are checked before the first frame and against what runs",
          "[runtime][passes]") {
    HeadlessContext context;
    const Scene scene = make_builtin_scene("cornell");
    const RenderSettings settings = settings_at(64, 32);
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    SECTION("a read that no earlier pass writes fails at construction, naming both") {
        std::vector<PassFactory> passes = default_pass_list();
        passes.insert(passes.begin() + 1, make_test_pass<NeedyPass>);
        CHECK_THROWS_WITH(Renderer(scene, settings, loader, passes),
                          "pass 'needy' reads the texture 'nothing.here', which no earlier "
                          "enabled pass writes");
    }
    SECTION("a read of what a later pass writes fails too: the list order is the frame's") {
        std::vector<PassFactory> passes = default_pass_list();
        std::swap(passes[0], passes[1]);  // shadow after gbuffer is fine ...
        CHECK_NOTHROW(Renderer(scene, settings, loader, passes));
        passes = default_pass_list();
        std::rotate(passes.begin(), passes.begin() + 3, passes.begin() + 4);  // direct light first
        CHECK_THROWS_WITH(Renderer(scene, settings, loader, passes),
                          Catch::Contains("reads the texture 'gbuffer."));
    }
    SECTION("a settings change that needs a disabled pass's texture is refused") {
        // The march reads the back faces; with the back-face pass removed the
        // solid angle still runs, and switching to the march is refused whole.
        std::vector<PassFactory> passes = default_pass_list();
        passes.erase(std::find(passes.begin(), passes.end(), &make_backface_depth_pass));
        RenderSettings solid = settings;
        solid.ao.method = AoMethod::solid_angle;
        Renderer renderer(scene, solid, loader, passes);
        CHECK_NOTHROW(renderer.render(scene.default_camera));
        RenderSettings march = solid;
        march.ao.method = AoMethod::march;
        CHECK_THROWS_WITH(renderer.set_settings(march),
                          "pass 'depth_pyramid' reads the texture 'backface.depth', which no "
                          "earlier enabled pass writes");
        CHECK(renderer.settings().ao.method == AoMethod::solid_angle);
    }
    SECTION("publishing an undeclared texture fails, naming the pass") {
        std::vector<PassFactory> passes = default_pass_list();
        passes.push_back(make_test_pass<SecretivePass>);
        Renderer renderer(scene, settings, loader, passes);
        CHECK_THROWS_WITH(renderer.render(scene.default_camera),
                          "pass 'secretive' writes the texture 'secretive.undeclared', which it "
                          "does not declare");
    }
    SECTION("a declared write the pass never publishes fails, naming it") {
        std::vector<PassFactory> passes = default_pass_list();
        passes.push_back(make_test_pass<IdlePass>);
        Renderer renderer(scene, settings, loader, passes);
        CHECK_THROWS_WITH(renderer.render(scene.default_camera),
                          "pass 'idle' declares the texture 'idle.promised' but did not write it");
    }
}

namespace {

// The declarations of the default passes as the Markdown rows that
// docs/architecture.md keeps between its pass-declarations markers.
std::string declaration_table(const RenderSettings& settings) {
    const Scene scene = make_builtin_scene("cornell");
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    std::string table =
        "| pass | reads (texture unit) | writes | values read | values written |\n"
        "|---|---|---|---|---|\n";
    for (PassFactory make : default_pass_list()) {
        const std::unique_ptr<Pass> pass = make(loader, scene);
        const PassDeclaration declaration = pass->declaration(settings);
        std::string reads, writes, value_reads, value_writes;
        for (const std::string& name : declaration.value_reads)
            value_reads += fmt::format("{}`{}`", value_reads.empty() ? "" : ", ", name);
        for (const PassValue& value : declaration.value_writes)
            value_writes += fmt::format("{}`{}`", value_writes.empty() ? "" : ", ", value.name);
        for (const PassRead& read : declaration.reads)
            reads +=
                fmt::format("{}`{}` ({})", reads.empty() ? "" : ", ", read.texture, read.binding);
        for (const std::string& name : declaration.writes)
            writes += fmt::format("{}`{}`", writes.empty() ? "" : ", ", name);
        table +=
            fmt::format("| `{}` | {} | {} | {} | {} |\n", pass->name(), reads.empty() ? "-" : reads,
                        writes.empty() ? "-" : writes, value_reads.empty() ? "-" : value_reads,
                        value_writes.empty() ? "-" : value_writes);
    }
    return table;
}

}  // namespace

TEST_CASE("passes: docs/architecture.md lists every pass's declared reads and writes",
          "[runtime][passes]") {
    HeadlessContext context;
    const std::string expected = declaration_table(RenderSettings{});
    const std::string doc = file_bytes(DEEPGI_ARCHITECTURE_DOC);
    const std::string begin = "<!-- pass-declarations:begin -->\n";
    const std::string end = "<!-- pass-declarations:end -->";
    const auto first = doc.find(begin);
    const auto last = doc.find(end);
    REQUIRE(first != std::string::npos);
    REQUIRE(last != std::string::npos);
    const std::string documented = doc.substr(first + begin.size(), last - first - begin.size());
    // The expected block, written beside the test's working directory too
    // (Catch wraps long lines): paste it between the markers.
    std::ofstream("pass-declarations.md") << expected;
    INFO("expected between the markers (also in pass-declarations.md):\n" << expected);
    CHECK(documented == expected);
}
