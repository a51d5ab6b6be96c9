// Every settings row has one owner, a pass of the frame's list, and no other
// pass's code reads the row unless that pass declares the owner's value
// (PassValue, runtime/src/pass.hpp). Oracle for "reads": the text of each
// pass's own .cpp in runtime/src/passes, searched for the row's member
// (NumericSetting::field), through the settings or through a local alias of
// one of its groups; the search is checked to find every row its owner reads.
#include "deepgi/context.hpp"
#include "deepgi/renderer.hpp"
#include "deepgi/scene.hpp"
#include "deepgi/settings.hpp"
#include "pass.hpp"
#include "support/runtime_support.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace fs = std::filesystem;
using namespace deepgi;

namespace {

std::string file_text(const fs::path& path) {
    std::ifstream in(path);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

// The code of a file without comments and string literals, which may name a
// row's member without reading it ("sao.radius" is a value's name).
std::string code_only(const std::string& text) {
    static const std::regex comment(R"(//[^\n]*)");
    static const std::regex literal(R"("(\\.|[^"\\\n])*")");
    return std::regex_replace(std::regex_replace(text, comment, ""), literal, "\"\"");
}

std::string escaped(std::string_view text) {
    std::string out;
    for (char c : text) {
        if (c == '.') out += '\\';
        out += c;
    }
    return out;
}

// The library's helpers that read a row for their caller: calling one reads it.
struct RowHelper {
    std::string_view function;
    std::string_view field;
};
constexpr RowHelper row_helpers[] = {
    {"reflections_traced", "mirror_roughness"},      // passes/passes.hpp
    {"reflection_distance", "reflection.distance"},  // deepgi/settings.hpp
};

// Whether `code` reads the member `field` ("ao.radius", "mirror_roughness"):
// as `.ao.radius` / `->ao.radius`; as `alias.radius` where the code binds a
// name to the group (`const AoSettings& s = frame.settings->ao;`); by passing
// the group whole to a function (`f(frame.settings->blur, ...)`); or by
// calling a helper that reads it (row_helpers).
bool reads_field(const std::string& code, std::string_view field) {
    if (std::regex_search(code, std::regex(fmt::format(R"((\.|->){}\b)", escaped(field)))))
        return true;
    for (const RowHelper& helper : row_helpers)
        if (helper.field == field &&
            std::regex_search(code, std::regex(fmt::format(R"(\b{}\s*\()", helper.function))))
            return true;
    const auto dot = field.find('.');
    if (dot == std::string_view::npos) return false;
    const std::string group(field.substr(0, dot));
    const std::string member(field.substr(dot + 1));
    if (std::regex_search(code, std::regex(fmt::format(R"((\.|->){}\s*[,)])", group)))) return true;
    const std::regex alias(fmt::format(R"((\w+)\s*=\s*[^;=]*(\.|->){}\s*;)", group));
    for (auto it = std::sregex_iterator(code.begin(), code.end(), alias);
         it != std::sregex_iterator(); ++it) {
        const std::string name = (*it)[1];
        if (std::regex_search(code, std::regex(fmt::format(R"(\b{}\.{}\b)", name, member))))
            return true;
    }
    return false;
}

// The value a pass declares to read another pass's row: "<owner>.<member>".
std::string value_name(const NumericSetting& row) {
    const auto dot = row.field.rfind('.');
    return fmt::format("{}.{}", row.owner,
                       dot == std::string_view::npos ? row.field : row.field.substr(dot + 1));
}

// Each pass's name and the code of the file that defines it.
struct PassSource {
    std::string name;
    std::string code;
};

std::vector<PassSource> pass_sources() {
    std::vector<PassSource> sources;
    static const std::regex name_pattern(
        R"re(name\(\)\s*const\s*override\s*\{\s*return\s*"(\w+)";)re");
    for (const auto& entry : fs::directory_iterator(DEEPGI_PASSES_DIR)) {
        if (entry.path().extension() != ".cpp") continue;
        const std::string text = file_text(entry.path());
        std::smatch match;
        if (!std::regex_search(text, match, name_pattern)) continue;  // helpers (fullscreen.cpp)
        sources.push_back({match[1], code_only(text)});
    }
    return sources;
}

}  // namespace

TEST_CASE("settings owner: the search for reads finds what is known to be read",
          "[runtime][settings]") {
    // Checks of the oracle itself, on code written here.
    CHECK(reads_field("x = frame.settings->ao.radius;", "ao.radius"));
    CHECK(reads_field("const AoSettings& s = frame.settings->ao;\ny = s.radius;", "ao.radius"));
    CHECK(reads_field("m = settings.mirror_roughness;", "mirror_roughness"));
    CHECK_FALSE(
        reads_field(code_only("v = frame.value(\"sao.radius\"); // ao.radius"), "ao.radius"));
    CHECK_FALSE(reads_field("x = settings.blur.extent;", "ao.extent"));
    CHECK(reads_field("apply(blur_, frame.settings->blur, 1.0f);", "blur.extent"));
    CHECK(reads_field("if (reflections_traced(*scene_, settings)) {}", "mirror_roughness"));
    CHECK_FALSE(reads_field("const AoSettings& s = frame.settings->ao; y = s.radius;", "ao.alpha"));
}

TEST_CASE(
    "settings owner: every row's owner is a pass of the list, and no pass reads a row "
    "it does not own without declaring the owner's value",
    "[runtime][settings]") {
    HeadlessContext context;
    const ShaderLoader loader = ShaderLoader::from_build_configuration();
    // cornell has no mirror, gallery has: between them every pass runs.
    const Scene scenes[] = {make_builtin_scene("cornell"), make_builtin_scene("gallery")};

    // The values each pass declares it reads, under every AO method, with
    // and without a debug view, on both scenes (a pass reads some values
    // only under some settings).
    std::map<std::string, std::set<std::string>> declared;
    std::set<std::string> pass_names;
    for (const Scene& scene : scenes) {
        for (const PassFactory make : default_pass_list()) {
            const std::unique_ptr<Pass> pass = make(loader, scene);
            pass_names.insert(std::string(pass->name()));
            for (const auto& method : enum_names(AoMethod{})) {
                // The final image, and a debug view (the debug view pass runs then).
                for (const DebugView view : {DebugView::final_image, DebugView::ao_raw}) {
                    RenderSettings settings;
                    settings.ao.method = method.value;
                    settings.view = view;
                    if (!pass->enabled(settings)) continue;
                    for (const std::string& value : pass->declaration(settings).value_reads)
                        declared[std::string(pass->name())].insert(value);
                }
            }
        }
    }

    const std::vector<PassSource> sources = pass_sources();
    std::set<std::string> with_source;
    for (const PassSource& source : sources) with_source.insert(source.name);
    // Every pass of the list has its file, and every file found is a pass of the list.
    CHECK(with_source == pass_names);

    const std::string frame_code = code_only(file_text(DEEPGI_FRAME_SOURCE));
    for (const NumericSetting& row : numeric_settings()) {
        INFO("row --" << row.name << " (" << row.field << "), owner " << row.owner);
        // "frame": the guard band, which sizes every pass and which no pass reads.
        CHECK((pass_names.count(std::string(row.owner)) == 1 || row.owner == "frame"));
        REQUIRE(!row.field.empty());
        bool read_somewhere = reads_field(frame_code, row.field);
        for (const PassSource& source : sources) {
            if (!reads_field(source.code, row.field)) continue;
            read_somewhere = true;
            if (source.name == row.owner) continue;
            INFO("pass " << source.name << " reads it");
            CHECK(declared[source.name].count(value_name(row)) == 1);
        }
        // The search is not blind: every row is read by its owner's code or
        // by the frame (which puts some in the frame constants).
        CHECK(read_somewhere);
    }
}
