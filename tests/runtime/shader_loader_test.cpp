// The shader loader: #include from several directories, include-once, and
// compile errors reported against the original file and line.
#include "deepgi/context.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/shader_loader.hpp"
#include "pass.hpp"
#include "passes/passes.hpp"
#include "support/runtime_support.hpp"

#include <catch2/catch.hpp>

#include <algorithm>
#include <fstream>
#include <unistd.h>

using namespace deepgi;
namespace fs = std::filesystem;

namespace {

// A scratch folder with the loader's two search directories in it.
struct LoaderFolders {
    test::TemporaryFolder folder;
    fs::path path = folder.path();
    LoaderFolders() {
        fs::create_directories(path / "shaders");
        fs::create_directories(path / "generated");
    }
    void write(const std::string& name, const std::string& text) const { folder.write(name, text); }
};

}  // namespace

TEST_CASE("shader loader: includes resolve from the shader and generated directories, once each",
          "[runtime][shader_loader]") {
    LoaderFolders dir;
    dir.write(
        "shaders/main.frag",
        "#version 450 core\n#include \"common.glsl\"\n#include \"taps.glsl\"\nvoid main() {}\n");
    dir.write("shaders/common.glsl", "#include \"taps.glsl\"\nconst float COMMON = 1.0;\n");
    dir.write("generated/taps.glsl", "const int NUM_TAPS = 7;\n");
    ShaderLoader loader({dir.path / "shaders", dir.path / "generated"});
    const auto source = loader.expand("main.frag");
    REQUIRE(source.text.rfind("#version 450 core\n", 0) == 0);
    REQUIRE(source.text.find("NUM_TAPS") != std::string::npos);
    // taps.glsl was included twice but appears once.
    REQUIRE(source.text.find("NUM_TAPS") == source.text.rfind("NUM_TAPS"));
    REQUIRE(source.files.size() == 3);
}

// deepgi --shaders puts a folder of edited copies first: a copy of an
// include alone must replace the build's file, though the including shader
// (not copied) has the build's beside it.
TEST_CASE("shader loader: an include in the first directory wins over the one beside its includer",
          "[runtime][shader_loader]") {
    LoaderFolders dir;
    fs::create_directories(dir.path / "copies");
    dir.write("shaders/main.frag", "#version 450 core\n#include \"common.glsl\"\nvoid main() {}\n");
    dir.write("shaders/common.glsl", "const float BUILD = 1.0;\n");
    dir.write("copies/common.glsl", "const float COPY = 1.0;\n");
    ShaderLoader loader({dir.path / "copies", dir.path / "shaders", dir.path / "generated"});
    const auto source = loader.expand("main.frag");
    REQUIRE(source.text.find("COPY") != std::string::npos);
    REQUIRE(source.text.find("BUILD") == std::string::npos);
}

TEST_CASE("shader loader: a missing include names the including file and line",
          "[runtime][shader_loader]") {
    LoaderFolders dir;
    dir.write("shaders/main.frag",
              "#version 450 core\n\n#include \"absent.glsl\"\nvoid main() {}\n");
    ShaderLoader loader({dir.path / "shaders"});
    REQUIRE_THROWS_WITH(loader.expand("main.frag"),
                        Catch::Contains("main.frag:3") && Catch::Contains("absent.glsl"));
}

TEST_CASE("shader loader: a compile error is reported against the included file and its line",
          "[runtime][shader_loader]") {
    HeadlessContext context;
    LoaderFolders dir;
    dir.write("shaders/main.frag",
              "#version 450 core\n#include \"helpers.glsl\"\nout vec4 colour;\nvoid main() {\n  "
              "colour = vec4(1.0);\n"
              "  colour.x = undefined_in_main;\n}\n");
    dir.write("generated/helpers.glsl",
              "// helpers\nfloat ok() { return 1.0; }\nfloat broken() { return nope; }\n");
    ShaderLoader loader({dir.path / "shaders", dir.path / "generated"});
    try {
        loader.build_program({{GL_FRAGMENT_SHADER, "main.frag"}}, "#define UNUSED 1\n");
        FAIL("the shader should not compile");
    } catch (const GraphicsError& error) {
        const std::string message = error.what();
        INFO(message);
        REQUIRE(message.find("helpers.glsl:3") != std::string::npos);
    }
    // The error in the main file, after an include and the inserted define, keeps its own line
    // number.
    dir.write("generated/helpers.glsl", "float ok() { return 1.0; }\n");
    try {
        loader.build_program({{GL_FRAGMENT_SHADER, "main.frag"}}, "#define UNUSED 1\n");
        FAIL("the shader should not compile");
    } catch (const GraphicsError& error) {
        const std::string message = error.what();
        INFO(message);
        REQUIRE(message.find("main.frag:6") != std::string::npos);
    }
}

TEST_CASE("shader loader: every pass of the pass list builds its programs, and they all link",
          "[runtime][shader_loader]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    const Scene scene = make_builtin_scene("cornell");
    // Each pass builds every program it may use when it is made (a setting
    // never compiles a shader later), so making each pass of the list the
    // frame runs compiles and links every shipped program; build_program
    // throws on any compile or link error.
    int passes = 0;
    for (const PassFactory make : default_pass_list()) {
        const int before = loader.programs_built();
        std::unique_ptr<Pass> pass;
        REQUIRE_NOTHROW(pass = make(loader, scene));
        const int built = loader.programs_built() - before;
        INFO("pass " << pass->name() << " built " << built << " programs");
        CHECK(built >= 1);
        // SAO builds one program per row of its program table, which holds
        // every estimator of the AoMethod table at every layer count.
        if (pass->name() == "sao") {
            const std::vector<SaoProgram> table = sao_program_table();
            CHECK(built == int(table.size()));
            CHECK(table.size() == enum_names(AoMethod{}).size() * limits::max_ao_layers);
            for (const auto& method : enum_names(AoMethod{}))
                for (int layers = 1; layers <= limits::max_ao_layers; ++layers)
                    CHECK(std::count_if(table.begin(), table.end(), [&](const SaoProgram& p) {
                              return p.method == method.value && p.layers == layers;
                          }) == 1);
        }
        ++passes;
    }
    CHECK(passes == int(default_pass_list().size()));
    // At least one program per pass, and the passes with variants build more
    // (peel's two layers and the single-pass G-buffer, the masked shadow and
    // back-face programs, the base and reduce levels of the pyramids).
    INFO(loader.programs_built() << " programs from " << passes << " passes");
    CHECK(loader.programs_built() > passes);
}
