// fileio's write_file_atomically (what spiralgen and deepgi write through):
// the result, the failures, and what failures leave behind.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "process.hpp"
#include "spiral/fileio.hpp"

namespace fs = std::filesystem;
using spiral::fileio::write_file_atomically;
using spiral::test::read_file;

namespace {

int entries_in(const fs::path& dir) {
    int count = 0;
    for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++count;
    return count;
}

// The error's message, which must be one line naming the path.
std::string failure_of(const fs::path& path, std::string_view contents) {
    try {
        write_file_atomically(path, contents);
    } catch (const std::runtime_error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("atomic file: write_file_atomically creates and replaces files", "[fileio][atomic]") {
    const auto dir = spiral::test::make_scratch_dir("fileio-atomic");
    const auto path = dir / "out.glsl";
    write_file_atomically(path, "first\n");
    CHECK(read_file(path) == "first\n");
    write_file_atomically(path, "second, longer\n");
    CHECK(read_file(path) == "second, longer\n");
    write_file_atomically(path, "");
    CHECK(fs::exists(path));
    CHECK(read_file(path).empty());
    const std::string binary("a\0b\xff", 4);
    write_file_atomically(path, binary);
    CHECK(read_file(path) == binary);
    CHECK(entries_in(dir) == 1);
    fs::remove_all(dir);
}

TEST_CASE(
    "atomic file: write_file_atomically fails with one line naming the path and leaves nothing",
    "[fileio][atomic]") {
    const auto dir = spiral::test::make_scratch_dir("fileio-atomic");

    SECTION("missing directory") {
        const auto path = dir / "missing" / "out.glsl";
        const std::string message = failure_of(path, "x");
        CHECK(message.find(path.string()) != std::string::npos);
        CHECK(message.find("No such file or directory") != std::string::npos);
        CHECK(message.find('\n') == std::string::npos);
        CHECK_FALSE(fs::exists(path));
    }
    SECTION("parent is a regular file") {
        write_file_atomically(dir / "file", "keep");
        const auto path = dir / "file" / "out.glsl";
        const std::string message = failure_of(path, "x");
        CHECK(message.find(path.string()) != std::string::npos);
        CHECK(read_file(dir / "file") == "keep");
    }
    SECTION("target is a directory") {
        fs::create_directory(dir / "sub");
        write_file_atomically(dir / "sub" / "inner", "keep");
        const std::string message = failure_of(dir / "sub", "x");
        CHECK(message.find((dir / "sub").string()) != std::string::npos);
        CHECK(message.find("directory") != std::string::npos);
        CHECK(read_file(dir / "sub" / "inner") == "keep");
    }
    SECTION("empty path") {
        CHECK_FALSE(failure_of("", "x").empty());
    }
    // Whatever failed, no temporary is left behind: only what the section made.
    int expected = 0;
    for (const char* made : {"file", "sub"}) expected += fs::exists(dir / made);
    CHECK(entries_in(dir) == expected);
    fs::remove_all(dir);
}

TEST_CASE("atomic file: concurrent writers never leave a mixed file or a temporary",
          "[fileio][atomic]") {
    const auto dir = spiral::test::make_scratch_dir("fileio-atomic");
    const auto path = dir / "shared.glsl";
    const std::string a(100000, 'a'), b(70000, 'b');
    std::vector<std::thread> writers;
    for (const std::string* text : {&a, &b, &a, &b})
        writers.emplace_back([&path, text] {
            for (int i = 0; i < 20; ++i) write_file_atomically(path, *text);
        });
    for (auto& writer : writers) writer.join();
    const std::string final_text = read_file(path);
    CHECK((final_text == a || final_text == b));
    CHECK(entries_in(dir) == 1);
    fs::remove_all(dir);
}
