// Writes the fuzzer's seed corpus (tests/fuzz/corpus): valid files and every
// hostile case the loader's tests cover, built by the same functions. Run
// once when a case is added: make_corpus <directory>.
#include "../support/gltf_support.hpp"

#include <stb_image_write.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

using namespace deepgi::test;

namespace {

void save(const std::filesystem::path& path, const std::string& bytes) {
    std::ofstream(path, std::ios::binary) << bytes;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2 && argc != 3) return 2;
    const std::filesystem::path dir(argv[1]);
    std::filesystem::create_directories(dir);
    save(dir / "valid-triangle.gltf", triangle_gltf({}));
    TriangleFile no_indices;
    no_indices.with_indices = false;
    save(dir / "valid-no-indices.gltf", triangle_gltf(no_indices));
    TriangleFile dag;
    dag.nodes = dag_nodes(6);
    save(dir / "valid-dag-64.gltf", triangle_gltf(dag));
    std::vector<std::uint8_t> rgba;
    for (int i = 0; i < 16; ++i) rgba.push_back(std::uint8_t(i * 16));
    std::vector<std::uint8_t> png;
    stbi_write_png_to_func(
        [](void* c, void* d, int n) {
            auto& o = *static_cast<std::vector<std::uint8_t>*>(c);
            o.insert(o.end(), static_cast<std::uint8_t*>(d), static_cast<std::uint8_t*>(d) + n);
        },
        &png, 2, 2, 4, rgba.data(), 8);
    TriangleFile textured;
    textured.primitive_extra = R"(,"material":0)";
    textured.extra = image_members({png});
    save(dir / "valid-textured.gltf", triangle_gltf(textured));
    {
        std::vector<std::uint8_t> buffer;
        for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) append(buffer, v);
        for (std::uint32_t i : {0u, 1u, 2u}) append(buffer, i);
        std::string json = triangle_gltf({});
        const std::size_t uri = json.find(R"(,"uri")");
        json.erase(uri, json.find('}', uri) - uri);
        save(dir / "valid-triangle.glb", glb(json, buffer));
    }
    TriangleFile offset;
    offset.position_fields = R"("count":3,"byteOffset":18446744073709551612)";
    save(dir / "huge-byteoffset.gltf", triangle_gltf(offset));
    TriangleFile indices;
    indices.index_fields = R"("count":4611686018427387907)";
    save(dir / "huge-index-count.gltf", triangle_gltf(indices));
    TriangleFile positions;
    positions.with_indices = false;
    positions.position_fields = R"("count":4611686018427387907)";
    save(dir / "huge-position-count.gltf", triangle_gltf(positions));
    save(dir / "deep-json-20000.gltf", deep_json(20000));
    dag.nodes = dag_nodes(20);
    save(dir / "dag-2-20.gltf", triangle_gltf(dag));
    dag.nodes = dag_nodes(40);
    save(dir / "dag-2-40.gltf", triangle_gltf(dag));
    textured.extra = image_members({png_header(16384, 16384)});
    save(dir / "png-16384.gltf", triangle_gltf(textured));

    // Second hostile corpus: images in buffer views, GLB chunks, total work,
    // float overflow and the specification's refusals.
    save(dir / "valid-view-image.glb", textured_glb(png));
    save(dir / "view-image-past-buffer.glb", textured_glb(png, 48, std::int64_t(png.size()) + 1));
    save(dir / "view-image-offset-past-buffer.glb", textured_glb(png, 1 << 30, 16));
    save(dir / "view-image-length-4g.glb", textured_glb(png, 48, std::int64_t(1) << 32));
    const std::vector<std::uint8_t> truncated(png.begin(),
                                              png.begin() + std::ptrdiff_t(png.size() / 2));
    save(dir / "view-image-truncated-png.glb", textured_glb(truncated));
    save(dir / "glb-empty-buffer.glb", textured_glb(png, 48, -1, 0));
    {
        std::string file = textured_glb(png);
        const std::size_t bin_header =
            20 + (std::size_t(std::uint8_t(file[12])) | std::size_t(std::uint8_t(file[13])) << 8);
        std::uint32_t length = 0;
        std::memcpy(&length, file.data() + bin_header, 4);
        length += 4;
        std::memcpy(file.data() + bin_header, &length, 4);
        save(dir / "glb-bin-chunk-past-end.glb", file);
    }
    TriangleFile fan;
    fan.nodes = fan_out_nodes(150);
    save(dir / "fan-out-150.gltf", triangle_gltf(fan));
    TriangleFile light;
    light.nodes =
        R"([{"mesh":0,"children":[1]},{"extensions":{"KHR_lights_punctual":{"light":0}}}])";
    light.extra =
        R"(,"extensionsUsed":["KHR_lights_punctual"],"extensions":{"KHR_lights_punctual":{"lights":[{"type":"directional","intensity":1e300}]}})";
    save(dir / "light-intensity-1e300.gltf", triangle_gltf(light));
    TriangleFile camera;
    camera.nodes = R"([{"mesh":0,"children":[1]},{"camera":0}])";
    camera.extra = R"(,"cameras":[{"type":"perspective","perspective":{"yfov":0.8,"znear":1e39}}])";
    save(dir / "camera-znear-1e39.gltf", triangle_gltf(camera));
    TriangleFile emissive;
    emissive.primitive_extra = R"(,"material":0)";
    emissive.extra =
        R"(,"materials":[{"emissiveFactor":[1,1,1],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":1e300}}}])";
    save(dir / "emissive-strength-1e300.gltf", triangle_gltf(emissive));
    TriangleFile draco;
    draco.extra =
        R"(,"extensionsUsed":["KHR_draco_mesh_compression"],"extensionsRequired":["KHR_draco_mesh_compression"])";
    save(dir / "required-draco.gltf", triangle_gltf(draco));
    std::string version3 = triangle_gltf({});
    version3.replace(version3.find(R"("version":"2.0")"), 15, R"("version":"3.0")");
    save(dir / "version-3.gltf", version3);
    TriangleFile sparse;
    sparse.position_fields =
        R"("count":3,"sparse":{"count":1,"indices":{"bufferView":1,"componentType":5125},"values":{"bufferView":0}})";
    save(dir / "sparse-accessor.gltf", triangle_gltf(sparse));

    // The image fuzzer's seeds (make_corpus <gltf dir> <image dir>): a layout
    // byte (0: the view is exact, 1..5: it runs past the buffer in some way),
    // then the image file.
    if (argc == 3) {
        const std::filesystem::path images(argv[2]);
        std::filesystem::create_directories(images);
        auto image_seed = [&](const std::string& name, std::uint8_t layout,
                              const std::vector<std::uint8_t>& bytes) {
            std::string seed(1, char(layout));
            seed.append(bytes.begin(), bytes.end());
            save(images / name, seed);
        };
        image_seed("valid-png-2x2", 0, png);
        for (std::uint8_t layout = 1; layout < 6; ++layout)
            image_seed(fmt::format("png-2x2-layout-{}", layout), layout, png);
        image_seed("png-truncated", 0, truncated);
        image_seed("png-header-16384", 0, png_header(16384, 16384));
        std::vector<std::uint8_t> jpeg;
        stbi_write_jpg_to_func(
            [](void* c, void* d, int n) {
                auto& o = *static_cast<std::vector<std::uint8_t>*>(c);
                o.insert(o.end(), static_cast<std::uint8_t*>(d), static_cast<std::uint8_t*>(d) + n);
            },
            &jpeg, 2, 2, 4, rgba.data(), 90);
        image_seed("valid-jpeg-2x2", 0, jpeg);
        const std::vector<std::uint8_t> jpeg_truncated(
            jpeg.begin(), jpeg.begin() + std::ptrdiff_t(jpeg.size() / 2));
        image_seed("jpeg-truncated", 0, jpeg_truncated);
    }
    return 0;
}
