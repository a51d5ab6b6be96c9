// Where does double precision choose a different number of turns than the
// exact integer search? For every n in [1, max_n] this runs spiral::search
// (exact) and a double-precision evaluator (spiral/float_compare.hpp)
// that picks the tau with the smallest floating-point D, the first on ties,
// and writes one CSV row per n with the exact K of both choices.
//
//   float_tau_compare [max_n (default 1024)] [out.csv (default: stdout)]
//
// Rows where the choices differ are also printed as a Markdown table on stderr.
#include <cstdlib>
#include <string>
#include <vector>

#include <fmt/core.h>

#include "spiral/fileio.hpp"
#include "spiral/float_compare.hpp"

int main(int argc, char** argv) {
    int max_n = 1024;
    if (argc > 1) {
        char* end = nullptr;
        const long v = std::strtol(argv[1], &end, 10);
        if (*end != '\0' || v < 1 || v > 4096) {
            fmt::print(stderr, "float_tau_compare: max_n must be an integer in [1, 4096]\n");
            return 2;
        }
        max_n = int(v);
    }
    const std::vector<spiral_float::Choice> choices = spiral_float::compare_float_search(max_n);

    std::string csv =
        "n,exact_tau,exact_K,float_tau,float_tau_exact_K,denominator,differs,exact_tie\n";
    std::string table =
        "| n | exact tau | exact K | double tau | K of double tau | 4n^2 | exact tie |\n"
        "|---|---|---|---|---|---|---|\n";
    int differing = 0, ties = 0, worse = 0;
    for (const spiral_float::Choice& c : choices) {
        // A different tau with the same K is another exact minimiser that
        // rounding ranked first; a larger K is a worse pattern.
        if (c.differs()) (c.tie() ? ties : worse) += 1;
        csv +=
            fmt::format("{},{},{},{},{},{},{},{}\n", c.n, c.exact_tau, c.exact_k, c.float_tau,
                        c.float_tau_exact_k, c.denominator, c.differs() ? 1 : 0, c.tie() ? 1 : 0);
        if (c.differs()) {
            ++differing;
            table += fmt::format("| {} | {} | {} | {} | {} | {} | {} |\n", c.n, c.exact_tau,
                                 c.exact_k, c.float_tau, c.float_tau_exact_k, c.denominator,
                                 c.tie() ? "yes" : "no");
        }
    }
    try {
        if (argc > 2) {
            spiral::fileio::AtomicFile out(argv[2]);
            out.write(csv);
            out.commit();
        } else {
            fmt::print("{}", csv);
        }
    } catch (const std::exception& error) {
        fmt::print(stderr, "float_tau_compare: {}\n", error.what());
        return 2;
    }
    if (differing == 0)
        fmt::print(stderr, "n in [1, {}]: double picks the exact tau for every n (none differ)\n",
                   max_n);
    else
        fmt::print(stderr,
                   "n in [1, {}]: {} differ ({} another exact minimiser, {} a larger K)\n{}", max_n,
                   differing, ties, worse, table);
    return 0;
}
