// Both programs' command lines against a second hostile corpus: paths that
// cannot be examined, standard output that cannot be written, a full disk
// under `deepgi reference`, lenient numbers, names with newlines, and the
// documented ways of writing to standard output. Each case runs the real
// executable through the shell and checks its exit status and its stderr.
#include "../support/process.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using spiral::test::count_lines;
using spiral::test::make_scratch_dir;
using spiral::test::read_file;
using spiral::test::run_command;

namespace {

const std::string deepgi = DEEPGI_EXECUTABLE;
const std::string spiralgen = SPIRALGEN_EXECUTABLE;

bool contains(const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
}

// Bad input: exit status 2 and exactly one line on stderr, naming `part`.
void require_bad_input(const std::string& command, const std::string& part) {
    const auto result = run_command(command);
    INFO(command << "\n" << result.err);
    REQUIRE(result.status == 2);
    REQUIRE(count_lines(result.err) == 1);
    REQUIRE(contains(result.err, part));
    REQUIRE(!contains(result.err, "filesystem error"));
}

std::string render(const std::string& arguments) {
    const std::string scene = contains(arguments, "--scene") ? "" : "--scene cornell ";
    return deepgi + " --headless --size 16x9 --frames 1 " + scene + arguments;
}

std::string reference(const std::string& arguments) {
    return deepgi + " reference --scene cornell --size 16x9 --rays 4 --irradiance-rays 4 " +
           arguments;
}

// `command` in a subshell: its own redirections and pipes are not replaced
// by run_command's, and its whole stderr is captured.
std::string subshell(const std::string& command) {
    return fmt::format("({})", command);
}

}  // namespace

TEST_CASE("cli: paths that cannot be examined are bad input, named in one line",
          "[runtime][cli][hostile]") {
    const fs::path dir = make_scratch_dir("cli-paths");
    fs::create_symlink(dir / "loop-a", dir / "loop-b");
    fs::create_symlink(dir / "loop-b", dir / "loop-a");
    const std::string loop = (dir / "loop-a").string();
    const std::string long_name = (dir / std::string(300, 'x')).string();
    require_bad_input(render("--output " + loop + ".png --scene " + loop), "loop-a");
    require_bad_input(render("--output " + loop + "/image.png"), "symbolic links");
    require_bad_input(render("--output " + long_name + ".png"), "File name too long");
    require_bad_input(render("--output x.png --scene " + long_name + ".gltf"), "too long");
    require_bad_input(reference("--output " + loop + "/set"), "symbolic links");
    require_bad_input(reference("--output " + long_name), "too long");
    require_bad_input(reference("--output /proc/deepgi-set"), "/proc/deepgi-set");
    require_bad_input(reference("--output /sys/deepgi-set"), "/sys/deepgi-set");
    require_bad_input(deepgi + " report --output " + loop + "/report", "symbolic links");
    // Thread counts the system cannot grant abort no more.
    require_bad_input(reference("--threads 100000 --output " + (dir / "set").string()),
                      "--threads");
    require_bad_input(reference("--threads 2147483647 --output " + (dir / "set").string()),
                      "--threads");
    fs::remove_all(dir);
}

TEST_CASE("cli: standard output that cannot be written fails the run", "[runtime][cli][hostile]") {
    const fs::path dir = make_scratch_dir("cli-stdout");
    // A full disk (/dev/full), a closed descriptor, a broken pipe with SIGPIPE
    // ignored: all were exit 0.
    // (In a subshell, so that the test's own redirection does not replace them.)
    require_bad_input(subshell(spiralgen + " discrepancy --n 8 --tau 3 >/dev/full"),
                      "standard output");
    require_bad_input(subshell(spiralgen + " discrepancy --n 8 --tau 3 >&-"), "standard output");
    const fs::path status = dir / "status";
    const auto piped = run_command(
        fmt::format("(trap '' PIPE; {{ {} table --min-n 4 --max-n 120; echo $? >'{}'; }} | true)",
                    spiralgen, status.string()));
    const std::string piped_status = read_file(status);
    INFO(piped.err);
    REQUIRE(piped_status == "2\n");
    REQUIRE(contains(piped.err, "Broken pipe"));
    require_bad_input(
        subshell(render("--output " + (dir / "a.png").string() + " --print-timings >/dev/full")),
        "standard output");
    require_bad_input(subshell(reference("--output " + (dir / "set").string() + " >/dev/full")),
                      "standard output");
    // Nothing printed to a closed descriptor is no failure.
    REQUIRE(run_command(subshell(spiralgen + " --help >&-")).status == 0);
    fs::remove_all(dir);
}

TEST_CASE("cli: deepgi reference writes its images as one set", "[runtime][cli][hostile]") {
    const fs::path dir = make_scratch_dir("cli-reference-set");
    const fs::path set = dir / "set";
    // A file-size limit of 15 KiB (dash counts 512-byte blocks; 30 KiB in
    // bash): the one-channel images (12.7 KB) fit, a three-channel one
    // fails with EFBIG, as a full disk fails with ENOSPC.
    const auto full = run_command(fmt::format(
        "trap '' XFSZ; ulimit -f 30; {}", deepgi +
                                              " reference --scene cornell --size 64x36 --rays 4 "
                                              "--irradiance-rays 4 --output " +
                                              set.string()));
    INFO(full.err);
    REQUIRE(full.status == 2);
    REQUIRE(count_lines(full.err) == 1);
    REQUIRE(contains(full.err, "File too large"));
    REQUIRE(!contains(full.err, "depth-layer0"));
    REQUIRE(!fs::exists(set));
    REQUIRE(fs::is_empty(dir));  // no temporary left either
    // The whole set (14 images, each a PFM and its PNG preview: 11, and the
    // irradiance split by the layer holding its source), then a second run
    // replacing it whole (7 images).
    REQUIRE(run_command(reference("--output " + set.string())).status == 0);
    REQUIRE(std::distance(fs::directory_iterator(set), fs::directory_iterator()) == 28);
    REQUIRE(run_command(reference("--no-irradiance --output " + set.string())).status == 0);
    REQUIRE(std::distance(fs::directory_iterator(set), fs::directory_iterator()) == 14);
    // A folder holding anything else is refused before tracing.
    std::ofstream(set / "notes.txt") << "mine";
    require_bad_input(reference("--output " + set.string()), "holds other files");
    fs::remove_all(dir);
}

TEST_CASE("cli: numbers are whole decimal text, names stay on one line",
          "[runtime][cli][hostile]") {
    const fs::path dir = make_scratch_dir("cli-numbers");
    const std::string out = " --output " + (dir / "a.png").string();
    require_bad_input(render("--ao-radius ''" + out), "--ao-radius");
    require_bad_input(render("--ao-radius 0x1p-2" + out), "--ao-radius");
    require_bad_input(render("--frames 0x10" + out), "--frames");
    // An option with a range check too.
    require_bad_input(render("--max-gpu-memory 0x10" + out), "'0x10' is not a whole");
    require_bad_input(reference("--seed -1 --output " + dir.string() + "/set"), "'-1'");
    require_bad_input(reference("--seed 18446744073709551616 --output " + dir.string() + "/set"),
                      "18446744073709551616");
    require_bad_input(spiralgen + " header --taps 4,,8", "4,,8");
    require_bad_input(spiralgen + " table --min-n 4 --max-n 8 --denominator 9223372036854775808",
                      "9223372036854775808");
    require_bad_input(spiralgen + " discrepancy --n '' --tau 3", "--n");
    // A scene name with a newline: one line, the newline shown escaped.
    require_bad_input(render("--scene \"$(printf 'two\\nlines')\"" + out), "two\\nlines");
    // Plain numbers still work, and a leading zero is decimal, not octal.
    const auto eight = run_command(spiralgen + " discrepancy --n 8 --tau 3");
    REQUIRE(eight.status == 0);
    const auto ten = run_command(spiralgen + " discrepancy --n 10 --tau 3");
    const auto zero_ten = run_command(spiralgen + " discrepancy --n 010 --tau 3");
    REQUIRE(zero_ten.status == 0);
    REQUIRE(zero_ten.out == ten.out);
    REQUIRE(zero_ten.out != eight.out);
    fs::remove_all(dir);
}

TEST_CASE("cli: the documented ways of writing to standard output work",
          "[runtime][cli][hostile]") {
    const fs::path dir = make_scratch_dir("cli-stdout-forms");
    const std::string table = spiralgen + " table --min-n 4 --max-n 6";
    const auto plain = run_command(table);
    const auto through_dev = run_command(subshell(table + " --out /dev/stdout | cat"));
    const auto dash = run_command(subshell(table + " --out - | cat"));
    INFO(through_dev.err);
    REQUIRE(plain.status == 0);
    REQUIRE(through_dev.status == 0);
    REQUIRE(through_dev.out == plain.out);
    REQUIRE(dash.out == plain.out);
    // deepgi --output - and a .png link to /dev/stdout give the same PNG.
    const fs::path link = dir / "out.png";
    fs::create_symlink("/dev/stdout", link);
    const auto to_dash = run_command(subshell(render("--output - | cat")));
    const auto to_link = run_command(subshell(render("--output " + link.string() + " | cat")));
    INFO(to_dash.err << to_link.err);
    REQUIRE(to_dash.status == 0);
    REQUIRE(to_link.status == 0);
    REQUIRE(to_dash.out.substr(0, 4) == "\x89PNG");
    REQUIRE(to_link.out == to_dash.out);
    fs::remove_all(dir);
}
