// Runs a command line through the shell and captures its exit status, standard
// output and standard error, for tests of the command-line tools.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <system_error>
#include <vector>

namespace spiral::test {

struct ProcessResult {
    int status = -1;
    std::string out;
    std::string err;
};

inline std::string read_file(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Every scratch directory this test program made, removed when it exits, so a
// test run leaves nothing under the temporary directory, whether a check
// failed or not (a crash or kill still leaves its directories behind).
class ScratchRegistry {
public:
    void add(const std::filesystem::path& dir) { dirs_.push_back(dir); }
    ~ScratchRegistry() {
        for (const auto& dir : dirs_) {
            std::error_code ignored;
            std::filesystem::remove_all(dir, ignored);
        }
    }

private:
    std::vector<std::filesystem::path> dirs_;
};

inline ScratchRegistry& scratch_registry() {
    static ScratchRegistry registry;
    return registry;
}

// A fresh, empty directory under the system's temporary directory, removed
// with everything in it when the test program exits.
inline std::filesystem::path make_scratch_dir(const std::string& tag) {
    std::random_device seed;
    const auto dir = std::filesystem::temp_directory_path() /
                     (tag + "-" + std::to_string(seed()) + "-" + std::to_string(seed()));
    std::filesystem::create_directories(dir);
    scratch_registry().add(dir);
    return dir;
}

inline ProcessResult run_command(const std::string& command_line) {
    const auto dir = make_scratch_dir("spiral-run");
    const auto out = dir / "stdout", err = dir / "stderr";
    const std::string full =
        command_line + " >'" + out.string() + "' 2>'" + err.string() + "' </dev/null";
    const int raw = std::system(full.c_str());
    ProcessResult result;
    result.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
    result.out = read_file(out);
    result.err = read_file(err);
    std::filesystem::remove_all(dir);
    return result;
}

// Ends the test program with ctest's skip code 77 when `program` cannot be
// run (e.g. xvfb-run removed after configuring): a skip, never a silent pass.
inline void skip_unless_executable(const char* program) {
    if (::access(program, X_OK) == 0) return;
    std::printf("%s not found: skipped (exit 77)\n", program);
    std::exit(77);
}

inline int count_lines(const std::string& text) {
    int lines = 0;
    for (char c : text) lines += c == '\n';
    return lines;
}

}  // namespace spiral::test
