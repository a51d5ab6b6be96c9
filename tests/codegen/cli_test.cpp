// spiralgen header / blur through the real executable: determinism, atomic
// output, and the error rules (one line on stderr, exit status 2, no file).
#include <catch2/catch.hpp>

#include <filesystem>
#include <string>

#include "process.hpp"
#include "skip.hpp"

namespace fs = std::filesystem;
using spiral::test::count_lines;
using spiral::test::read_file;

namespace {

const std::string kSpiralgen = SPIRALGEN_PATH;

spiral::test::ProcessResult spiralgen(const std::string& arguments) {
    return spiral::test::run_command("'" + kSpiralgen + "' " + arguments);
}

std::string quoted(const fs::path& path) {
    // Appended piecewise: "'" + path.string() trips a false -Wrestrict in GCC 12.
    std::string text = "'";
    text.append(path.string()).append("'");
    return text;
}

int entries_in(const fs::path& dir) {
    int count = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++count;
    return count;
}

}  // namespace

TEST_CASE("spiralgen: header and blur are deterministic and --out writes what stdout shows",
          "[codegen][cli]") {
    const std::string arguments = GENERATE(as<std::string>{}, "header --pass ao --taps 19",
                                           "header --pass radiosity --taps 64 --tau 5",
                                           "blur --radius 4", "blur --radius 6 --sigma 2.5");
    INFO("spiralgen " << arguments);
    const auto dir = spiral::test::make_scratch_dir("codegen-cli");
    const auto first = spiralgen(arguments);
    const auto second = spiralgen(arguments);
    REQUIRE(first.status == 0);
    CHECK(first.err.empty());
    CHECK_FALSE(first.out.empty());
    CHECK(first.out == second.out);
    // Two different output paths: the bytes must not depend on where they go.
    REQUIRE(spiralgen(arguments + " --out " + quoted(dir / "a.glsl")).status == 0);
    REQUIRE(spiralgen(arguments + " --out " + quoted(dir / "b.glsl")).status == 0);
    CHECK(read_file(dir / "a.glsl") == first.out);
    CHECK(read_file(dir / "b.glsl") == first.out);
    CHECK(entries_in(dir) == 2);
    fs::remove_all(dir);
}

TEST_CASE("bad input: one line on stderr naming the problem, exit status 2, no output",
          "[codegen][cli][errors]") {
    struct Case {
        std::string arguments;
        std::string named;  // what the message must mention
    };
    const Case bad = GENERATE(values<Case>({
        {"header --pass ao --taps 0", "--taps"},
        {"header --pass ao --taps -3", "--taps"},
        {"header --pass ao --taps abc", "--taps"},
        {"header --pass ao --taps 1.5", "--taps"},
        {"header --pass ao --taps 70000", "--taps"},
        {"header --pass ao --taps 99999999999", "--taps"},
        {"header --pass ao --taps 11 --tau 0", "--tau"},
        {"header --pass ao --taps 11 --tau x", "--tau"},
        {"header --pass '' --taps 11", "--pass"},
        {"header --pass 3d --taps 11", "--pass"},
        {"header --pass '!!' --taps 3", "--pass"},
        {"header --pass gl_ao --taps 3", "--pass"},
        {"header --taps 11", "--pass"},
        {"header --pass ao", "--taps"},
        {"blur --radius -1", "radius"},
        {"blur --radius abc", "--radius"},
        {"blur --radius 2000", "radius"},
        {"blur --radius 4 --sigma 0", "sigma"},
        {"blur --radius 4 --sigma -2", "sigma"},
        {"blur --radius 4 --sigma nan", "sigma"},
        {"blur --radius 4 --sigma inf", "sigma"},
        {"blur --radius 4 --sigma wide", "--sigma"},
        {"blur", "--radius"},
        {"table --max-n 3 --max-n 4", "--max-n was given 2 times; give it once"},
        {"table --max-n 99999999999999999",
         "--max-n '99999999999999999' is out of range for this option"},
        {"table --bogus", "unknown option '--bogus'"},
        {"ties --n 4 extra", "unexpected argument 'extra'"},
        {"header --pass ao --taps 11 --out no-such-dir/sub/ao.glsl", "no-such-dir/sub/ao.glsl"},
        {"blur --radius 4 --out no-such-dir/blur.glsl", "no-such-dir/blur.glsl"},
    }));
    INFO("spiralgen " << bad.arguments);
    const auto result = spiralgen(bad.arguments);
    CHECK(result.status == 2);
    CHECK(count_lines(result.err) == 1);
    CHECK(result.err.rfind("spiralgen: error: ", 0) == 0);
    CHECK(result.err.find(bad.named) != std::string::npos);
    CHECK(result.out.empty());
}

TEST_CASE("spiralgen: a failing run leaves no file and does not clobber an existing one",
          "[codegen][cli][atomic]") {
    const auto dir = spiral::test::make_scratch_dir("codegen-cli");
    const auto out = dir / "ao.glsl";

    SECTION("no file is created") {
        CHECK(spiralgen("header --pass ao --taps 0 --out " + quoted(out)).status == 2);
        CHECK(spiralgen("blur --radius -1 --out " + quoted(out)).status == 2);
        CHECK(spiralgen("header --pass 3d --taps 4 --out " + quoted(out)).status == 2);
        CHECK(entries_in(dir) == 0);
    }
    SECTION("an existing file survives a failing run byte for byte") {
        REQUIRE(spiralgen("header --pass ao --taps 11 --out " + quoted(out)).status == 0);
        const std::string before = read_file(out);
        REQUIRE_FALSE(before.empty());
        CHECK(spiralgen("header --pass ao --taps abc --out " + quoted(out)).status == 2);
        CHECK(spiralgen("header --pass ao --taps 11 --tau 0 --out " + quoted(out)).status == 2);
        CHECK(spiralgen("blur --radius 4 --sigma -1 --out " + quoted(out)).status == 2);
        CHECK(read_file(out) == before);
        CHECK(entries_in(dir) == 1);
    }
    SECTION("--out naming a directory fails and leaves the directory alone") {
        fs::create_directory(dir / "sub");
        const auto result = spiralgen("blur --radius 4 --out " + quoted(dir / "sub"));
        CHECK(result.status == 2);
        CHECK(count_lines(result.err) == 1);
        CHECK(fs::is_directory(dir / "sub"));
        CHECK(entries_in(dir / "sub") == 0);
        CHECK(entries_in(dir) == 1);
    }
    fs::remove_all(dir);
}

TEST_CASE("spiralgen: --help works on header and blur", "[codegen][cli]") {
    const std::string command = GENERATE(as<std::string>{}, "header", "blur");
    const auto result = spiralgen(command + " --help");
    CHECK(result.status == 0);
    CHECK(result.out.find("--out") != std::string::npos);
}

TEST_CASE("spiralgen: a failed write to standard output is an error, not a silent exit 0",
          "[codegen][cli][errors]") {
    if (!fs::exists("/dev/full")) {
        spiral::test::skip_test("no /dev/full on this system");
    }
    const std::string arguments =
        GENERATE(as<std::string>{}, "header --pass ao --taps 3", "blur --radius 2");
    INFO("spiralgen " << arguments << " >/dev/full");
    // The inner redirection wins over the one run_command adds around the group.
    const auto result =
        spiral::test::run_command("{ '" + kSpiralgen + "' " + arguments + " >/dev/full; }");
    CHECK(result.status == 2);
    CHECK(count_lines(result.err) == 1);
    CHECK(result.err.find("standard output") != std::string::npos);
}
