#pragma once
// Helpers every runtime (deepgi) test file may use: scratch folders, finite
// checks, and a shader loader that prefers a test's own headers.
#include "deepgi/image_io.hpp"
#include "deepgi/shader_loader.hpp"

#include <atomic>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace deepgi::test {

// A fresh folder under the system temp dir, removed with everything in it.
class TemporaryFolder {
public:
    TemporaryFolder() {
        static std::atomic<int> counter{0};
        path_ = std::filesystem::temp_directory_path() /
                ("deepgi-test-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TemporaryFolder() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    TemporaryFolder(const TemporaryFolder&) = delete;
    TemporaryFolder& operator=(const TemporaryFolder&) = delete;
    const std::filesystem::path& path() const { return path_; }
    // Writes `text` to `name` inside the folder (subfolders must exist).
    void write(const std::string& name, const std::string& text) const {
        std::ofstream(path_ / name) << text;
    }

private:
    std::filesystem::path path_;
};

inline bool all_finite(const FloatImage& image) {
    for (float value : image.pixels) {
        if (!std::isfinite(value)) return false;
    }
    return true;
}

// The build's loader with `override_dir` searched before the generated
// headers, so a header written there replaces the build-time one.
inline ShaderLoader loader_with_override(const std::filesystem::path& override_dir) {
    auto dirs = ShaderLoader::from_build_configuration().include_dirs();
    dirs.insert(dirs.begin() + 1, override_dir);
    return ShaderLoader(dirs);
}

}  // namespace deepgi::test
