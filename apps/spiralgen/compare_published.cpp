// spiralgen table --compare-published: the deep G-buffer paper's tau table
// (optimizer/include/spiral/published.hpp) next to the exact optimum.
#include <fmt/core.h>

#include <string>

#include "commands.hpp"
#include "spiral/optimizer.hpp"
#include "spiral/published.hpp"

namespace spiralgen {

std::string format_published_comparison(const std::vector<spiral::PublishedComparison>& rows,
                                        bool csv) {
    int ties = 0, one_off = 0, worse = 0;
    std::string one_off_list, worse_list;
    auto append = [](std::string& list, int n) {
        list += fmt::format("{}{}", list.empty() ? "" : ", ", n);
    };
    for (const auto& row : rows) {
        switch (row.verdict) {
            case spiral::PublishedVerdict::ties_optimum:
                ++ties;
                break;
            case spiral::PublishedVerdict::one_off:
                ++one_off;
                append(one_off_list, row.n);
                break;
            case spiral::PublishedVerdict::worse:
                ++worse;
                append(worse_list, row.n);
                break;
        }
    }
    std::string out;
    if (csv) {
        out = "n,published_tau,published_num,optimal_tau,optimal_num,den,verdict,optimal_for_n\n";
        for (const auto& row : rows)
            out += fmt::format("{},{},{},{},{},{},{},{}\n", row.n, row.published_tau,
                               row.published_scaled, row.optimal_tau, row.optimal_scaled,
                               row.denominator(),
                               row.verdict == spiral::PublishedVerdict::ties_optimum ? "ties"
                               : row.verdict == spiral::PublishedVerdict::one_off    ? "one-off"
                                                                                     : "worse",
                               row.optimal_for_n);
        return out;
    }
    out += fmt::format(
        "Published tau: Mara, McGuire, Nowrouzezahrai and Luebke, \"Deep G-Buffers for Stable "
        "Global Illumination Approximation\" (HPG 2016), Listing 3, for the spiral of McGuire, "
        "Mara and Luebke, \"Scalable Ambient Obscurance\" (HPG 2012). Its {} values are read "
        "with element i belonging to n = i + 1 taps. D = K / 4n^2 is exact.\n\n",
        rows.size());
    out += fmt::format(
        "{} of {} published values tie the optimum; {} are indexed one off (optimal for a "
        "neighbouring n{}{}); {} are worse{}{}.\n\n",
        ties, rows.size(), one_off, one_off ? ": n = " : "", one_off_list, worse,
        worse ? ": n = " : "", worse_list);
    // The other reading some ports use, element i for n = i: how many of
    // elements 1.. would then tie (element 0 has no n).
    const auto published = spiral::published_turns();
    int shifted_ties = 0;
    for (std::size_t i = 1; i < rows.size(); ++i)
        shifted_ties +=
            spiral::discrepancy_scaled(int(i), published[i]) == rows[i - 1].optimal_scaled;
    out += fmt::format(
        "Read the other way, element i for n = i, {} of {} would tie: the table is indexed "
        "by n - 1 (tau for n taps is element n - 1).\n\n",
        shifted_ties, rows.size() - 1);
    out +=
        "| n | published tau | D(n, published) | optimal tau | D optimum | verdict |\n"
        "|--:|--:|--:|--:|--:|:--|\n";
    for (const auto& row : rows) {
        std::string verdict{spiral::to_string(row.verdict)};
        if (row.verdict == spiral::PublishedVerdict::one_off)
            verdict += fmt::format(" (optimal for n = {})", row.optimal_for_n);
        else if (row.verdict == spiral::PublishedVerdict::worse)
            verdict += fmt::format(" ({:.2f}x the optimum)",
                                   double(row.published_scaled) / double(row.optimal_scaled));
        out += fmt::format("| {} | {} | {}/{} = {:.6f} | {} | {}/{} = {:.6f} | {} |\n", row.n,
                           row.published_tau, row.published_scaled, row.denominator(),
                           double(row.published_scaled) / double(row.denominator()),
                           row.optimal_tau, row.optimal_scaled, row.denominator(),
                           double(row.optimal_scaled) / double(row.denominator()), verdict);
    }
    return out;
}

}  // namespace spiralgen
