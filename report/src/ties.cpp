// The report's tie table (report_ties.hpp). The exact columns come from the
// search itself; the sampling verdicts are a tie_error_study run's, read as
// written, since measuring every tie of 62 tap counts with repeats takes far
// longer than a report run (docs/optimizer.md, "Ties").
#include "deepgi/report_ties.hpp"

#include "deepgi/errors.hpp"

#include <spiral/fileio.hpp>
#include <spiral/optimizer.hpp>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

namespace fs = std::filesystem;

namespace deepgi::report {
namespace {

constexpr const char* kVerdictHeader =
    "n,pairs,pick,best_other,pick_mae,other_mae,difference,spread,mirror_spread,repeats,verdict";

// n -> the verdict row's fields after n (pairs .. verdict), as written.
std::map<int, std::vector<std::string>> read_verdicts(const fs::path& path) {
    std::map<int, std::vector<std::string>> rows;
    if (path.empty()) return rows;
    std::ifstream in(path);
    if (!in) throw InputError(fmt::format("--ties-from '{}' cannot be read", path.string()));
    std::string line;
    if (!std::getline(in, line) || line != kVerdictHeader)
        throw InputError(fmt::format(
            "--ties-from '{}' is not a tie_error_study --verdicts-csv file", path.string()));
    while (std::getline(in, line)) {
        std::vector<std::string> fields;
        std::stringstream row(line);
        for (std::string field; std::getline(row, field, ',');) fields.push_back(field);
        int n = 0;
        try {
            n = std::stoi(fields.at(0));
            for (std::size_t i : {2u, 3u, 9u}) (void)std::stoi(fields.at(i));
            for (std::size_t i : {4u, 5u, 6u, 7u, 8u}) (void)std::stod(fields.at(i));
        } catch (const std::exception&) {
            throw InputError(fmt::format("--ties-from '{}': bad row '{}'", path.string(), line));
        }
        if (fields.size() != 11 || n < 1 || n > 1024)
            throw InputError(fmt::format("--ties-from '{}': bad row '{}'", path.string(), line));
        rows[n] = std::vector<std::string>(fields.begin() + 1, fields.end());
    }
    return rows;
}

}  // namespace

TieVerdict judge_ties(const TieErrors& errors) {
    if (errors.mae.size() < 2 || !errors.mae.contains(errors.pick))
        throw std::invalid_argument("judge_ties: needs two tau or more, the pick among them");
    const std::size_t repeats = errors.mae.at(errors.pick).size();
    for (const auto& [tau, values] : errors.mae) {
        if (values.size() != repeats || repeats == 0)
            throw std::invalid_argument("judge_ties: every tau needs the same repeats");
        if (tau < 1 || tau >= errors.n)
            throw std::invalid_argument("judge_ties: every tau lies in [1, n - 1]");
    }
    // A pair's error in repeat r: the mean of its members (a lone tau is its
    // own pair, as tau = n / 2 is its own mirror).
    auto pair_of = [&](int tau) { return std::min(tau, errors.n - tau); };
    auto pair_mae = [&](int pair, std::size_t r) {
        double sum = 0.0;
        int count = 0;
        for (const int tau : std::set<int>{pair, errors.n - pair})
            if (auto it = errors.mae.find(tau); it != errors.mae.end()) {
                sum += it->second[r];
                ++count;
            }
        return sum / double(count);
    };
    auto mean = [&](auto&& value) {
        double sum = 0.0;
        for (std::size_t r = 0; r < repeats; ++r) sum += value(r);
        return sum / double(repeats);
    };
    TieVerdict v;
    v.n = errors.n;
    v.pick = errors.pick;
    v.repeats = int(repeats);
    const int pick_pair = pair_of(errors.pick);
    std::set<int> pairs;
    for (const auto& [tau, values] : errors.mae) pairs.insert(pair_of(tau));
    v.pairs = int(pairs.size());
    auto pair_mean = [&](int pair) {
        return mean([&](std::size_t r) { return pair_mae(pair, r); });
    };
    for (const int pair : pairs)
        if (pair != pick_pair && (v.other == 0 || pair_mean(pair) < pair_mean(v.other)))
            v.other = pair;
    // The mirror spread: how far a pattern's two reflections lie apart.
    for (const int pair : {pick_pair, v.other}) {
        if (pair == 0 || !errors.mae.contains(pair) || !errors.mae.contains(errors.n - pair))
            continue;
        v.mirror_spread = std::max(
            v.mirror_spread,
            std::abs(mean([&](std::size_t r) { return errors.mae.at(pair)[r]; }) -
                     mean([&](std::size_t r) { return errors.mae.at(errors.n - pair)[r]; })));
    }
    v.pick_mae = pair_mean(pick_pair);
    if (v.other == 0) {
        v.other_mae = v.pick_mae;
        v.verdict = kTieOnePair;
        return v;
    }
    v.other_mae = pair_mean(v.other);
    double low = 0.0, high = 0.0;
    for (std::size_t r = 0; r < repeats; ++r) {
        const double d = pair_mae(pick_pair, r) - pair_mae(v.other, r);
        v.difference += d / double(repeats);
        low = r == 0 ? d : std::min(low, d);
        high = r == 0 ? d : std::max(high, d);
    }
    v.spread = high - low;
    const double noise = std::max(v.spread, v.mirror_spread);
    v.verdict = repeats < 2             ? kTieNotMeasured
                : v.difference > noise  ? kTieWorse
                : -v.difference > noise ? kTieBetter
                                        : kTieWithinSpread;
    return v;
}

std::string format_verdict_csv(const std::vector<TieVerdict>& verdicts) {
    std::string text = std::string(kVerdictHeader) + "\n";
    for (const TieVerdict& v : verdicts)
        text += fmt::format("{},{},{},{},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{},{}\n", v.n, v.pairs,
                            v.pick, v.other, v.pick_mae, v.other_mae, v.difference, v.spread,
                            v.mirror_spread, v.repeats, v.verdict);
    return text;
}

void validate(const TieOptions& options) {
    (void)read_verdicts(options.verdicts_from);
}

std::string format_tie_csv(const std::vector<int>& taps, const TieOptions& options) {
    const auto verdicts = read_verdicts(options.verdicts_from);
    std::set<int> in_run;
    for (const int n : taps)
        if (spiral::search(n).ties.size() > 1) in_run.insert(n);
    std::set<int> every(in_run);
    for (const auto& [n, fields] : verdicts) every.insert(n);
    std::string text =
        "n,in_run,scaled,denominator,ties,pick,study_pick,best_other,pick_mae,other_mae,"
        "difference,spread,mirror_spread,repeats,verdict\n";
    for (const int n : every) {
        const spiral::SearchResult result = spiral::search(n);
        std::string study = ",,,,,,,,";
        if (auto it = verdicts.find(n); it != verdicts.end()) {
            const std::vector<std::string>& f = it->second;  // pairs, pick, ...
            study = fmt::format("{},{},{},{},{},{},{},{},{}", f[1], f[2], f[3], f[4], f[5], f[6],
                                f[7], f[8], f[9]);
        }
        text += fmt::format("{},{},{},{},{},{},{}\n", n, in_run.contains(n) ? 1 : 0, result.scaled,
                            result.denominator(), fmt::join(result.ties, " "), result.tau, study);
    }
    return text;
}

void write_tie_table(const fs::path& directory, const std::vector<int>& taps,
                     const TieOptions& options) {
    spiral::fileio::AtomicFile file(directory / "ties.csv");
    file.write(format_tie_csv(taps, options));
    file.commit();
}

}  // namespace deepgi::report
