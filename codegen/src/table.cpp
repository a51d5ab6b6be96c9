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
        if (r.m != results.front().m)
            throw std::invalid_argument(fmt::format(
                "format_table: mixed turn denominators {} and {}", results.front().m, r.m));
    }
    if (results.front().m < 1)
        throw std::invalid_argument(
            fmt::format("format_table: turn denominator {} is below 1", results.front().m));
}

// tau as text: the integer for m = 1, else the fraction p/m as the search
// found it (not reduced, so p and m read straight off).
std::string turns_text(std::int64_t p, std::int64_t m) {
    return m == 1 ? fmt::format("{}", p) : fmt::format("{}/{}", p, m);
}

std::string join_turns(const std::vector<int>& ties, std::int64_t m, std::string_view separator) {
    std::vector<std::string> parts;
    for (const int p : ties) parts.push_back(turns_text(p, m));
    return fmt::format("{}", fmt::join(parts, separator));
}

// The lines that say how to read a table of numerators; empty for m = 1 so
// that integer tables keep their bytes.
std::string denominator_note(std::int64_t m, std::string_view table, std::string_view name) {
    if (m == 1) return "";
    return fmt::format(
        "// With fractional turns the entries are numerators: {} holds p for\n"
        "// tau = p / {} turns ({} = {}).\n",
        table, m, name, m);
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
    const std::int64_t m = results.front().m;
    const std::string space =
        m == 1 ? "tau*(n) in [1, n]" : fmt::format("tau*(n) = p / {0} with p in [1, {0} n]", m);
    return fmt::format(
        "{} minimising the annular-sector discrepancy, among ties the one whose band profile "
        "is preferred (docs/design.md, section 2), for n = {}..{}{}",
        space, results.front().n, results.back().n, contiguous ? "" : " (with gaps)");
}

std::string format_cpp(const std::vector<SearchResult>& results, const Provenance& provenance) {
    const std::vector<int> turns = dense_turns(results);
    std::string out = detail::banner(provenance, "Spiral turns table (C++)", inputs_text(results));
    out += fmt::format(
        "//\n"
        "// Indexed by the tap count itself, not n - 1: kSpiralTurns[n] is the number of\n"
        "// spiral turns for an n-tap pattern, e.g. int tau = kSpiralTurns[9];\n"
        "// Entry 0 and every n outside the computed set hold 0, never a valid tau.\n"
        "{}"
        "#pragma once\n"
        "\n"
        "#include <array>\n"
        "\n"
        "namespace spiral::generated {{\n"
        "\n"
        "inline constexpr int kSpiralTurnsMinTaps = {};\n"
        "inline constexpr int kSpiralTurnsMaxTaps = {};\n"
        "{}"
        "inline constexpr std::array<int, {}> kSpiralTurns = {{\n",
        denominator_note(results.front().m, "kSpiralTurns[n]", "kSpiralTurnsDenominator"),
        results.front().n, results.back().n,
        results.front().m == 1 ? std::string()
                               : fmt::format("inline constexpr int kSpiralTurnsDenominator = {};\n",
                                             results.front().m),
        turns.size());
    out += array_body(turns);
    out += "};\n\n}  // namespace spiral::generated\n";
    return out;
}

std::string format_glsl(const std::vector<SearchResult>& results, const Provenance& provenance) {
    const std::vector<int> turns = dense_turns(results);
    std::string out = detail::banner(provenance, "Spiral turns table (GLSL)", inputs_text(results));
    out += fmt::format(
        "//\n"
        "// Indexed by the tap count itself, not n - 1: SPIRAL_TURNS[n] is the number of\n"
        "// spiral turns for an n-tap pattern, e.g. int tau = SPIRAL_TURNS[NUM_TAPS];\n"
        "// Entry 0 and every n outside the computed set hold 0, never a valid tau.\n"
        "{}"
        "#ifndef SPIRAL_TURNS_TABLE_GLSL\n"
        "#define SPIRAL_TURNS_TABLE_GLSL\n"
        "\n"
        "#define SPIRAL_TURNS_MIN_TAPS {}\n"
        "#define SPIRAL_TURNS_MAX_TAPS {}\n"
        "{}"
        "const int SPIRAL_TURNS[SPIRAL_TURNS_MAX_TAPS + 1] = int[](\n",
        denominator_note(results.front().m, "SPIRAL_TURNS[n]", "SPIRAL_TURNS_DENOMINATOR"),
        results.front().n, results.back().n,
        results.front().m == 1
            ? std::string()
            : fmt::format("#define SPIRAL_TURNS_DENOMINATOR {}\n", results.front().m));
    out += array_body(turns);
    out += ");\n\n#endif  // SPIRAL_TURNS_TABLE_GLSL\n";
    return out;
}

std::string format_json(const std::vector<SearchResult>& results) {
    std::string out = "[\n";
    for (std::size_t i = 0; i < results.size(); ++i) {
        const SearchResult& r = results[i];
        out += fmt::format(
            "  {{\"n\":{},\"tau\":{},\"p\":{},\"m\":{},\"ties\":[{}],\"discrepancy\":{{"
            "\"num\":{},\"den\":{},\"value\":{}}}}}{}\n",
            r.n,
            r.m == 1 ? fmt::format("{}", r.tau) : detail::double_text(double(r.tau) / double(r.m)),
            r.tau, r.m, join_ties(r.ties, ","), r.scaled, r.denominator(),
            detail::double_text(r.value()), i + 1 < results.size() ? "," : "");
    }
    out += "]\n";
    return out;
}

std::string format_csv(const std::vector<SearchResult>& results) {
    std::string out = "n,tau,ties,num,den,value\n";
    for (const SearchResult& r : results)
        out += fmt::format("{},{},{},{},{},{}\n", r.n, turns_text(r.tau, r.m),
                           join_turns(r.ties, r.m, " "), r.scaled, r.denominator(),
                           detail::double_text(r.value()));
    return out;
}

std::string format_md(const std::vector<SearchResult>& results) {
    std::string out = fmt::format(
        "| n | tau | ties | K/4n^2{} | value |\n"
        "|--:|--:|:--|--:|--:|\n",
        results.front().m == 1 ? "" : "m");
    for (const SearchResult& r : results)
        out += fmt::format("| {} | {} | {} | {}/{} | {} |\n", r.n, turns_text(r.tau, r.m),
                           join_turns(r.ties, r.m, ", "), r.scaled, r.denominator(),
                           detail::double_text(r.value()));
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
