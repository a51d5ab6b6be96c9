#pragma once
// Scene data holds only what a pass reads: positions, normals, texture
// coordinates and colours; base colour (factor, texture, alpha mask) and
// emissive (factor and texture) per material;
// one key light; a camera and a repeatable camera path.
#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace deepgi {

struct Vertex {
    glm::vec3 position;
    glm::vec3 normal;
    glm::vec2 uv;
    glm::vec4 colour{1.0f};  // linear; multiplies the base colour (glTF COLOR_0)
};

// How a texture is read: GL filter and wrap enums, as glTF samplers name them.
struct TextureSampler {
    int mag_filter = 0x2601;  // GL_LINEAR
    int min_filter = 0x2703;  // GL_LINEAR_MIPMAP_LINEAR
    int wrap_s = 0x2901;      // GL_REPEAT
    int wrap_t = 0x2901;
    friend bool operator==(const TextureSampler&, const TextureSampler&) = default;
};

struct Material {
    glm::vec4 base_colour{1.0f};   // linear; alpha only matters for a mask
    glm::vec3 emissive{0.0f};      // linear radiance (times the emissive texture)
    int base_colour_texture = -1;  // index into Scene::textures, -1 for none
    TextureSampler base_colour_sampler;
    int emissive_texture = -1;  // index into Scene::textures, -1 for none
    TextureSampler emissive_sampler;
    // Alpha mask: fragments whose alpha (factor x texture x vertex colour) is
    // below this are not surfaces, in both G-buffer layers. Negative: opaque.
    float alpha_cutoff = -1.0f;
    // glTF's metallic-roughness factors (a file's material takes the file's,
    // whose defaults are 1 and 1; built-in materials are diffuse). A material
    // with roughness <= --mirror-roughness and metallic >= 0.5 is a mirror
    // (docs/reflections.md): its base colour is the reflectance of a perfect
    // mirror, and only its pixels trace reflected rays.
    float roughness = 1.0f;
    float metallic = 0.0f;
};

struct TextureImage {
    int width = 0;
    int height = 0;
    std::vector<std::uint8_t> rgba8;  // sRGB-encoded colour, linear alpha, rows top to bottom
};

// A contiguous index range drawn with one material.
struct DrawBatch {
    std::uint32_t first_index = 0;
    std::uint32_t index_count = 0;
    int material = 0;
};

struct Camera {
    glm::vec3 position{0.0f};
    float yaw = 0.0f;    // radians about +Y; 0 looks down -Z
    float pitch = 0.0f;  // radians; positive looks up
    float vertical_fov = glm::radians(60.0f);
    float near_plane = 0.05f;
};

// Keys are visited in order and the path returns to the first; between keys
// the camera moves with a smooth (C1) blend, so motion vectors stay moderate.
struct CameraPath {
    std::vector<Camera> keys;
    int frames_per_key = 24;
};

enum class LightKind { directional, spot, point };

struct KeyLight {
    LightKind kind = LightKind::directional;
    glm::vec3 position{0.0f};       // spot and point
    glm::vec3 direction{0, -1, 0};  // unit, the way the light travels (directional, spot)
    glm::vec3 colour{1.0f};
    // Irradiance in W/m^2 (directional) or radiant intensity in W/sr (spot,
    // point; falling off with the inverse square of the distance).
    float intensity = 3.0f;
    float outer_cone = glm::radians(60.0f);  // spot half angles
    float inner_cone = glm::radians(45.0f);
    // Spot and point: the distance (m) where the light ends, reached smoothly
    // by the window max(0, 1 - (d / range)^4) of KHR_lights_punctual; 0: unlimited.
    float range = 0.0f;

    friend bool operator==(const KeyLight&, const KeyLight&) = default;
};

// A perspective camera placed in a scene file, in file order of traversal.
struct FileCamera {
    std::string name;  // the camera's name, or its node's when the camera has none
    int index = 0;     // its index in the file's camera list
    Camera camera;
};

struct Bounds {
    glm::vec3 min{0.0f};
    glm::vec3 max{0.0f};
};

struct Scene {
    std::string name;
    std::vector<Vertex> vertices;
    std::vector<std::uint32_t> indices;  // triangles, counter-clockwise front faces
    std::vector<DrawBatch> batches;
    std::vector<Material> materials;
    std::vector<TextureImage> textures;
    Camera default_camera;
    CameraPath camera_path;
    KeyLight key_light;
    glm::vec3 ambient{0.03f};    // constant fill until the radiosity pass exists
    glm::vec3 background{0.0f};  // radiance where no surface is hit
    Bounds bounds;
    // What a scene file holds that is not rendered as written (one line each).
    // load_gltf_scene also prints them to stderr; the in-memory loader does not.
    std::vector<std::string> warnings;
    // The file's perspective cameras; default_camera is the first of them, or
    // a fitted view when there are none.
    std::vector<FileCamera> file_cameras;
};

std::vector<std::string> builtin_scene_names();

// Throws InputError for an unknown name.
Scene make_builtin_scene(std::string_view name);

// Small scenes for measuring deep SAO against the ray-traced reference
// (ref-crease, ref-slab, ref-board, ref-bench; docs/reference.md). Accepted by
// make_builtin_scene too, but not listed among the built-in scenes.
std::vector<std::string> reference_scene_names();
Scene make_reference_scene(std::string_view name);

// What one scene file may cost. A scene file is untrusted input: a few
// kilobytes can describe a JSON nesting that overflows the parser's stack, a
// node graph that instantiates one mesh 2^40 times, or a PNG that decodes to
// gigabytes. Each limit fails with a message naming it; raise it with
// set_scene_limit (deepgi: --scene-limit NAME=VALUE). docs/hardening.md.
struct SceneLimits {
    std::uint64_t json_depth = 128;             // nesting of JSON arrays and objects
    std::uint64_t node_visits = 1'000'000;      // nodes visited, counted once per path
    std::uint64_t triangles = 10'000'000;       // triangles after instancing
    std::uint64_t texture_side = 8192;          // pixels per side of one image
    std::uint64_t texture_bytes = 1u << 30;     // decoded bytes of all images together
    std::uint64_t instances = 100'000;          // mesh primitives drawn, after instancing
    std::uint64_t geometry_bytes = 2ull << 30;  // vertices and indices after instancing
    std::uint64_t load_seconds = 60;            // wall time of flattening the node graph
    std::uint64_t file_bytes = 2ull << 30;      // the scene file and its external files
};

// Sets one limit from "NAME=VALUE" (json-depth, node-visits, triangles,
// texture-side, texture-bytes, instances, geometry-bytes, load-seconds,
// file-bytes); throws InputError for anything else.
void set_scene_limit(SceneLimits& limits, std::string_view assignment);

// glTF 2.0 (.gltf or .glb). Throws InputError for a missing, malformed,
// unsupported or over-limit file.
Scene load_gltf_scene(const std::filesystem::path& path, const SceneLimits& limits = {});

// The same from bytes in memory, with no file access at all: buffers and
// images must be embedded (data: URIs or the GLB binary chunk). `name` is used
// in messages. This is the loader's whole CPU side, as the fuzzer drives it.
Scene load_gltf_scene_from_memory(std::span<const std::uint8_t> bytes, bool binary,
                                  std::string_view name, const SceneLimits& limits = {});

// A built-in name, or a path ending in .gltf/.glb.
Scene load_scene(std::string_view name_or_path, const SceneLimits& limits = {});

// The file camera named `name_or_index` (its name, or its index in the file's
// camera list); throws InputError naming the cameras there are.
Camera find_file_camera(const Scene& scene, std::string_view name_or_index);

// --camera pose:X,Y,Z,YAW,PITCH,FOVY,NEAR: an explicit camera, position in
// scene units, yaw, pitch and vertical field of view in degrees, near plane in
// scene units. Throws InputError "--camera '...': <problem>".
Camera parse_camera_pose(std::string_view text);
// The pose in that form, written so that parse_camera_pose gives back the same
// floats bit for bit (a window's view reproduced headless; camera.txt).
std::string format_camera_pose(const Camera& camera);
// What --camera names: empty, the scene's default camera; "pose:...", that
// pose; otherwise a file camera (find_file_camera).
Camera select_camera(const Scene& scene, std::string_view camera);

glm::vec3 camera_forward(const Camera& camera);
glm::mat4 camera_view_matrix(const Camera& camera);
Camera camera_on_path(const CameraPath& path, int frame);

Bounds compute_bounds(const std::vector<Vertex>& vertices);

}  // namespace deepgi
