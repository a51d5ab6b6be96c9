// The glTF loader's scene assembly: the node graph flattened into one
// triangle list per material, with materials, textures, the default camera and a
// summary of what the renderer does not use (cameras and lights:
// gltf_cameras_lights.cpp).
#include "gltf_assembly.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <map>

namespace deepgi::gltf {

namespace {

glm::mat4 node_transform(const tinygltf::Node& node) {
    if (node.matrix.size() == 16) {
        glm::mat4 matrix;
        for (int i = 0; i < 16; ++i) glm::value_ptr(matrix)[i] = float(node.matrix[std::size_t(i)]);
        return matrix;
    }
    glm::mat4 transform(1.0f);
    if (node.translation.size() == 3) {
        transform = glm::translate(
            transform, glm::vec3(node.translation[0], node.translation[1], node.translation[2]));
    }
    if (node.rotation.size() == 4) {
        glm::quat rotation(float(node.rotation[3]), float(node.rotation[0]),
                           float(node.rotation[1]), float(node.rotation[2]));
        transform *= glm::mat4_cast(rotation);
    }
    if (node.scale.size() == 3)
        transform = glm::scale(transform, glm::vec3(node.scale[0], node.scale[1], node.scale[2]));
    return transform;
}

// Strips and fans as a plain triangle list, winding as the glTF specification
// defines it: strip triangle i is (i, i+1, i+2) for even i and (i, i+2, i+1)
// for odd i, so every triangle keeps the first one's orientation; fan triangle
// i is (i+1, i+2, 0).
std::vector<std::uint32_t> triangle_list(int mode, std::vector<std::uint32_t> indices) {
    if (mode == TINYGLTF_MODE_TRIANGLES) return indices;
    std::vector<std::uint32_t> triangles;
    const std::size_t n = indices.size();
    if (n < 3) return triangles;
    triangles.reserve((n - 2) * 3);
    for (std::size_t i = 0; i + 2 < n; ++i) {
        if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
            const bool odd = i % 2 == 1;
            triangles.insert(triangles.end(), {indices[i], indices[odd ? i + 2 : i + 1],
                                               indices[odd ? i + 1 : i + 2]});
        } else {
            triangles.insert(triangles.end(), {indices[i + 1], indices[i + 2], indices[0]});
        }
    }
    return triangles;
}

// "3 skins" / "1 skin"; empty for none.
std::string counted(std::uint64_t n, std::string_view noun) {
    if (n == 0) return "";
    return fmt::format("{} {}{}", n, noun, n == 1 ? "" : "s");
}

// One line naming everything in the file that the renderer does not use, so
// nothing is dropped silently: "ignored: 2 skins, 1 animation, KHR_texture_transform".
std::string ignored_summary(const tinygltf::Model& model, std::uint64_t orthographic_cameras) {
    std::uint64_t morph_targets = 0, extra_colour_sets = 0, tangents = 0, extra_uv_sets = 0;
    for (const auto& mesh : model.meshes) {
        for (const auto& primitive : mesh.primitives) {
            morph_targets += primitive.targets.size();
            for (const auto& [name, accessor] : primitive.attributes) {
                if (name.rfind("COLOR_", 0) == 0 && name != "COLOR_0") ++extra_colour_sets;
                if (name == "TANGENT") ++tangents;
                if (name.rfind("TEXCOORD_", 0) == 0 && name != "TEXCOORD_0") ++extra_uv_sets;
            }
        }
    }
    // Normal textures are skipped, not half-used: shading normals from a
    // normal map need tangents (given or MikkTSpace-generated), which the
    // G-buffer does not carry.
    std::uint64_t normal_maps = 0, occlusion_maps = 0, metal_rough_maps = 0;
    for (const auto& material : model.materials) {
        normal_maps += material.normalTexture.index >= 0;
        occlusion_maps += material.occlusionTexture.index >= 0;
        metal_rough_maps += material.pbrMetallicRoughness.metallicRoughnessTexture.index >= 0;
    }
    std::vector<std::string> parts = {
        counted(model.skins.size(), "skin"),
        counted(model.animations.size(), "animation"),
        counted(morph_targets, "morph target"),
        counted(orthographic_cameras, "orthographic camera"),
        counted(extra_colour_sets, "extra vertex colour set"),
        counted(tangents, "tangent set"),
        counted(extra_uv_sets, "extra texture coordinate set"),
        counted(normal_maps, "normal texture"),
        counted(occlusion_maps, "occlusion texture"),
        counted(metal_rough_maps, "metallic-roughness texture"),
    };
    for (const auto& extension : model.extensionsUsed)
        if (extension != "KHR_materials_emissive_strength" && extension != "KHR_lights_punctual")
            parts.push_back(extension);
    std::string line;
    for (const auto& part : parts) {
        if (part.empty()) continue;
        line += line.empty() ? "ignored: " : ", ";
        line += part;
    }
    return line;
}

}  // namespace

// The node-visit and triangle limits bound each kind of work; the clock
// bounds their sum (a fan-out of shared nodes stays under both and still
// takes minutes).
void SceneAssembly::check_time() const {
    const auto limit = std::chrono::seconds(std::min<std::uint64_t>(limits.load_seconds, 1u << 30));
    if (std::chrono::steady_clock::now() - start > limit)
        reader.fail(
            fmt::format("flattening the node graph took more than {} s (raise with --scene-limit "
                        "load-seconds=N)",
                        limits.load_seconds));
}

void SceneAssembly::add_primitive(const tinygltf::Primitive& primitive,
                                  const glm::mat4& transform) {
    // Each placement of a primitive costs its accessors' setup whatever its
    // size, so placements are counted on their own.
    if (++instances > limits.instances)
        reader.fail(fmt::format(
            "the scene draws more than {} mesh primitive instances (raise with --scene-limit "
            "instances=N)",
            limits.instances));
    check_time();
    const int mode = primitive.mode == -1 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode == TINYGLTF_MODE_POINTS || mode == TINYGLTF_MODE_LINE ||
        mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP) {
        // Not surfaces: nothing for a G-buffer to hold. Counted for one warning.
        ++skipped_points_and_lines;
        return;
    }
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP &&
        mode != TINYGLTF_MODE_TRIANGLE_FAN) {
        reader.fail(fmt::format("primitive mode {} is not supported", primitive.mode));
    }
    const auto position_attribute = primitive.attributes.find("POSITION");
    if (position_attribute == primitive.attributes.end())
        reader.fail("a primitive has no POSITION attribute");
    std::size_t vertex_count = 0;
    auto read_position = reader.accessor_reader(position_attribute->second, 3, vertex_count);
    std::function<float(std::size_t, int)> read_normal;
    std::function<float(std::size_t, int)> read_uv;
    if (auto it = primitive.attributes.find("NORMAL"); it != primitive.attributes.end()) {
        std::size_t count = 0;
        read_normal = reader.accessor_reader(it->second, 3, count);
        if (count != vertex_count) reader.fail("NORMAL and POSITION counts differ");
    }
    if (auto it = primitive.attributes.find("TEXCOORD_0"); it != primitive.attributes.end()) {
        std::size_t count = 0;
        read_uv = reader.accessor_reader(it->second, 2, count);
        if (count != vertex_count) reader.fail("TEXCOORD_0 and POSITION counts differ");
    }
    // COLOR_0: RGB or RGBA, float or normalised unsigned byte or short
    // (the only forms the specification allows), linear.
    std::function<float(std::size_t, int)> read_colour;
    int colour_components = 0;
    if (auto it = primitive.attributes.find("COLOR_0"); it != primitive.attributes.end()) {
        if (it->second < 0 || it->second >= int(model.accessors.size()))
            reader.fail("accessor index out of range");
        const auto& accessor = model.accessors[std::size_t(it->second)];
        colour_components = accessor.type == TINYGLTF_TYPE_VEC3   ? 3
                            : accessor.type == TINYGLTF_TYPE_VEC4 ? 4
                                                                  : 0;
        const bool float_colour = accessor.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
        const bool normalised_colour =
            accessor.normalized &&
            (accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
             accessor.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
        if (colour_components == 0 || !(float_colour || normalised_colour))
            reader.fail(
                fmt::format("COLOR_0 (accessor {}) must be VEC3 or VEC4 of float, or of normalized "
                            "unsigned byte or short",
                            it->second));
        std::size_t count = 0;
        read_colour = reader.accessor_reader(it->second, colour_components, count);
        if (count != vertex_count) reader.fail("COLOR_0 and POSITION counts differ");
    }
    std::vector<std::uint32_t> local_indices;
    if (primitive.indices >= 0) {
        local_indices = reader.read_indices(primitive.indices);
    } else {
        local_indices.resize(vertex_count);
        for (std::size_t i = 0; i < vertex_count; ++i)
            local_indices[i] = static_cast<std::uint32_t>(i);
    }
    local_indices = triangle_list(mode, std::move(local_indices));
    if (local_indices.size() % 3 != 0) reader.fail("triangle index count is not a multiple of 3");
    if (primitive.material >= int(model.materials.size()))
        reader.fail("material index out of range");
    const bool double_sided =
        primitive.material >= 0 && model.materials[std::size_t(primitive.material)].doubleSided;
    // Counted before any vertex is emitted, so an instanced mesh stops here.
    triangles += (local_indices.size() / 3) * (double_sided ? 2 : 1);
    if (triangles > limits.triangles)
        reader.fail(
            fmt::format("the scene instantiates more than {} triangles (raise with --scene-limit "
                        "triangles=N)",
                        limits.triangles));
    // Every triangle becomes 3 vertices and 3 indices (flat, after instancing).
    const std::uint64_t triangle_bytes = 3 * (sizeof(Vertex) + sizeof(std::uint32_t));
    if (triangles > limits.geometry_bytes / triangle_bytes)
        reader.fail(fmt::format(
            "the scene's geometry after instancing needs more than {} bytes ({} per triangle; "
            "raise with --scene-limit geometry-bytes=N)",
            limits.geometry_bytes, triangle_bytes));
    for (auto index : local_indices) {
        if (index >= vertex_count) reader.fail("an index refers past the end of the vertices");
    }
    const glm::mat3 normal_matrix = glm::transpose(glm::inverse(glm::mat3(transform)));
    const bool mirrored = glm::determinant(glm::mat3(transform)) < 0.0f;
    // Without normals every triangle gets its own flat-shaded vertices.
    const bool flat = !read_normal;
    auto& target = indices_by_material[primitive.material];
    // The renderer culls back faces, so a double-sided material gets each
    // triangle twice: the back copy wound the other way, its normal flipped.
    auto emit_vertex = [&](std::uint32_t i, glm::vec3 flat_normal, bool back = false) {
        Vertex vertex;
        vertex.position = glm::vec3(transform * glm::vec4(read_position(i, 0), read_position(i, 1),
                                                          read_position(i, 2), 1.0f));
        vertex.normal =
            flat ? flat_normal
                 : glm::normalize(normal_matrix * glm::vec3(read_normal(i, 0), read_normal(i, 1),
                                                            read_normal(i, 2)));
        if (!std::isfinite(vertex.normal.x)) vertex.normal = flat_normal;
        if (back) vertex.normal = -vertex.normal;
        vertex.uv = read_uv ? glm::vec2(read_uv(i, 0), read_uv(i, 1)) : glm::vec2(0.0f);
        if (read_colour) {
            vertex.colour = glm::vec4(read_colour(i, 0), read_colour(i, 1), read_colour(i, 2),
                                      colour_components == 4 ? read_colour(i, 3) : 1.0f);
            if (!std::isfinite(vertex.colour.r + vertex.colour.g + vertex.colour.b +
                               vertex.colour.a))
                reader.fail("a COLOR_0 value is not finite");
        }
        if (!std::isfinite(vertex.position.x) || !std::isfinite(vertex.position.y) ||
            !std::isfinite(vertex.position.z)) {
            reader.fail("a vertex position is not finite");
        }
        scene.vertices.push_back(vertex);
        target.push_back(static_cast<std::uint32_t>(scene.vertices.size() - 1));
    };
    for (std::size_t t = 0; t < local_indices.size(); t += 3) {
        std::uint32_t a = local_indices[t];
        std::uint32_t b = local_indices[t + 1];
        std::uint32_t c = local_indices[t + 2];
        if (mirrored) std::swap(b, c);
        auto world = [&](std::uint32_t i) {
            return glm::vec3(transform * glm::vec4(read_position(i, 0), read_position(i, 1),
                                                   read_position(i, 2), 1.0f));
        };
        glm::vec3 face = glm::cross(world(b) - world(a), world(c) - world(a));
        const float length = glm::length(face);
        const glm::vec3 flat_normal = length > 0.0f ? face / length : glm::vec3(0, 1, 0);
        emit_vertex(a, flat_normal);
        emit_vertex(b, flat_normal);
        emit_vertex(c, flat_normal);
        if (double_sided) {
            emit_vertex(a, flat_normal, true);
            emit_vertex(c, flat_normal, true);
            emit_vertex(b, flat_normal, true);
        }
    }
}

// A node listed by several parents is visited once per path, so a few
// nodes can describe 2^40 visits; the depth limit alone does not bound that.
void SceneAssembly::visit(int node_index, const glm::mat4& parent, int depth) {
    if (node_index < 0 || node_index >= int(model.nodes.size()))
        reader.fail("node index out of range");
    if (depth > 64) reader.fail("node hierarchy is too deep (cycle?)");
    check_time();
    if (++visits > limits.node_visits)
        reader.fail(
            fmt::format("the node graph expands to more than {} node visits (nodes shared by "
                        "several parents count once per path; raise with --scene-limit "
                        "node-visits=N)",
                        limits.node_visits));
    const auto& node = model.nodes[std::size_t(node_index)];
    const glm::mat4 transform = parent * node_transform(node);
    if (auto it = node.extensions.find("KHR_lights_punctual");
        it != node.extensions.end() && it->second.Has("light")) {
        const auto& value = it->second.Get("light");
        const int light = value.IsInt() ? value.Get<int>() : -1;
        if (light < 0 || light >= int(model.lights.size()))
            reader.fail("KHR_lights_punctual light index out of range");
        add_light(light, transform);
    }
    if (node.camera >= 0) {
        if (node.camera >= int(model.cameras.size())) reader.fail("camera index out of range");
        add_camera(node.camera, node.name, transform);
    }
    if (node.mesh >= 0) {
        if (node.mesh >= int(model.meshes.size())) reader.fail("mesh index out of range");
        for (const auto& primitive : model.meshes[std::size_t(node.mesh)].primitives)
            add_primitive(primitive, transform);
    }
    for (int child : node.children) visit(child, transform, depth + 1);
}

// The default scene's node graph, or every mesh once when the file has no scene.
void SceneAssembly::flatten() {
    if (!model.scenes.empty()) {
        const int scene_index =
            model.defaultScene >= 0 && model.defaultScene < int(model.scenes.size())
                ? model.defaultScene
                : 0;
        for (int node : model.scenes[std::size_t(scene_index)].nodes)
            visit(node, glm::mat4(1.0f), 0);
    } else {
        for (std::size_t i = 0; i < model.meshes.size(); ++i) {
            for (const auto& primitive : model.meshes[i].primitives)
                add_primitive(primitive, glm::mat4(1.0f));
        }
    }
    if (scene.vertices.empty())
        reader.fail(skipped_points_and_lines == 0
                        ? std::string("contains no triangles")
                        : fmt::format("contains no triangles (only {} point or line primitives)",
                                      skipped_points_and_lines));
    if (skipped_points_and_lines > 0)
        scene.warnings.push_back(
            fmt::format("skipped {} point or line primitive(s): they are not surfaces",
                        skipped_points_and_lines));
}

// A glTF texture is an image plus a sampler; images are uploaded once,
// samplers travel with the material that uses them.
int SceneAssembly::use_texture(int texture_index, TextureSampler& sampler) {
    if (texture_index >= int(model.textures.size())) reader.fail("texture index out of range");
    const auto& texture = model.textures[std::size_t(texture_index)];
    const int image_index = texture.source;
    if (image_index < 0 || image_index >= int(model.images.size()))
        reader.fail("texture has no valid image");
    if (texture.sampler >= 0) {
        if (texture.sampler >= int(model.samplers.size()))
            reader.fail(fmt::format("texture {}: sampler index out of range", texture_index));
        sampler =
            read_sampler(model.samplers[std::size_t(texture.sampler)], texture.sampler, reader);
    }
    auto [it, inserted] = texture_of_image.try_emplace(image_index, int(scene.textures.size()));
    if (inserted)
        scene.textures.push_back(convert_image(model.images[std::size_t(image_index)], reader));
    return it->second;
}

// One material and one draw batch per material the triangles use.
void SceneAssembly::add_materials() {
    std::uint64_t blended_materials = 0;
    for (auto& [material_index, indices] : indices_by_material) {
        Material material;
        if (material_index >= 0) {
            if (material_index >= int(model.materials.size()))
                reader.fail("material index out of range");
            const auto& source = model.materials[std::size_t(material_index)];
            const auto& factor = source.pbrMetallicRoughness.baseColorFactor;
            if (factor.size() == 4)
                material.base_colour = glm::vec4(factor[0], factor[1], factor[2], factor[3]);
            // Kept for the mirror test (docs/reflections.md); the specification
            // bounds both to [0, 1].
            const double roughness = source.pbrMetallicRoughness.roughnessFactor;
            const double metallic = source.pbrMetallicRoughness.metallicFactor;
            if (!(roughness >= 0.0 && roughness <= 1.0) || !(metallic >= 0.0 && metallic <= 1.0))
                reader.fail(fmt::format(
                    "material {}: roughnessFactor and metallicFactor must lie in [0, 1]",
                    material_index));
            material.roughness = float(roughness);
            material.metallic = float(metallic);
            if (source.emissiveFactor.size() == 3) {
                material.emissive = glm::vec3(source.emissiveFactor[0], source.emissiveFactor[1],
                                              source.emissiveFactor[2]);
            }
            // KHR_materials_emissive_strength scales the factor past 1.
            if (auto it = source.extensions.find("KHR_materials_emissive_strength");
                it != source.extensions.end() && it->second.Has("emissiveStrength")) {
                const auto& value = it->second.Get("emissiveStrength");
                const double strength = value.IsNumber() ? value.GetNumberAsDouble() : -1.0;
                if (!(strength >= 0.0) || !std::isfinite(strength))
                    reader.fail(
                        fmt::format("material {}: emissiveStrength must be a finite number >= 0",
                                    material_index));
                material.emissive *= float(strength);
            }
            if (!finite_floats(material.base_colour) || !finite_floats(material.emissive))
                reader.fail(fmt::format(
                    "material {}: base colour or emissive (factor x strength) overflows a float",
                    material_index));
            if (source.alphaMode == "BLEND") {
                ++blended_materials;
            } else if (source.alphaMode == "MASK") {
                if (!(source.alphaCutoff >= 0.0) || !std::isfinite(source.alphaCutoff))
                    reader.fail(fmt::format("material {}: alphaCutoff must be a finite number >= 0",
                                            material_index));
                material.alpha_cutoff = float(source.alphaCutoff);
            } else if (source.alphaMode != "OPAQUE") {
                reader.fail(fmt::format("material {}: alphaMode '{}' is not OPAQUE, MASK or BLEND",
                                        material_index, source.alphaMode));
            }
            if (const int index = source.pbrMetallicRoughness.baseColorTexture.index; index >= 0)
                material.base_colour_texture = use_texture(index, material.base_colour_sampler);
            if (const int index = source.emissiveTexture.index; index >= 0)
                material.emissive_texture = use_texture(index, material.emissive_sampler);
        }
        scene.materials.push_back(material);
        DrawBatch batch;
        batch.first_index = static_cast<std::uint32_t>(scene.indices.size());
        batch.index_count = static_cast<std::uint32_t>(indices.size());
        batch.material = int(scene.materials.size()) - 1;
        scene.indices.insert(scene.indices.end(), indices.begin(), indices.end());
        scene.batches.push_back(batch);
    }

    if (blended_materials > 0)
        scene.warnings.push_back(fmt::format(
            "{} material(s) with alphaMode BLEND are rendered opaque", blended_materials));
}

// Bounds, the default and orbit cameras, the key light and the warnings.
void SceneAssembly::finish() {
    scene.bounds = compute_bounds(scene.vertices);
    const glm::vec3 centre = (scene.bounds.min + scene.bounds.max) * 0.5f;
    const float radius = std::max(glm::length(scene.bounds.max - scene.bounds.min) * 0.5f, 1e-3f);
    // Default view: three-quarter, from the front right and above (35 degrees
    // round, 30 down), so a box shows three faces instead of a flat card, far
    // enough to see the bounding sphere whole with a tenth to spare.
    Camera camera;
    camera.vertical_fov = glm::radians(50.0f);
    camera.near_plane = std::max(radius * 1e-3f, 1e-4f);
    const float distance = 1.1f * radius / std::sin(camera.vertical_fov * 0.5f);
    camera.yaw = glm::radians(-35.0f);
    camera.pitch = glm::radians(-30.0f);
    camera.position = centre - camera_forward(camera) * distance;
    scene.default_camera = camera;
    if (!scene.file_cameras.empty()) {
        scene.default_camera = scene.file_cameras.front().camera;
        if (rolled_camera)
            scene.warnings.push_back("camera roll is ignored (the view is levelled)");
    } else {
        scene.warnings.push_back("the file has no perspective camera; using a fitted view");
    }
    if (const std::string ignored = ignored_summary(model, orthographic_cameras); !ignored.empty())
        scene.warnings.push_back(ignored);
    scene.camera_path.frames_per_key = 30;
    for (int key = 0; key < 4; ++key) {  // orbit around the centre
        Camera orbit = camera;
        orbit.yaw = glm::radians(30.0f * float(key) - 45.0f);
        orbit.position = centre - camera_forward(orbit) * distance;
        scene.camera_path.keys.push_back(orbit);
    }
    if (!have_key_light) {
        scene.key_light.kind = LightKind::directional;
        scene.key_light.direction = glm::normalize(glm::vec3(0.3f, -1.0f, -0.4f));
        scene.key_light.intensity = 3.0f;
    }
    if (!dropped_lights.empty()) {
        std::string list;
        for (const auto& light : dropped_lights) list += (list.empty() ? "" : ", ") + light;
        scene.warnings.push_back("dropped lights: " + list);
    }
    scene.ambient = glm::vec3(0.05f);
    scene.background = glm::vec3(0.2f, 0.22f, 0.25f);
}

Scene build_scene(const tinygltf::Model& model, const std::string& display_name,
                  const std::string& scene_name, const SceneLimits& limits) {
    SceneAssembly assembly(model, limits, display_name);
    assembly.scene.name = scene_name;
    assembly.flatten();
    assembly.add_materials();
    assembly.finish();
    return std::move(assembly.scene);
}

}  // namespace deepgi::gltf
