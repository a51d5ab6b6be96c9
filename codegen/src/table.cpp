// The tau table in the five formats of `spiralgen table`.
#include "text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace spiral::codegen {

std::optional<TableFormat> parse_table_format(std::string_view name) {
    if (name == "cpp") return TableFormat::cpp;
    if (name == "glsl") return TableFormat::glsl;
    if (name == "json") return TableFormat::json;
    if (name == "csv") return TableFormat::csv;
    if (name == "md") return TableFormat::md;
    return std::nullopt;
}

std::string_view to_string(TableFormat format) {
    switch (format) {
        case TableFormat::cpp:
            return "cpp";
        case TableFormat::glsl:
            return "glsl";
        case TableFormat::json:
            return "json";
        case TableFormat::csv:
            return "csv";
        case TableFormat::md:
            return "md";
    }
    throw std::invalid_argument("unknown table format");
}

namespace {

void check_results(const std::vector<SearchResult>& results) {
    if (results.empty()) throw std::invalid_argument("format_table: no results to format");
    int previous = 0;
    for (const SearchResult& r : results) {
        if (r.n <= previous)
            throw std::invalid_argument(
                fmt::format("format_table: n must be >= 1 and strictly ascending, got {} after {}",
                            r.n, previous));
        previous = r.n;
    }
}

std::string join_ties(const std::vector<int>& ties, std::string_view separator) {
    return fmt::format("{}", fmt::join(ties, separator));
}

// The table as max_n + 1 entries indexed by n; 0 where nothing was computed.
std::vector<int> dense_turns(const std::vector<SearchResult>& results) {
    std::vector<int> turns(static_cast<std::size_t>(results.back().n) + 1, 0);
    for (const SearchResult& r : results) turns[static_cast<std::size_t>(r.n)] = r.tau;
    return turns;
}

// Rows of 16 entries, each prefixed with the index of its first entry, so a
// reader can find n without counting commas.
std::string array_body(const std::vector<int>& turns) {
    constexpr std::size_t per_row = 16;
    const int index_width = static_cast<int>(fmt::formatted_size("{}", turns.size() - 1));
    std::string body;
    for (std::size_t row = 0; row < turns.size(); row += per_row) {
        body += fmt::format("    /* {:>{}} */", row, index_width);
        for (std::size_t i = row; i < std::min(turns.size(), row + per_row); ++i) {
            body += fmt::format(" {}", turns[i]);
            if (i + 1 < turns.size()) body += ',';
        }
        body += '\n';
    }
    return body;
}

std::string inputs_text(const std::vector<SearchResult>& results) {
    const bool contiguous =
        results.back().n - results.front().n + 1 == static_cast<int>(results.size());
    return fmt::format(
        "tau*(n), the smallest tau in [1, n] minimising the annular-sector discrepancy "
        "(design.md 1.2), for n = {}..{}{}",
        results.front().n, results.back().n, contiguous ? "" : " (with gaps)");
}

std::string format_cpp(const std::vector<SearchResult>& results, const Provenance& provenance) {
    const std::vector<int> turns = dense_turns(results);
    std::string out = detail::banner(provenance, "Spiral turns table (C++)", inputs_text(results));
    out += fmt::format(
        "//\n"
        "// kSpiralTurns[n] is the number of spiral turns for an n-tap pattern.\n"
        "// Entry 0 and every n outside the computed set hold 0, never a valid tau.\n"
        "#pragma once\n"
        "\n"
        "#include <array>\n"
        "\n"
        "namespace spiral::generated {{\n"
        "\n"
        "inline constexpr int kSpiralTurnsMinTaps = {};\n"
        "inline constexpr int kSpiralTurnsMaxTaps = {};\n"
        "inline constexpr std::array<int, {}> kSpiralTurns = {{\n",
        results.front().n, results.back().n, turns.size());
    out += array_body(turns);
    out += "};\n\n}  // namespace spiral::generated\n";
    return out;
}

std::string format_glsl(const std::vector<SearchResult>& results, const Provenance& provenance) {
    const std::vector<int> turns = dense_turns(results);
    std::string out = detail::banner(provenance, "Spiral turns table (GLSL)", inputs_text(results));
    out += fmt::format(
        "//\n"
        "// SPIRAL_TURNS[n] is the number of spiral turns for an n-tap pattern.\n"
        "// Entry 0 and every n outside the computed set hold 0, never a valid tau.\n"
        "#ifndef SPIRAL_TURNS_TABLE_GLSL\n"
        "#define SPIRAL_TURNS_TABLE_GLSL\n"
        "\n"
        "#define SPIRAL_TURNS_MIN_TAPS {}\n"
        "#define SPIRAL_TURNS_MAX_TAPS {}\n"
        "const int SPIRAL_TURNS[SPIRAL_TURNS_MAX_TAPS + 1] = int[](\n",
        results.front().n, results.back().n);
    out += array_body(turns);
    out += ");\n\n#endif  // SPIRAL_TURNS_TABLE_GLSL\n";
    return out;
}

std::string format_json(const std::vector<SearchResult>& results) {
    std::string out = "[\n";
    for (std::size_t i = 0; i < results.size(); ++i) {
        const SearchResult& r = results[i];
        out += fmt::format(
            "  {{\"n\":{},\"tau\":{},\"ties\":[{}],\"discrepancy\":{{\"num\":{},\"den\":{},"
            "\"value\":{}}}}}{}\n",
            r.n, r.tau, join_ties(r.ties, ","), r.scaled, r.denominator(),
            detail::double_text(r.value()), i + 1 < results.size() ? "," : "");
    }
    out += "]\n";
    return out;
}

std::string format_csv(const std::vector<SearchResult>& results) {
    std::string out = "n,tau,ties,num,den,value\n";
    for (const SearchResult& r : results)
        out += fmt::format("{},{},{},{},{},{}\n", r.n, r.tau, join_ties(r.ties, " "), r.scaled,
                           r.denominator(), detail::double_text(r.value()));
    return out;
}

std::string format_md(const std::vector<SearchResult>& results) {
    std::string out =
        "| n | tau | ties | K/4n^2 | value |\n"
        "|--:|--:|:--|--:|--:|\n";
    for (const SearchResult& r : results)
        out += fmt::format("| {} | {} | {} | {}/{} | {} |\n", r.n, r.tau, join_ties(r.ties, ", "),
                           r.scaled, r.denominator(), detail::double_text(r.value()));
    return out;
}

}  // namespace

std::string format_table(const std::vector<SearchResult>& results, TableFormat format,
                         const Provenance& provenance) {
    check_results(results);
    switch (format) {
        case TableFormat::cpp:
            return format_cpp(results, provenance);
        case TableFormat::glsl:
            return format_glsl(results, provenance);
        case TableFormat::json:
            return format_json(results);
        case TableFormat::csv:
            return format_csv(results);
        case TableFormat::md:
            return format_md(results);
    }
    throw std::invalid_argument("format_table: unknown table format");
}

}  // namespace spiral::codegen
