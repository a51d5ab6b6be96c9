// libFuzzer target: the command-line parsers. The input is split at NUL
// bytes into arguments and parsed by a CLI11 app with every kind of option
// the two programs declare (integers signed and unsigned, 64-bit, floats,
// lists, text), under the same plain-number check (apps/strict_numbers.hpp);
// --scene-limit values go through deepgi::set_scene_limit. Whatever parses
// must hold exactly the decimal text given: no wrapped negatives, no hex, no
// empty-as-zero.
#include "../../apps/strict_numbers.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/scene.hpp"

#include <charconv>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace {

template <typename T>
void require_exact(CLI::Option* option, T value) {
    if (option->count() == 0) return;
    const std::string text = option->results().back();
    T parsed{};
    const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), parsed);
    if (error != std::errc() || end != text.data() + text.size() || parsed != value)
        __builtin_trap();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    std::vector<std::string> arguments{"fuzz"};
    std::string current;
    for (std::size_t i = 0; i < size && arguments.size() < 64; ++i) {
        if (data[i] == 0) {
            arguments.push_back(current);
            current.clear();
        } else {
            current += char(data[i]);
        }
    }
    arguments.push_back(current);
    std::vector<const char*> argv;
    for (const auto& argument : arguments) argv.push_back(argument.c_str());

    CLI::App app{"fuzz"};
    int frames = 1;
    std::uint64_t seed = 0;
    std::int64_t denominator = 1;
    double radius = 0.5;
    std::vector<int> taps;
    std::vector<std::string> limits_text;
    std::string scene;
    auto* frames_option = app.add_option("--frames", frames);
    auto* seed_option = app.add_option("--seed", seed);
    auto* denominator_option = app.add_option("--denominator", denominator);
    app.add_option("--ao-radius", radius);
    app.add_option("--taps", taps)->delimiter(',');
    app.add_option("--scene-limit", limits_text);
    app.add_option("--scene", scene);
    spiral_cli::require_plain_numbers(app);
    try {
        app.parse(int(argv.size()), argv.data());
    } catch (const CLI::Error&) {
        return 0;
    }
    require_exact(frames_option, frames);
    require_exact(seed_option, seed);
    require_exact(denominator_option, denominator);
    try {
        deepgi::SceneLimits limits;
        for (const auto& assignment : limits_text) deepgi::set_scene_limit(limits, assignment);
    } catch (const deepgi::InputError&) {
    }
    return 0;
}

// For the corpus replay (replay_main.cpp): the parser's verdicts are checked
// inside the target, which traps on a wrong one, so every input counts as
// accepted and the corpus holds no valid-* files.
bool fuzz_target_accepts(const std::uint8_t* data, std::size_t size) {
    LLVMFuzzerTestOneInput(data, size);
    return true;
}
