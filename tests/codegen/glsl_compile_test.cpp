// Every generated GLSL header compiles with a real GLSL compiler
// (glslangValidator) inside a minimal #version 450 fragment shader that uses
// every symbol the header defines.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "process.hpp"

namespace fs = std::filesystem;

namespace {

const std::string kSpiralgen = SPIRALGEN_PATH;
const std::string kValidator = GLSLANG_VALIDATOR_PATH;

std::string generate(const std::string& arguments) {
    const auto result = spiral::test::run_command("'" + kSpiralgen + "' " + arguments);
    INFO("spiralgen " << arguments << "\n" << result.err);
    REQUIRE(result.status == 0);
    return result.out;
}

// A main() that reads every symbol, so an unused-but-broken one still fails.
std::string gather_use(const std::string& prefix) {
    return "    for (int i = 0; i < " + prefix +
           "_NUM_TAPS; ++i) {\n"
           "        acc.xy += rotation * " +
           prefix +
           "_TAP_OFFSETS[i];\n"
           "        acc.z += " +
           prefix +
           "_TAP_ALPHAS[i];\n"
           "    }\n"
           "    acc.w += float(" +
           prefix + "_NUM_SPIRAL_TURNS);\n";
}
const std::string kBlurUse =
    "    for (int k = -BLUR_RADIUS; k <= BLUR_RADIUS; ++k) acc.x += BLUR_WEIGHTS[k + "
    "BLUR_RADIUS];\n"
    "    acc.y += BLUR_SIGMA;\n";
const std::string kTableUse =
    "    acc.z += float(SPIRAL_TURNS[clamp(int(gl_FragCoord.x), SPIRAL_TURNS_MIN_TAPS,\n"
    "                                      SPIRAL_TURNS_MAX_TAPS)]);\n";

struct Compiled {
    int status;
    std::string log;
};

Compiled compile(const std::string& headers, const std::string& uses) {
    const auto dir = spiral::test::make_scratch_dir("codegen-glsl");
    const auto shader = dir / "test.frag";
    std::ofstream(shader) << "#version 450\n"
                          << headers
                          << "layout(location = 0) out vec4 color;\n"
                             "void main() {\n"
                             "    mat2 rotation = mat2(1.0, 0.0, 0.0, 1.0);\n"
                             "    vec4 acc = vec4(0.0);\n"
                          << uses << "    color = acc;\n}\n";
    const auto result = spiral::test::run_command("'" + kValidator + "' '" + shader.string() + "'");
    fs::remove_all(dir);
    return {result.status, result.out + result.err};
}

}  // namespace

TEST_CASE("glsl: gather headers compile for 1, 2, 11, 19, 64 and 255 taps", "[codegen][glsl]") {
    const int taps = GENERATE(1, 2, 11, 19, 64, 255);
    const auto header = generate("header --pass ao --taps " + std::to_string(taps));
    const auto compiled = compile(header, gather_use("AO"));
    INFO(compiled.log);
    CHECK(compiled.status == 0);
}

TEST_CASE("glsl: a multi-word pass name and an overridden tau compile", "[codegen][glsl]") {
    const auto header = generate("header --pass 'deep radiosity' --taps 19 --tau 19");
    const auto compiled = compile(header, gather_use("DEEP_RADIOSITY"));
    INFO(compiled.log);
    CHECK(compiled.status == 0);
}

TEST_CASE("glsl: offsets printed with an exponent compile", "[codegen][glsl]") {
    // 1000 taps, tau 501: tap 0 sits 2/1000 of a quarter turn past 90 degrees,
    // so its x is about -alpha * pi/1000 = -1.57e-6, printed as "-1.57...e-06".
    const auto header = generate("header --pass ao --taps 1000 --tau 501");
    REQUIRE(header.find("e-06") != std::string::npos);
    const auto compiled = compile(header, gather_use("AO"));
    INFO(compiled.log);
    CHECK(compiled.status == 0);
}

TEST_CASE("glsl: blur headers compile", "[codegen][glsl]") {
    const std::string arguments = GENERATE(as<std::string>{}, "blur --radius 0", "blur --radius 4",
                                           "blur --radius 16 --sigma 3.5");
    const auto compiled = compile(generate(arguments), kBlurUse);
    INFO(arguments << "\n" << compiled.log);
    CHECK(compiled.status == 0);
}

TEST_CASE("glsl: table headers compile", "[codegen][glsl]") {
    const std::string arguments = GENERATE(
        as<std::string>{}, "table --min-n 1 --max-n 1 --format glsl",
        "table --min-n 5 --max-n 40 --format glsl", "table --min-n 1 --max-n 128 --format glsl");
    const auto compiled = compile(generate(arguments), kTableUse);
    INFO(arguments << "\n" << compiled.log);
    CHECK(compiled.status == 0);
}

TEST_CASE("glsl: the compiler does reject a broken header (the check has teeth)",
          "[codegen][glsl]") {
    // One tap more declared than listed: the array constructor no longer
    // matches the declared size.
    std::string header = generate("header --pass ao --taps 11");
    const auto at = header.find("#define AO_NUM_TAPS 11");
    REQUIRE(at != std::string::npos);
    header.replace(at, 22, "#define AO_NUM_TAPS 12");
    CHECK(compile(header, gather_use("AO")).status != 0);
    // A symbol the header does not define.
    CHECK(compile(generate("blur --radius 2"), kBlurUse + "    acc.x += BLUR_MISSING;\n").status !=
          0);
}

#ifdef SPIRAL_GENERATED_DIR
TEST_CASE("glsl: the headers generated by the build compile together in one shader",
          "[codegen][glsl]") {
    // Also proves the passes' symbols and include guards do not clash.
    std::string headers;
    for (const char* name : {"ao_taps.glsl", "radiosity_taps.glsl", "blur_kernel.glsl",
                             "tau_table.glsl", "ao_taps.glsl"}) {
        const std::string text = spiral::test::read_file(fs::path(SPIRAL_GENERATED_DIR) / name);
        INFO(name);
        REQUIRE_FALSE(text.empty());
        headers += text;
    }
    const auto compiled =
        compile(headers, gather_use("AO") + gather_use("RADIOSITY") + kBlurUse + kTableUse);
    INFO(compiled.log);
    CHECK(compiled.status == 0);
}
#endif
