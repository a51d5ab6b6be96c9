#pragma once
// GLSL has no #include; this loader splices included files in and inserts
// #line directives so the driver's error log can be mapped back to the file and
// line the programmer wrote.
#include "deepgi/gl_objects.hpp"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace deepgi {

struct ExpandedShaderSource {
    std::string text;
    // files[i] is the file the driver calls source string i in its log.
    std::vector<std::string> files;
};

struct ShaderStage {
    GLenum type;
    std::string file;  // relative to one of the include directories
};

class ShaderLoader {
public:
    // Searched in order; the first is where top-level shader files live. An
    // include is looked up in the first, then beside the file that includes
    // it, then in the others.
    explicit ShaderLoader(std::vector<std::filesystem::path> include_dirs);

    // The directories the build configured: shaders/ and the generated headers.
    // `first`, when not empty, is searched before them, so a folder of edited
    // copies overrides the build's shaders file by file (deepgi --shaders):
    // a study can change a shader without touching the sources tests read.
    static ShaderLoader from_build_configuration(std::filesystem::path first = {});

    // `defines` is inserted right after the #version line (one #define per line).
    ExpandedShaderSource expand(const std::string& file, const std::string& defines = {}) const;

    // Compiles and links; throws GraphicsError with file:line messages on failure.
    gl::Program build_program(const std::vector<ShaderStage>& stages,
                              const std::string& defines = {}) const;

    const std::vector<std::filesystem::path>& include_dirs() const { return include_dirs_; }

    // Programs built by this loader and every copy of it (copies share the
    // count), so a test can see that a resize rebuilds nothing.
    int programs_built() const { return *programs_built_; }

private:
    std::filesystem::path resolve(const std::string& name,
                                  const std::filesystem::path& including_dir) const;
    void expand_file(const std::filesystem::path& path, ExpandedShaderSource& out,
                     std::vector<std::filesystem::path>& included, int depth) const;

    std::vector<std::filesystem::path> include_dirs_;
    std::shared_ptr<int> programs_built_ = std::make_shared<int>(0);
};

// Rewrites "0:12(3): error" (Mesa) and "0(12) : error" (NVIDIA) prefixes of a
// driver log into "file:12: error".
std::string map_shader_log(const std::string& log, const std::vector<std::string>& files);

}  // namespace deepgi
