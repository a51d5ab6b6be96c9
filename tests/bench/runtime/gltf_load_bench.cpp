// gltf_load_bench: time and peak memory of loading a 1-million-triangle glTF
// (a 708 x 708 grid of quads with normals and 32-bit indices, as .glb), the
// valid-file cost that the loader's hardening must not raise.
//   gltf_load_bench [--runs N]
// Each run loads the file in a fresh child process, so its peak resident set
// (getrusage ru_maxrss) is the load's own. Prints the median wall time, the
// median peak RSS and the triangle count.
#include "deepgi/scene.hpp"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace {

template <typename T>
void append(std::vector<std::uint8_t>& out, T value) {
    std::uint8_t raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    out.insert(out.end(), raw, raw + sizeof(T));
}

void write_grid_glb(const fs::path& path, int quads) {
    const int side = quads + 1;
    std::vector<std::uint8_t> bin;
    for (int y = 0; y < side; ++y)
        for (int x = 0; x < side; ++x)
            for (float v : {float(x) / float(quads), 0.0f, float(y) / float(quads)}) append(bin, v);
    const std::size_t normals_offset = bin.size();
    for (int i = 0; i < side * side; ++i)
        for (float v : {0.0f, 1.0f, 0.0f}) append(bin, v);
    const std::size_t indices_offset = bin.size();
    for (int y = 0; y < quads; ++y) {
        for (int x = 0; x < quads; ++x) {
            const std::uint32_t a = std::uint32_t(y * side + x);
            const std::uint32_t b = a + 1;
            const std::uint32_t c = a + std::uint32_t(side);
            const std::uint32_t d = c + 1;
            for (std::uint32_t i : {a, c, b, b, c, d}) append(bin, i);
        }
    }
    const std::size_t vertex_bytes = normals_offset;
    const std::size_t index_count = std::size_t(quads) * std::size_t(quads) * 6;
    std::string json = fmt::format(
        R"({{"asset":{{"version":"2.0"}},"buffers":[{{"byteLength":{}}}],)"
        R"("bufferViews":[{{"buffer":0,"byteLength":{}}},{{"buffer":0,"byteOffset":{},"byteLength":{}}},)"
        R"({{"buffer":0,"byteOffset":{},"byteLength":{}}}],)"
        R"("accessors":[{{"bufferView":0,"componentType":5126,"count":{},"type":"VEC3","min":[0,0,0],"max":[1,0,1]}},)"
        R"({{"bufferView":1,"componentType":5126,"count":{},"type":"VEC3"}},)"
        R"({{"bufferView":2,"componentType":5125,"count":{},"type":"SCALAR"}}],)"
        R"("meshes":[{{"primitives":[{{"attributes":{{"POSITION":0,"NORMAL":1}},"indices":2}}]}}],)"
        R"("nodes":[{{"mesh":0}}],"scenes":[{{"nodes":[0]}}],"scene":0}})",
        bin.size(), vertex_bytes, normals_offset, vertex_bytes, indices_offset, index_count * 4,
        side * side, side * side, index_count);
    while (json.size() % 4) json += ' ';
    std::vector<std::uint8_t> out;
    out.reserve(28 + json.size() + bin.size());
    append(out, 0x46546c67u);
    append(out, 2u);
    append(out, std::uint32_t(28 + json.size() + bin.size()));
    append(out, std::uint32_t(json.size()));
    append(out, 0x4e4f534au);
    out.insert(out.end(), json.begin(), json.end());
    append(out, std::uint32_t(bin.size()));
    append(out, 0x004e4942u);
    out.insert(out.end(), bin.begin(), bin.end());
    std::ofstream(path, std::ios::binary)
        .write(reinterpret_cast<const char*>(out.data()), std::streamsize(out.size()));
}

struct Run {
    double seconds = 0;
    double peak_mib = 0;
    std::size_t triangles = 0;
};

// One load in a child; the child reports through a pipe.
Run load_in_child(const fs::path& path) {
    int channel[2];
    if (::pipe(channel) != 0) throw std::runtime_error("pipe failed");
    const pid_t pid = ::fork();
    if (pid == 0) {
        ::close(channel[0]);
        const auto start = std::chrono::steady_clock::now();
        const deepgi::Scene scene = deepgi::load_gltf_scene(path);
        Run run;
        run.seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        rusage usage{};
        ::getrusage(RUSAGE_SELF, &usage);
        run.peak_mib = double(usage.ru_maxrss) / 1024.0;
        run.triangles = scene.indices.size() / 3;
        const bool sent = ::write(channel[1], &run, sizeof run) == sizeof run;
        ::_exit(sent ? 0 : 1);
    }
    ::close(channel[1]);
    Run run;
    const bool received = ::read(channel[0], &run, sizeof run) == sizeof run;
    ::close(channel[0]);
    int status = 0;
    ::waitpid(pid, &status, 0);
    if (!received || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        throw std::runtime_error("the loading child failed");
    return run;
}

}  // namespace

int main(int argc, char** argv) {
    int runs = 5;
    int grid = 708;  // 708^2 quads = 1,002,528 triangles
    CLI::App app{"gltf_load_bench: load time and peak memory of a generated glTF grid"};
    app.add_option("--frames", runs, "Loads timed, each in a fresh child (median reported)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1000));
    app.add_option("--grid", grid, "Quads per side of the generated grid")
        ->capture_default_str()
        ->check(CLI::Range(1, 4096));
    CLI11_PARSE(app, argc, argv);
    const fs::path dir = fs::temp_directory_path() / fmt::format("gltf-bench-{}", ::getpid());
    fs::create_directories(dir);
    const fs::path path = dir / "grid.glb";
    write_grid_glb(path, grid);
    std::vector<Run> results;
    for (int i = 0; i < runs; ++i) results.push_back(load_in_child(path));
    fs::remove_all(dir);
    auto median = [&](auto member) {
        std::vector<double> values;
        for (const auto& run : results) values.push_back(run.*member);
        std::sort(values.begin(), values.end());
        return values[values.size() / 2];
    };
    fmt::print(
        "glTF grid load ({} triangles, {} runs): median {:.3f} s, median peak RSS "
        "{:.0f} MiB\n",
        results.front().triangles, runs, median(&Run::seconds), median(&Run::peak_mib));
    return 0;
}
