// Exhaustive search over the turns p / m with branch and bound.
//
// Every candidate first gets the O(log n) lower bound of bounds.cpp. The
// candidates are then evaluated in ascending order of that bound (ties by
// numerator), each exact evaluation stopping at the first band that exceeds
// the best K found so far. Because the order is ascending, the first candidate
// whose bound exceeds the best K ends the whole search: every later one is
// strictly worse without being scanned. A candidate is only dropped when it is
// strictly worse than a value already attained, so every tie survives and the
// answer is independent of timing and thread count.
#include <algorithm>
#include <atomic>
#include <limits>
#include <mutex>
#include <numeric>
#include <stdexcept>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "evaluate.hpp"
#include "lattice.hpp"

namespace spiral {
namespace {

// How many bands each worker probes before a full sweep (recent failures
// first), in groups of kProbeGroup per pass (evaluate_bands).
constexpr std::size_t kProbeBands = 32;
constexpr std::size_t kProbeGroup = 8;

int resolve_jobs(int jobs) {
    if (jobs > 0) return jobs;
    return std::max(1u, std::thread::hardware_concurrency());
}

template <class Work>
void run_workers(int jobs, Work&& work) {
    if (jobs <= 1) {
        work();
        return;
    }
    std::vector<std::jthread> workers;
    for (int j = 0; j < jobs; ++j) workers.emplace_back(work);
}

}  // namespace

SearchResult search(int n, const SearchOptions& options) {
    const std::int64_t m = options.denominator;
    detail::require_valid_denominator(n, m);
    const std::int64_t nm = std::int64_t{n} * m;
    if (nm > kMaxSearchCandidates)
        throw std::invalid_argument("n m = " + std::to_string(nm) +
                                    " for n = " + std::to_string(n) + ", m = " + std::to_string(m) +
                                    " exceeds the search limit 2^30 candidates");

    // D(p) = D(nm - p): p <= nm/2 covers [1, nm - 1]; p = nm (tau = n) stands alone.
    struct Candidate {
        std::int64_t lower_bound;
        int p;
    };
    std::vector<Candidate> candidates;
    candidates.reserve(static_cast<std::size_t>(nm / 2 + 1));
    for (std::int64_t p = 1; p <= nm / 2; ++p)
        candidates.push_back({discrepancy_lower_bound(n, p, m), static_cast<int>(p)});
    candidates.push_back({discrepancy_lower_bound(n, nm, m), static_cast<int>(nm)});
    const int jobs = std::min<int>(resolve_jobs(options.jobs), static_cast<int>(candidates.size()));

    // Sharpen every bound with eight bands probed from scratch in one pass
    // (evaluate_bands: about the cost of one scalar probe, as much in all as
    // a few full sweeps). They are the bands that most often exceed the
    // optimum among candidates passing the cluster bound, measured at n = 512
    // and 1000 (80% of the taps first). The sharper order puts a near-optimal
    // candidate first and cuts off most candidates without any further work.
    std::vector<std::int64_t> first_probes;
    for (const int percent : {80, 65, 90, 70, 55, 40, 85, 60})
        if (const std::int64_t taps = percent * std::int64_t{n} / 100;
            taps >= 1 &&
            std::find(first_probes.begin(), first_probes.end(), taps) == first_probes.end())
            first_probes.push_back(taps);
    if (!first_probes.empty()) {
        std::atomic<std::size_t> next_probe{0};
        run_workers(jobs, [&] {
            detail::BandScratch scratch;
            std::int64_t excess[kProbeGroup];
            for (std::size_t k = next_probe++; k < candidates.size(); k = next_probe++) {
                Candidate& c = candidates[k];
                detail::evaluate_bands(n, c.p, m, first_probes.data(),
                                       static_cast<int>(first_probes.size()), scratch, excess);
                c.lower_bound = std::max(c.lower_bound,
                                         *std::max_element(excess, excess + first_probes.size()));
            }
        });
    }
    std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) {
        return a.lower_bound != b.lower_bound ? a.lower_bound < b.lower_bound : a.p < b.p;
    });

    constexpr std::int64_t kUnbounded = std::numeric_limits<std::int64_t>::max();
    std::vector<std::int64_t> excess(candidates.size(), kUnbounded);
    std::vector<char> exact(candidates.size(), 0);
    std::atomic<std::int64_t> best{kUnbounded};
    std::atomic<std::size_t> next{0};

    // Aspiration: search below a ceiling first. Every candidate above the
    // ceiling is rejected as cheaply as one whose bound is above the optimum,
    // so the sweeps of a descending chain of incumbents are avoided. If some
    // candidate has K <= ceiling, the pass is exact: its minimum is the
    // minimum, and every candidate it dropped was strictly above a value
    // attained. Otherwise the ceiling grows by a quarter and the pass repeats;
    // K <= 4 n^2 m always, so a ceiling that large cannot fail. Whether a pass
    // succeeds depends only on the candidates' K, never on timing.
    const std::int64_t largest_k = 4 * std::int64_t{n} * n * m;
    std::int64_t ceiling = candidates.front().lower_bound + candidates.front().lower_bound / 4;
    for (;;) {
        std::fill(excess.begin(), excess.end(), kUnbounded);
        std::fill(exact.begin(), exact.end(), 0);
        best = ceiling >= largest_k ? kUnbounded : ceiling;
        next = 0;
        run_workers(jobs, [&] {
            // Bands that recently exceeded the bound, most recent first: the worst
            // band of one poor candidate tends to be poor for the next, and wide
            // bands (many taps, a large arc) are where candidates that pass the
            // cluster bound usually fail. Each probe is one band from scratch,
            // O(k log k), instead of the O(k^2) incremental sweep up to band k.
            detail::BandScratch scratch;
            std::vector<std::int64_t> probes;
            // Initial order: a grid of 2.5% steps, the 5% steps first, without
            // the eight bands every bound already includes. n and n / 2 taps are
            // nearly uniform and left to the sweep.
            std::vector<int> permille{750, 950, 450, 350, 300, 250, 200, 150, 100};
            for (int p = 975; p >= 50; p -= 50) permille.push_back(p);
            for (const int per : permille)
                if (const std::int64_t taps = per * std::int64_t{n} / 1000;
                    taps >= 1 && probes.size() < kProbeBands &&
                    std::find(first_probes.begin(), first_probes.end(), taps) ==
                        first_probes.end() &&
                    std::find(probes.begin(), probes.end(), taps) == probes.end())
                    probes.push_back(taps);
            auto promote = [&](std::size_t index, std::int64_t taps) {
                if (index == probes.size()) {
                    if (probes.size() < kProbeBands) probes.push_back(taps);
                    index = probes.size() - 1;
                    probes[index] = taps;
                }
                std::rotate(probes.begin(), probes.begin() + static_cast<std::ptrdiff_t>(index),
                            probes.begin() + static_cast<std::ptrdiff_t>(index) + 1);
            };
            for (std::size_t k = next++; k < candidates.size(); k = next++) {
                const std::int64_t bound = best.load(std::memory_order_relaxed);
                // best only decreases, so a bound above it now is above the final
                // minimum, and so is every later (larger) bound.
                if (candidates[k].lower_bound > bound) {
                    next = candidates.size();
                    break;
                }
                // Any one band's excess is a lower bound on K (K is the maximum
                // over all bands), so one probe above the bound rejects exactly.
                bool rejected = false;
                for (std::size_t g = 0; g < probes.size() && !rejected; g += kProbeGroup) {
                    const std::size_t count = std::min(kProbeGroup, probes.size() - g);
                    std::int64_t excess[kProbeGroup];
                    detail::evaluate_bands(n, candidates[k].p, m, probes.data() + g,
                                           static_cast<int>(count), scratch, excess);
                    for (std::size_t b = g; b < g + count; ++b)
                        if (excess[b - g] > bound) {
                            rejected = true;
                            promote(b, probes[b]);
                            break;
                        }
                }
                if (rejected) continue;
                std::int64_t failed_band = 0;
                const std::int64_t value = detail::evaluate(
                    n, candidates[k].p, m, bound, nullptr, &failed_band, candidates[k].lower_bound);
                excess[k] = value;
                if (value > bound) {
                    if (failed_band > 0) promote(probes.size(), failed_band);
                    continue;
                }
                exact[k] = 1;
                std::int64_t seen = best.load(std::memory_order_relaxed);
                while (value < seen && !best.compare_exchange_weak(seen, value)) {
                }
            }
        });
        if (std::find(exact.begin(), exact.end(), 1) != exact.end()) break;
        ceiling += ceiling / 4 + 1;
    }

    SearchResult result{n, 0, {}, best.load(), m};
    for (std::size_t k = 0; k < candidates.size(); ++k) {
        if (!exact[k] || excess[k] != result.scaled) continue;
        const int p = candidates[k].p;
        result.ties.push_back(p);
        if (p < nm && nm - p != p) result.ties.push_back(static_cast<int>(nm - p));
    }
    std::sort(result.ties.begin(), result.ties.end());
    result.ties.erase(std::unique(result.ties.begin(), result.ties.end()), result.ties.end());
    // The second, exact criterion among the minimisers (ties.cpp).
    result.tau = result.ties.size() == 1 ? result.ties.front() : break_tie(n, result.ties, m);
    return result;
}

std::vector<SearchResult> search_range(int min_n, int max_n, const SearchOptions& options,
                                       const std::function<void(int, int)>& progress) {
    if (min_n < 1 || max_n > kMaxTaps || min_n > max_n)
        throw std::invalid_argument("tap range [" + std::to_string(min_n) + ", " +
                                    std::to_string(max_n) + "] is not within [1, " +
                                    std::to_string(kMaxTaps) + "]");
    // Checked once up front (the largest n is the binding one), so a bad
    // denominator fails before any work and not inside a worker thread.
    detail::require_valid_denominator(max_n, options.denominator);
    if (std::int64_t{max_n} * options.denominator > kMaxSearchCandidates)
        throw std::invalid_argument(
            "n m = " + std::to_string(std::int64_t{max_n} * options.denominator) +
            " exceeds the search limit 2^30 candidates");
    const int total = max_n - min_n + 1;
    std::vector<SearchResult> results(static_cast<std::size_t>(total));
    // Largest n first: the costly searches start early and small ones fill the gaps.
    std::atomic<int> next{0};
    std::mutex progress_mutex;
    int done = 0;
    run_workers(std::min(resolve_jobs(options.jobs), total), [&] {
        for (int k = next++; k < total; k = next++) {
            const int n = max_n - k;
            results[static_cast<std::size_t>(n - min_n)] =
                search(n, SearchOptions{1, options.denominator});
            if (progress) {
                std::lock_guard lock(progress_mutex);
                progress(++done, total);
            }
        }
    });
    return results;
}

}  // namespace spiral
