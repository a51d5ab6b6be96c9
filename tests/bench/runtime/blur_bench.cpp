// blur_bench: milliseconds of the bilateral blur alone, without the
// radiosity gather in the frame (seconds per frame on llvmpipe), so the blur
// can be timed over many frames. The frame runs the G-buffer, the depth
// pyramid and SAO, then a stand-in for the radiosity pass (an RGBA16F texture
// of noise under the name radiosity.irradiance.layer0: the blur's cost does
// not depend on the values), then either
//   - separate: ao_blur and radiosity_blur, one blur per signal, or
//   - shared:   blur, both signals filtered with one set of weights,
// alternating frame by frame so both see the same machine load. CPU clock
// around glFinish (--timing gpu: timer queries); medians.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/renderer.hpp"
#include "pass.hpp"
#include "passes/passes.hpp"
#include "shader_shared.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <map>
#include <random>
#include <regex>

namespace {

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const std::size_t middle = values.size() / 2;
    return values.size() % 2 == 1 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

// Publishes a fixed noise texture where the radiosity pass would publish
// layer 0's filtered E and confidence.
class StandInRadiosityPass final : public deepgi::Pass {
public:
    std::string_view name() const override { return "radiosity_stand_in"; }
    deepgi::PassDeclaration declaration(const deepgi::RenderSettings&) const override {
        return {.reads = {}, .writes = {"radiosity.irradiance.layer0"}};
    }
    void resize(deepgi::FrameResources& frame) override {
        const int w = frame.layout.internal_width;
        const int h = frame.layout.internal_height;
        texture_ = deepgi::gl::create_texture_2d(GL_RGBA16F, w, h);
        std::vector<float> noise(std::size_t(w) * std::size_t(h) * 4);
        std::mt19937 generator(1);
        std::uniform_real_distribution<float> uniform(0.0f, 4.0f);
        for (float& value : noise) value = uniform(generator);
        glTextureSubImage2D(texture_.get(), 0, 0, 0, w, h, GL_RGBA, GL_FLOAT, noise.data());
    }
    void run(deepgi::FrameResources& frame) override {
        frame.publish("radiosity.irradiance.layer0", texture_.get());
    }

private:
    deepgi::gl::Texture texture_;
};

std::unique_ptr<deepgi::Pass> make_stand_in(const deepgi::ShaderLoader&, const deepgi::Scene&) {
    return std::make_unique<StandInRadiosityPass>();
}

std::vector<deepgi::PassFactory> pass_list(bool shared) {
    std::vector<deepgi::PassFactory> passes = {
        deepgi::make_shadow_pass,        deepgi::make_gbuffer_pass, deepgi::make_direct_light_pass,
        deepgi::make_depth_pyramid_pass, deepgi::make_sao_pass,     make_stand_in};
    if (shared) {
        passes.push_back(deepgi::make_blur_pass);
    } else {
        passes.push_back(deepgi::make_ao_blur_pass);
        passes.push_back(deepgi::make_radiosity_blur_pass);
    }
    return passes;
}

}  // namespace

int main(int argc, char** argv) {
    std::string size = "1280x720";
    std::vector<std::string> scenes = {"cornell", "atrium", "warehouse"};
    int frames = 9;
    std::string timing = "cpu";
    CLI::App app{"blur_bench: bilateral blur milliseconds, separate against shared"};
    app.add_option("--size", size, "WIDTHxHEIGHT")->capture_default_str();
    app.add_option("--scenes", scenes, "Built-in scenes or glTF files")->capture_default_str();
    app.add_option("--frames", frames, "Timed frames of each kind (the median is reported)")
        ->capture_default_str();
    app.add_option("--timing", timing, "cpu (clock around glFinish) or gpu (timer queries)")
        ->capture_default_str();
    CLI11_PARSE(app, argc, argv);

    try {
        std::smatch match;
        if (!std::regex_match(size, match, std::regex(R"((\d{1,5})x(\d{1,5}))")))
            throw deepgi::InputError(fmt::format("--size '{}' is not WIDTHxHEIGHT", size));
        if (frames < 1) throw deepgi::InputError("--frames must be at least 1");
        deepgi::RenderSettings settings;
        settings.width = std::stoi(match[1].str());
        settings.height = std::stoi(match[2].str());
        settings.timing = deepgi::parse_timing_mode("--timing", timing);
        deepgi::validate(settings);

        deepgi::HeadlessContext context;
        const auto info = deepgi::query_context_info();
        fmt::print("{} | {} | {}x{} | median of {} frames, after one warm-up frame\n\n",
                   info.renderer, info.version, settings.width, settings.height, frames);
        fmt::print(
            "| scene | before: ao_blur | before: radiosity_blur | before: both | key pass: "
            "ao_blur | key pass: both, separate | shared blur | shared / before |\n"
            "|---|---|---|---|---|---|---|---|\n");
        for (const auto& name : scenes) {
            const deepgi::Scene scene = deepgi::load_scene(name);
            const auto loader = deepgi::ShaderLoader::from_build_configuration();
            auto before_dirs = loader.include_dirs();
            before_dirs.insert(before_dirs.begin(), BLUR_BEFORE_SHADER_DIR);
            deepgi::Renderer before(scene, settings, deepgi::ShaderLoader(before_dirs),
                                    pass_list(false));
            deepgi::Renderer separate(scene, settings, loader, pass_list(false));
            deepgi::Renderer shared(scene, settings, loader, pass_list(true));
            // ms of the blur passes per frame, per configuration
            std::map<std::string, std::vector<double>> samples;
            for (int i = 0; i <= frames; ++i) {
                for (auto [label, renderer] :
                     {std::pair{"before", &before}, {"separate", &separate}, {"shared", &shared}}) {
                    renderer->render(scene.default_camera);
                    if (i == 0) continue;  // warm-up
                    double blur_ms = 0.0;
                    for (const auto& t : renderer->last_timings()) {
                        if (t.pass.find("blur") == std::string::npos) continue;
                        blur_ms += t.milliseconds;
                        samples[fmt::format("{} {}", label, t.pass)].push_back(t.milliseconds);
                    }
                    samples[label].push_back(blur_ms);
                }
            }
            fmt::print("| {} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.1f} | {:.2f} |\n",
                       name, median(samples["before ao_blur"]),
                       median(samples["before radiosity_blur"]), median(samples["before"]),
                       median(samples["separate ao_blur"]), median(samples["separate"]),
                       median(samples["shared"]),
                       median(samples["shared"]) / median(samples["before"]));
            std::fflush(stdout);
        }
        return 0;
    } catch (const deepgi::InputError& error) {
        fmt::print(stderr, "blur_bench: error: {}\n", error.what());
        return 2;
    } catch (const std::exception& error) {
        fmt::print(stderr, "blur_bench: error: {}\n", error.what());
        return 1;
    }
}
