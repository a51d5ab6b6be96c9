// libFuzzer target: the glTF loader's whole CPU side (JSON, accessors, node
// graph, images, flattening into a Scene) on arbitrary bytes. Input starting
// with the GLB magic "glTF" is read as binary glTF, anything else as JSON.
// Limits are lowered so a single input stays fast; the limits' logic is the
// same code either way.
#include "deepgi/errors.hpp"
#include "deepgi/scene.hpp"

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <span>

// Loads one input as the fuzzer does; true when the loader accepted it, false
// when it refused it with an InputError. The corpus replay requires the
// valid seed files to be accepted.
bool gltf_fuzz_load(const std::uint8_t* data, std::size_t size) {
    deepgi::SceneLimits limits;
    limits.node_visits = 20'000;
    limits.triangles = 200'000;
    limits.texture_side = 512;
    limits.texture_bytes = 16u << 20;
    limits.instances = 5'000;
    limits.geometry_bytes = 64u << 20;
    limits.load_seconds = 5;
    const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    try {
        const deepgi::Scene scene = deepgi::load_gltf_scene_from_memory(
            std::span<const std::uint8_t>(data, size), binary, "fuzz", limits);
        // Whatever loads must be self-consistent: every index names a vertex,
        // every batch lies inside the indices.
        for (std::uint32_t index : scene.indices)
            if (index >= scene.vertices.size()) __builtin_trap();
        for (const auto& batch : scene.batches)
            if (std::uint64_t(batch.first_index) + batch.index_count > scene.indices.size())
                __builtin_trap();
        return true;
    } catch (const deepgi::InputError&) {
        // Refusing bad input with a message is the expected outcome.
        return false;
    }
}

// For the corpus replay (replay_main.cpp).
bool fuzz_target_accepts(const std::uint8_t* data, std::size_t size) {
    return gltf_fuzz_load(data, size);
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    gltf_fuzz_load(data, size);
    return 0;
}
