// glTF 2.0 through tinygltf. Reads positions, normals, TEXCOORD_0 (to look up
// the textures), COLOR_0, base colour factor and texture with its sampler,
// alpha mode and cutoff, emissive factor, texture and strength, cameras and
// KHR_lights_punctual; everything else is named in one summary warning.
#include "gltf_internal.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <fstream>

namespace deepgi {

namespace fs = std::filesystem;

namespace {

using namespace gltf;

// For bytes loaded from memory: no URI may reach the file system.
bool no_file_exists(const std::string&, void*) {
    return false;
}
std::string no_expand(const std::string& path, void*) {
    return path;
}
bool no_read(std::vector<unsigned char>*, std::string* error, const std::string& path, void*) {
    if (error) *error += fmt::format("'{}' is external; only embedded data is accepted. ", path);
    return false;
}
bool no_write(std::string* error, const std::string&, const std::vector<unsigned char>&, void*) {
    if (error) *error += "writing is not supported. ";
    return false;
}

// The checked, limited parse into tinygltf's model. Returned by value so the
// caller can free the file's bytes before the scene is built (peak memory).
tinygltf::Model parse_gltf(std::span<const std::uint8_t> bytes, bool binary,
                           const std::string& display_name, const std::string& base_dir,
                           bool allow_files, const SceneLimits& limits) {
    const std::uint64_t depth = json_depth(json_text(bytes, binary), limits.json_depth);
    if (depth > limits.json_depth)
        throw InputError(fmt::format(
            "glTF file '{}': JSON nests deeper than {} levels (raise with --scene-limit "
            "json-depth=N)",
            display_name, limits.json_depth));
    // tinygltf takes the length as unsigned int.
    if (bytes.size() > 0xffffffffu)
        throw InputError(fmt::format("glTF file '{}' is larger than 4 GiB", display_name));
    tinygltf::TinyGLTF loader;
    ImageBudget budget{&limits, 0};
    loader.SetImageLoader(load_image_within_limits, &budget);
    if (!allow_files)
        loader.SetFsCallbacks(
            tinygltf::FsCallbacks{no_file_exists, no_expand, no_read, no_write, nullptr});
    tinygltf::Model model;
    std::string error;
    std::string warning;
    const bool loaded =
        binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, bytes.data(),
                                             unsigned(bytes.size()), base_dir)
               : loader.LoadASCIIFromString(&model, &error, &warning,
                                            reinterpret_cast<const char*>(bytes.data()),
                                            unsigned(bytes.size()), base_dir);
    if (!loaded) {
        throw InputError(fmt::format("cannot load glTF file '{}': {}", display_name,
                                     one_line(error.empty() ? "unknown error" : error)));
    }
    return model;
}

}  // namespace

Scene load_gltf_scene(const fs::path& path, const SceneLimits& limits) {
    if (!fs::exists(path))
        throw InputError(fmt::format("scene file '{}' does not exist", path.string()));
    if (!fs::is_regular_file(path))
        throw InputError(fmt::format("scene file '{}' is not a regular file", path.string()));
    const fs::path directory = path.has_parent_path() ? path.parent_path() : fs::path(".");
    tinygltf::Model model;
    {
        // One read of the whole file (a byte-wise istreambuf_iterator copy
        // costs a tenth of a second per 24 MB).
        std::error_code error;
        const std::uintmax_t size = fs::file_size(path, error);
        if (error || size > 0xffffffffu)
            throw InputError(fmt::format("cannot read scene file '{}': {}", path.string(),
                                         error ? error.message() : "larger than 4 GiB"));
        std::vector<std::uint8_t> bytes(static_cast<std::size_t>(size));
        std::ifstream stream(path, std::ios::binary);
        if (!stream.read(reinterpret_cast<char*>(bytes.data()), std::streamsize(size)))
            throw InputError(fmt::format("cannot read scene file '{}'", path.string()));
        // The content decides, not the name: a .glb holding JSON is read as JSON.
        const GltfKind kind = sniff_gltf(bytes);
        if (kind == GltfKind::none)
            throw InputError(
                fmt::format("scene file '{}' is not a glTF file (neither GLB magic "
                            "nor a JSON object)",
                            path.string()));
        model = parse_gltf(bytes, kind == GltfKind::binary, path.string(), directory.string(), true,
                           limits);
    }  // the file's bytes are freed before the scene is built
    Scene scene = build_scene(model, path.string(), path.stem().string(), limits);
    for (const auto& warning : scene.warnings)
        fmt::print(stderr, "warning: glTF file '{}': {}\n", path.string(), warning);
    return scene;
}

Scene load_gltf_scene_from_memory(std::span<const std::uint8_t> bytes, bool binary,
                                  std::string_view name, const SceneLimits& limits) {
    const tinygltf::Model model = parse_gltf(bytes, binary, std::string(name), "", false, limits);
    return build_scene(model, std::string(name), std::string(name), limits);
}

Camera find_file_camera(const Scene& scene, std::string_view name_or_index) {
    for (const auto& file_camera : scene.file_cameras)
        if (file_camera.name == name_or_index) return file_camera.camera;
    int index = -1;
    const auto [end, error] =
        std::from_chars(name_or_index.data(), name_or_index.data() + name_or_index.size(), index);
    if (error == std::errc() && end == name_or_index.data() + name_or_index.size()) {
        for (const auto& file_camera : scene.file_cameras)
            if (file_camera.index == index) return file_camera.camera;
    }
    std::string known;
    for (const auto& file_camera : scene.file_cameras)
        known += fmt::format("{}{} '{}'", known.empty() ? "" : ", ", file_camera.index,
                             file_camera.name);
    throw InputError(fmt::format("--camera '{}': scene '{}' has no such perspective camera ({})",
                                 name_or_index, scene.name,
                                 known.empty() ? "it has none" : "it has " + known));
}

Scene load_scene(std::string_view name_or_path, const SceneLimits& limits) {
    const fs::path path(name_or_path);
    // A built-in name wins over a file of that name in the working directory.
    for (const auto& builtin : builtin_scene_names())
        if (name_or_path == builtin) return make_builtin_scene(name_or_path);
    if (name_or_path.substr(0, 4) == "ref-") return make_builtin_scene(name_or_path);
    std::string extension = path.extension().string();
    std::transform(extension.begin(), extension.end(), extension.begin(),
                   [](unsigned char c) { return char(std::tolower(c)); });
    // Named like glTF, or an existing file of any name: its content decides.
    if (extension == ".gltf" || extension == ".glb" || fs::exists(path))
        return load_gltf_scene(path, limits);
    return make_builtin_scene(name_or_path);
}

}  // namespace deepgi
