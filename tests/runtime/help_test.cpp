// What a new user meets first: `deepgi --help` and the subcommands' --help
// name every subcommand and scene, and every option says its default.
#include "deepgi/scene.hpp"
#include "help_check.hpp"
#include "process.hpp"

#include <catch2/catch.hpp>

#include <string>

namespace {

spiral::test::ProcessResult run_deepgi(const std::string& arguments) {
    return spiral::test::run_command("'" + std::string(DEEPGI_EXECUTABLE) + "' " + arguments);
}

}  // namespace

TEST_CASE("help: deepgi --help names every subcommand and every scene", "[cli][help]") {
    const auto help = run_deepgi("--help");
    REQUIRE(help.status == 0);
    for (const char* subcommand : {"deepgi reference", "deepgi report"}) {
        INFO(subcommand);
        CHECK(help.out.find(subcommand) != std::string::npos);
    }
    auto scenes = deepgi::builtin_scene_names();
    for (const auto& name : deepgi::reference_scene_names()) scenes.push_back(name);
    REQUIRE(scenes.size() >= 7);
    const std::size_t list = help.out.find("Scenes");
    REQUIRE(list != std::string::npos);
    for (const auto& name : scenes) {
        INFO(name);
        CHECK(help.out.find(name, list) != std::string::npos);
        // Every listed scene loads.
        CHECK_NOTHROW(deepgi::load_scene(name));
    }
}

TEST_CASE("help: every deepgi option's help shows its default, without parser notation",
          "[cli][help]") {
    const std::string command = GENERATE(as<std::string>{}, "", "reference ", "report ");
    const auto help = run_deepgi(command + "--help");
    REQUIRE(help.status == 0);
    const auto entries = spiral::test::help_entries(help.out);
    INFO(command << "--help");
    CHECK(entries.size() >= 10);
    for (const auto& bad : spiral::test::undocumented_options(help.out)) {
        INFO(bad);
        CHECK(false);
    }
}
