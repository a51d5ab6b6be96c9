// spiralgen under hostile arguments and output paths: every header it writes
// compiles, limits are named, and special output paths are not replaced.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <string>

#include "process.hpp"

namespace fs = std::filesystem;
using spiral::test::make_scratch_dir;
using spiral::test::read_file;
using spiral::test::run_command;

namespace {

const std::string kSpiralgen = SPIRALGEN_PATH;

spiral::test::ProcessResult spiralgen(const std::string& arguments) {
    return run_command("'" + kSpiralgen + "' " + arguments);
}

}  // namespace

TEST_CASE("spiralgen blur: a sigma outside the normal float range is refused",
          "[codegen][hardening]") {
    // 1e308 became `inf.0`, 1e-300 became `0.0`; 1e-40 is a float denormal.
    for (const char* sigma : {"1e308", "1e-300", "1e-40", "3.5e38", "-1", "0", "nan", "inf"}) {
        INFO(sigma);
        const auto result = spiralgen(std::string("blur --radius 3 --sigma ") + sigma);
        REQUIRE(result.status == 2);
        REQUIRE(result.out.empty());
        REQUIRE(result.err.find("--sigma") != std::string::npos);
    }
#ifdef GLSLANG_VALIDATOR_PATH
    // The extremes that are accepted compile, with a real GLSL compiler.
    for (const char* sigma : {"1.1754944e-38", "3.4028234e38", "1e-30", "1e30"}) {
        INFO(sigma);
        const auto header = spiralgen(std::string("blur --radius 3 --sigma ") + sigma);
        REQUIRE(header.status == 0);
        const fs::path dir = make_scratch_dir("codegen-sigma");
        std::ofstream(dir / "test.frag")
            << "#version 450\n"
            << header.out
            << "layout(location = 0) out vec4 color;\nvoid main() {\n    float s = BLUR_SIGMA;\n"
               "    for (int k = -BLUR_RADIUS; k <= BLUR_RADIUS; ++k) s += BLUR_WEIGHTS[k + "
               "BLUR_RADIUS];\n    color = vec4(s);\n}\n";
        const auto compiled = run_command("'" + std::string(GLSLANG_VALIDATOR_PATH) + "' '" +
                                          (dir / "test.frag").string() + "'");
        fs::remove_all(dir);
        INFO(compiled.out);
        REQUIRE(compiled.status == 0);
    }
#endif
}

TEST_CASE("spiralgen: --out '' is an error and '-' is standard output", "[codegen][hardening]") {
    for (const char* command :
         {"header --pass ao --taps 8", "blur --radius 2", "table --max-n 8"}) {
        INFO(command);
        const auto empty = spiralgen(std::string(command) + " --out ''");
        REQUIRE(empty.status == 2);
        REQUIRE(empty.out.empty());
        REQUIRE(empty.err.find("--out") != std::string::npos);
        const auto dash = spiralgen(std::string(command) + " --out -");
        const auto plain = spiralgen(command);
        REQUIRE(dash.status == 0);
        REQUIRE(!plain.out.empty());
        REQUIRE(dash.out == plain.out);
    }
}

TEST_CASE("spiralgen header: tap counts above the header limit are refused by name",
          "[codegen][hardening]") {
    for (const char* taps : {"4097", "16384", "65535"}) {
        INFO(taps);
        const auto result = spiralgen(std::string("header --pass ao --taps ") + taps + " --tau 1");
        REQUIRE(result.status == 2);
        REQUIRE(result.err.find("limit of 4096") != std::string::npos);
    }
}

TEST_CASE("spiralgen: symlinks and FIFOs given to --out are written through, not replaced",
          "[codegen][hardening]") {
    const fs::path dir = make_scratch_dir("codegen-special");
    std::ofstream(dir / "real.glsl") << "old";
    fs::create_symlink("real.glsl", dir / "link.glsl");
    const auto result = spiralgen("blur --radius 2 --out '" + (dir / "link.glsl").string() + "'");
    REQUIRE(result.status == 0);
    REQUIRE(fs::is_symlink(dir / "link.glsl"));
    REQUIRE(read_file(dir / "real.glsl") == spiralgen("blur --radius 2").out);
    // A FIFO with a reader (cat) gets the header; it stays a FIFO.
    REQUIRE(run_command("mkfifo '" + (dir / "pipe").string() + "'").status == 0);
    const auto piped = run_command(
        "cat '" + (dir / "pipe").string() + "' > '" + (dir / "piped").string() + "' & '" +
        kSpiralgen + "' blur --radius 2 --out '" + (dir / "pipe").string() + "'; wait");
    REQUIRE(piped.status == 0);
    REQUIRE(fs::is_fifo(dir / "pipe"));
    REQUIRE(read_file(dir / "piped") == read_file(dir / "real.glsl"));
    fs::remove_all(dir);
}
