// glTF 2.0 through tinygltf. Reads positions, normals, TEXCOORD_0 (to look up
// the textures), COLOR_0, base colour factor and texture with its sampler,
// alpha mode and cutoff, emissive factor, texture and strength, cameras and
// KHR_lights_punctual; everything else is named in one summary warning.
#include "gltf_internal.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

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

// The bytes of files a scene reads (the scene file, its external buffers and
// images) against the file-bytes limit, and the first refusal's reason.
struct FileBudget {
    const SceneLimits* limits = nullptr;
    std::uint64_t bytes_read = 0;
};

// The whole of a regular file, or the reason it was not read. Opened
// non-blocking, so a FIFO cannot stall the open; anything but a regular file
// (a FIFO, a directory, a device) is refused before a byte is read, and the
// size is checked against the limit before anything is allocated.
std::string read_regular_file(const std::string& path, FileBudget& budget,
                              std::vector<unsigned char>& out) {
    if (path.find('\0') != std::string::npos)
        return "its name holds a NUL byte (a %00 percent-escape)";
    const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) return errno == ENOENT ? "does not exist" : std::strerror(errno);
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    struct stat status {};
    if (::fstat(fd, &status) != 0) return std::strerror(errno);
    if (!S_ISREG(status.st_mode)) return "not a regular file";
    const std::uint64_t size = std::uint64_t(status.st_size);
    const std::uint64_t limit = budget.limits->file_bytes;
    if (size > limit || budget.bytes_read > limit - size)
        return fmt::format(
            "its {} bytes bring the scene's files to {} bytes, above the limit of {} (raise "
            "with --scene-limit file-bytes=N)",
            size, budget.bytes_read + size, limit);
    budget.bytes_read += size;
    out.resize(std::size_t(size));
    std::size_t done = 0;
    while (done < out.size()) {
        const ssize_t n = ::read(fd, out.data() + done, out.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n < 0) return std::strerror(errno);
        if (n == 0) return "the file shrank while it was read";
        done += std::size_t(n);
    }
    return "";
}

// tinygltf's file-system callbacks for a scene read from disk: paths are
// used as given (no shell-style expansion), and every read goes through
// read_regular_file.
bool file_exists(const std::string& path, void*) {
    struct stat status {};
    return path.find('\0') != std::string::npos || ::stat(path.c_str(), &status) == 0;
}
std::string expand_nothing(const std::string& path, void*) {
    return path;
}
bool read_within_budget(std::vector<unsigned char>* out, std::string* error,
                        const std::string& path, void* user_data) {
    const std::string reason = read_regular_file(path, *static_cast<FileBudget*>(user_data), *out);
    if (!reason.empty() && error) *error += reason;
    return reason.empty();
}

// Refuses what tinygltf would otherwise read out of bounds or let through:
// a GLB whose chunks run past the file (tinygltf's own check of the BIN
// chunk forgets its 8-byte header).
void check_glb_layout(std::span<const std::uint8_t> bytes, const std::string& display_name) {
    auto refuse = [&](const std::string& what) {
        throw InputError(fmt::format("glTF file '{}': {}", display_name, what));
    };
    if (bytes.size() < 20) refuse("a GLB file needs at least 20 bytes");
    auto u32 = [&](std::size_t at) {
        return std::uint64_t(bytes[at]) | std::uint64_t(bytes[at + 1]) << 8 |
               std::uint64_t(bytes[at + 2]) << 16 | std::uint64_t(bytes[at + 3]) << 24;
    };
    const std::uint64_t length = u32(8);
    if (length > bytes.size())
        refuse(fmt::format("the GLB header says {} bytes, the file has {}", length, bytes.size()));
    const std::uint64_t json_end = 20 + u32(12);
    if (json_end > length)
        refuse(fmt::format("the JSON chunk ends at byte {}, past the GLB's {} bytes", json_end,
                           length));
    if (json_end + 8 <= length) {
        const std::uint64_t bin_end = json_end + 8 + u32(std::size_t(json_end));
        if (bin_end > length)
            refuse(fmt::format("the BIN chunk ends at byte {}, past the GLB's {} bytes", bin_end,
                               length));
    }
}

// Refuses a file that requires an extension this loader does not implement,
// as the specification says a loader must.
void refuse_unimplemented_extensions(const std::vector<std::string>& required,
                                     const std::string& display_name) {
    for (const auto& extension : required)
        if (extension != "KHR_lights_punctual" && extension != "KHR_materials_emissive_strength")
            throw InputError(
                fmt::format("glTF file '{}': extension {} is required by the file, "
                            "and this loader does not implement it",
                            display_name, extension));
}

// What the specification says a loader must refuse: another major version,
// a minVersion above 2.0, and required extensions it does not implement.
void check_specification(const tinygltf::Model& model, const std::string& display_name) {
    auto refuse = [&](const std::string& what) {
        throw InputError(fmt::format("glTF file '{}': {}", display_name, what));
    };
    const std::string& version = model.asset.version;
    if (version.size() < 3 || version.compare(0, 2, "2.") != 0 ||
        !std::all_of(version.begin() + 2, version.end(),
                     [](unsigned char c) { return std::isdigit(c); }))
        refuse(fmt::format("asset.version '{}' is not 2.x (only glTF 2 is read)", version));
    const std::string& minimum = model.asset.minVersion;
    if (!minimum.empty() && minimum != "2.0")
        refuse(fmt::format("asset.minVersion '{}' is above 2.0, the version this loader reads",
                           minimum));
    refuse_unimplemented_extensions(model.extensionsRequired, display_name);
}

// The names in the file's "extensionsRequired" array, found in its JSON text
// alone, for a file tinygltf could not load: a Draco-compressed mesh has
// accessors with no buffer view, and tinygltf's "accessor[0] invalid
// bufferView" would hide that the file needs an extension. Only the message
// of a refused file depends on it, so a plain scan serves: the first such key
// followed by an array of plain strings; anything else gives no names.
std::vector<std::string> required_extension_names(std::string_view json) {
    const std::string_view key = "\"extensionsRequired\"";
    std::size_t at = json.find(key);
    if (at == std::string_view::npos) return {};
    at += key.size();
    auto skip_space = [&] {
        while (at < json.size() && std::isspace(static_cast<unsigned char>(json[at]))) ++at;
    };
    auto take = [&](char c) {
        skip_space();
        if (at >= json.size() || json[at] != c) return false;
        ++at;
        return true;
    };
    if (!take(':') || !take('[')) return {};
    std::vector<std::string> names;
    if (take(']')) return names;
    do {
        if (!take('"')) return {};
        const std::size_t end = json.find('"', at);
        const std::string_view name = json.substr(at, end - at);
        if (end == std::string_view::npos || name.find('\\') != std::string_view::npos) return {};
        names.emplace_back(name);
        at = end + 1;
    } while (take(','));
    return take(']') ? names : std::vector<std::string>{};
}

// The checked, limited parse into tinygltf's model. Returned by value so the
// caller can free the file's bytes before the scene is built (peak memory).
tinygltf::Model parse_gltf(std::span<const std::uint8_t> bytes, bool binary,
                           const std::string& display_name, const std::string& base_dir,
                           FileBudget* files, const SceneLimits& limits) {
    const std::string_view json = json_text(bytes, binary);
    const std::uint64_t depth = json_depth(json, limits.json_depth);
    if (depth > limits.json_depth)
        throw InputError(fmt::format(
            "glTF file '{}': JSON nests deeper than {} levels (raise with --scene-limit "
            "json-depth=N)",
            display_name, limits.json_depth));
    if (const std::string bad = malformed_uri(json); !bad.empty())
        throw InputError(fmt::format("glTF file '{}': {}", display_name, bad));
    // tinygltf takes the length as unsigned int.
    if (bytes.size() > 0xffffffffu)
        throw InputError(fmt::format("glTF file '{}' is larger than 4 GiB", display_name));
    if (binary) check_glb_layout(bytes, display_name);
    tinygltf::TinyGLTF loader;
    tinygltf::Model model;
    ImageBudget budget{&limits, &model, 0};
    loader.SetImageLoader(load_image_within_limits, &budget);
    if (files == nullptr)
        loader.SetFsCallbacks(
            tinygltf::FsCallbacks{no_file_exists, no_expand, no_read, no_write, nullptr});
    else
        loader.SetFsCallbacks(tinygltf::FsCallbacks{file_exists, expand_nothing, read_within_budget,
                                                    no_write, files});
    std::string error;
    std::string warning;
    bool loaded = false;
    try {
        loaded = binary ? loader.LoadBinaryFromMemory(&model, &error, &warning, bytes.data(),
                                                      unsigned(bytes.size()), base_dir)
                        : loader.LoadASCIIFromString(&model, &error, &warning,
                                                     reinterpret_cast<const char*>(bytes.data()),
                                                     unsigned(bytes.size()), base_dir);
    } catch (const std::bad_alloc&) {
        throw InputError(fmt::format(
            "cannot load glTF file '{}': it asks for more memory than there is", display_name));
    } catch (const std::exception& failure) {
        // tinygltf indexes some arrays with at() (a GLB buffer of byteLength
        // 0, for one): what it throws is a fault of the file.
        throw InputError(fmt::format("cannot load glTF file '{}': malformed ({})", display_name,
                                     one_line(failure.what())));
    }
    if (!loaded) {
        refuse_unimplemented_extensions(required_extension_names(json), display_name);
        throw InputError(fmt::format("cannot load glTF file '{}': {}", display_name,
                                     one_line(error.empty() ? "unknown error" : error)));
    }
    check_specification(model, display_name);
    return model;
}

}  // namespace

Scene load_gltf_scene(const fs::path& path, const SceneLimits& limits) {
    const fs::path directory = path.has_parent_path() ? path.parent_path() : fs::path(".");
    FileBudget files{&limits, 0};
    tinygltf::Model model;
    {
        // One read of the whole file, through the same checks as the files it names.
        std::vector<std::uint8_t> bytes;
        if (const std::string reason = read_regular_file(path.string(), files, bytes);
            !reason.empty())
            throw InputError(fmt::format("cannot read scene file '{}': {}", path.string(), reason));
        // The content decides, not the name: a .glb holding JSON is read as JSON.
        const GltfKind kind = sniff_gltf(bytes);
        if (kind == GltfKind::none)
            throw InputError(
                fmt::format("scene file '{}' is not a glTF file (neither GLB magic "
                            "nor a JSON object)",
                            path.string()));
        model = parse_gltf(bytes, kind == GltfKind::binary, path.string(), directory.string(),
                           &files, limits);
    }  // the file's bytes are freed before the scene is built
    Scene scene = build_scene(model, path.string(), path.stem().string(), limits);
    for (const auto& warning : scene.warnings)
        fmt::print(stderr, "warning: glTF file '{}': {}\n", path.string(), warning);
    return scene;
}

Scene load_gltf_scene_from_memory(std::span<const std::uint8_t> bytes, bool binary,
                                  std::string_view name, const SceneLimits& limits) {
    const tinygltf::Model model = parse_gltf(bytes, binary, std::string(name), "", nullptr, limits);
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
    // A path that cannot even be examined (a symlink loop, an over-long
    // name) goes to the loader too, which names the reason.
    std::error_code error;
    const bool exists = fs::exists(path, error);
    if (extension == ".gltf" || extension == ".glb" || exists || error)
        return load_gltf_scene(path, limits);
    return make_builtin_scene(name_or_path);
}

}  // namespace deepgi
