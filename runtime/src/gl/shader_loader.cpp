#include "deepgi/shader_loader.hpp"

#include "deepgi/errors.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cstring>
#include <fstream>
#include <regex>
#include <sstream>

namespace deepgi {

namespace fs = std::filesystem;

namespace {

constexpr int max_include_depth = 16;

std::string read_text_file(const fs::path& path) {
    std::ifstream stream(path, std::ios::binary);
    if (!stream) throw GraphicsError(fmt::format("cannot read shader file '{}'", path.string()));
    std::ostringstream text;
    text << stream.rdbuf();
    return text.str();
}

// `#include "name"` with optional whitespace; anything else is left to the driver.
bool parse_include(const std::string& line, std::string& name) {
    static const std::regex include_pattern(R"(^\s*#\s*include\s+"([^"]+)\"\s*(//.*)?$)");
    std::smatch match;
    if (!std::regex_match(line, match, include_pattern)) return false;
    name = match[1].str();
    return true;
}

bool is_version_line(const std::string& line) {
    static const std::regex version_pattern(R"(^\s*#\s*version\b.*$)");
    return std::regex_match(line, version_pattern);
}

std::vector<std::string> split_lines(const std::string& text) {
    std::vector<std::string> lines;
    std::string current;
    for (char c : text) {
        if (c == '\n') {
            lines.push_back(current);
            current.clear();
        } else if (c != '\r') {
            current.push_back(c);
        }
    }
    if (!current.empty()) lines.push_back(current);
    return lines;
}

const char* stage_name(GLenum type) {
    switch (type) {
        case GL_VERTEX_SHADER:
            return "vertex";
        case GL_GEOMETRY_SHADER:
            return "geometry";
        case GL_FRAGMENT_SHADER:
            return "fragment";
        case GL_COMPUTE_SHADER:
            return "compute";
        default:
            return "shader";
    }
}

}  // namespace

ShaderLoader::ShaderLoader(std::vector<fs::path> include_dirs) {
    for (auto& dir : include_dirs) {
        if (!dir.empty()) include_dirs_.push_back(std::move(dir));
    }
}

ShaderLoader ShaderLoader::from_build_configuration(fs::path first) {
    return ShaderLoader({std::move(first), fs::path(DEEPGI_SHADER_SOURCE_DIR),
                         fs::path(DEEPGI_GENERATED_SHADER_DIR)});
}

fs::path ShaderLoader::resolve(const std::string& name, const fs::path& including_dir) const {
    // The first directory wins even over the including file's own: it may be
    // a folder of edited copies (deepgi --shaders), and an edited include
    // must replace the build's file beside the shader that includes it.
    if (!include_dirs_.empty() && fs::is_regular_file(include_dirs_.front() / name))
        return include_dirs_.front() / name;
    if (!including_dir.empty() && fs::is_regular_file(including_dir / name))
        return including_dir / name;
    for (const auto& dir : include_dirs_) {
        if (fs::is_regular_file(dir / name)) return dir / name;
    }
    return {};
}

void ShaderLoader::expand_file(const fs::path& path, ExpandedShaderSource& out,
                               std::vector<fs::path>& included, int depth) const {
    const int file_index = static_cast<int>(out.files.size());
    out.files.push_back(path.lexically_normal().string());
    const auto lines = split_lines(read_text_file(path));
    // Source string numbers in #line directives are how the driver log names files.
    out.text += fmt::format("#line 1 {}\n", file_index);
    for (std::size_t i = 0; i < lines.size(); ++i) {
        std::string include_name;
        if (!parse_include(lines[i], include_name)) {
            out.text += lines[i];
            out.text += '\n';
            continue;
        }
        const fs::path target = resolve(include_name, path.parent_path());
        if (target.empty()) {
            throw GraphicsError(fmt::format("{}:{}: cannot find included file \"{}\"",
                                            out.files[file_index], i + 1, include_name));
        }
        if (depth >= max_include_depth) {
            throw GraphicsError(fmt::format("{}:{}: includes nest deeper than {}",
                                            out.files[file_index], i + 1, max_include_depth));
        }
        // Every header is included once, like #pragma once, so shared headers can be
        // included by several headers of one shader.
        const fs::path canonical = fs::weakly_canonical(target);
        if (std::find(included.begin(), included.end(), canonical) == included.end()) {
            included.push_back(canonical);
            expand_file(target, out, included, depth + 1);
        }
        out.text += fmt::format("#line {} {}\n", i + 2, file_index);
    }
}

ExpandedShaderSource ShaderLoader::expand(const std::string& file,
                                          const std::string& defines) const {
    const fs::path path = resolve(file, {});
    if (path.empty()) throw GraphicsError(fmt::format("cannot find shader file '{}'", file));
    ExpandedShaderSource body;
    std::vector<fs::path> included{fs::weakly_canonical(path)};
    expand_file(path, body, included, 0);

    // #version must stay the first line; defines and the body follow it.
    ExpandedShaderSource result;
    result.files = body.files;
    const auto lines = split_lines(body.text);
    std::size_t version_index = lines.size();
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (is_version_line(lines[i])) {
            version_index = i;
            break;
        }
    }
    if (version_index == lines.size())
        throw GraphicsError(fmt::format("{}: no #version line", file));
    result.text = lines[version_index] + "\n" + defines;
    if (!defines.empty() && defines.back() != '\n') result.text += '\n';
    for (std::size_t i = 0; i < lines.size(); ++i) {
        if (i == version_index) {
            result.text += "\n";  // keeps the line count of the original file
        } else {
            result.text += lines[i];
            result.text += '\n';
        }
    }
    return result;
}

std::string map_shader_log(const std::string& log, const std::vector<std::string>& files) {
    static const std::regex mesa_prefix(R"(^(\d+):(\d+)\((\d+)\): (.*)$)");
    static const std::regex nvidia_prefix(R"(^(\d+)\((\d+)\) ?: (.*)$)");
    std::string mapped;
    auto file_name = [&](const std::string& index_text) {
        std::size_t index = std::stoul(index_text);
        return index < files.size() ? files[index] : fmt::format("<source {}>", index);
    };
    for (const auto& line : split_lines(log)) {
        std::smatch match;
        if (std::regex_match(line, match, mesa_prefix)) {
            mapped += fmt::format("{}:{}:{}: {}\n", file_name(match[1]), match[2].str(),
                                  match[3].str(), match[4].str());
        } else if (std::regex_match(line, match, nvidia_prefix)) {
            mapped +=
                fmt::format("{}:{}: {}\n", file_name(match[1]), match[2].str(), match[3].str());
        } else if (!line.empty()) {
            mapped += line + "\n";
        }
    }
    return mapped;
}

gl::Program ShaderLoader::build_program(const std::vector<ShaderStage>& stages,
                                        const std::string& defines) const {
    ++*programs_built_;
    gl::Program program(glCreateProgram());
    std::vector<gl::Shader> shaders;
    for (const auto& stage : stages) {
        const ExpandedShaderSource source = expand(stage.file, defines);
        gl::Shader shader(glCreateShader(stage.type));
        const char* text = source.text.c_str();
        glShaderSource(shader.get(), 1, &text, nullptr);
        glCompileShader(shader.get());
        GLint compiled = GL_FALSE;
        glGetShaderiv(shader.get(), GL_COMPILE_STATUS, &compiled);
        if (compiled != GL_TRUE) {
            GLint length = 0;
            glGetShaderiv(shader.get(), GL_INFO_LOG_LENGTH, &length);
            std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
            glGetShaderInfoLog(shader.get(), length, nullptr, log.data());
            log.resize(std::strlen(log.c_str()));
            throw GraphicsError(fmt::format("cannot compile {} shader {}:\n{}",
                                            stage_name(stage.type), stage.file,
                                            map_shader_log(log, source.files)));
        }
        glAttachShader(program.get(), shader.get());
        shaders.push_back(std::move(shader));
    }
    glLinkProgram(program.get());
    GLint linked = GL_FALSE;
    glGetProgramiv(program.get(), GL_LINK_STATUS, &linked);
    if (linked != GL_TRUE) {
        GLint length = 0;
        glGetProgramiv(program.get(), GL_INFO_LOG_LENGTH, &length);
        std::string log(static_cast<std::size_t>(std::max(length, 1)), '\0');
        glGetProgramInfoLog(program.get(), length, nullptr, log.data());
        std::string files;
        for (const auto& stage : stages) files += " " + stage.file;
        throw GraphicsError(fmt::format("cannot link program{}: {}", files, log.c_str()));
    }
    for (const auto& shader : shaders) glDetachShader(program.get(), shader.get());
    return program;
}

}  // namespace deepgi
