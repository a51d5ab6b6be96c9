// Runs the fuzz target once on every file named (or in every directory named)
// on the command line, without libFuzzer: the corpus as a regression test in
// every build, whatever the compiler. A crash fails the test, and so does a
// seed file named valid-* that the target refuses: a loader that refused
// everything would otherwise pass. Each target's file defines
// fuzz_target_accepts.
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

// Runs the target on one input; true when it accepted the input.
bool fuzz_target_accepts(const std::uint8_t* data, std::size_t size);

namespace {

struct Counts {
    int files = 0;
    int valid = 0;
    int failures = 0;
};

void replay(const std::filesystem::path& path, Counts& counts) {
    ++counts.files;
    std::ifstream stream(path, std::ios::binary);
    const std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(stream)),
                                          std::istreambuf_iterator<char>());
    if (!stream && !stream.eof()) {
        std::fprintf(stderr, "cannot read %s\n", path.c_str());
        ++counts.failures;
        return;
    }
    const bool loaded = fuzz_target_accepts(bytes.data(), bytes.size());
    if (path.filename().string().rfind("valid-", 0) == 0) {
        ++counts.valid;
        if (!loaded) {
            std::fprintf(stderr, "the target refused the valid file %s\n", path.c_str());
            ++counts.failures;
        }
    }
}

}  // namespace

int main(int argc, char** argv) {
    Counts counts;
    for (int i = 1; i < argc; ++i) {
        const std::filesystem::path path(argv[i]);
        if (std::filesystem::is_directory(path)) {
            for (const auto& entry : std::filesystem::directory_iterator(path))
                replay(entry.path(), counts);
        } else {
            replay(path, counts);
        }
    }
    std::printf("replayed %d inputs, %d of them valid files that must load\n", counts.files,
                counts.valid);
    return counts.failures == 0 && counts.files > 0 ? 0 : 1;
}
