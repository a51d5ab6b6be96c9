// Exhaustive search over tau with branch and bound.
//
// Candidates with small partial quotients in the continued fraction of tau/n
// spread their taps evenly, so they are evaluated first; the best K found so
// far then lets every later candidate stop at the first band that exceeds it.
// A candidate is only dropped when it is strictly worse than a value already
// attained, so every tie survives and the answer is independent of timing and
// thread count.
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

struct PartialQuotients {
    std::int64_t largest = 0;
    std::int64_t sum = 0;
};

PartialQuotients partial_quotients(std::int64_t tau, std::int64_t n) {
    PartialQuotients q;
    std::int64_t a = n, b = tau;
    while (b != 0) {
        q.largest = std::max(q.largest, a / b);
        q.sum += a / b;
        a = std::exchange(b, a % b);
    }
    return q;
}

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
    if (n < 1 || n > kMaxTaps)
        throw std::invalid_argument("tap count n = " + std::to_string(n) + " is outside [1, " +
                                    std::to_string(kMaxTaps) + "]");

    // D(n, tau) = D(n, n - tau): tau <= n/2 covers [1, n - 1]; tau = n stands alone.
    std::vector<int> candidates;
    for (int tau = 1; tau <= n / 2; ++tau) candidates.push_back(tau);
    candidates.push_back(n);
    std::stable_sort(candidates.begin(), candidates.end(), [n](int a, int b) {
        const PartialQuotients qa = partial_quotients(a % n, n), qb = partial_quotients(b % n, n);
        if (qa.largest != qb.largest) return qa.largest < qb.largest;
        return qa.sum < qb.sum;
    });

    constexpr std::int64_t kUnbounded = std::numeric_limits<std::int64_t>::max();
    std::vector<std::int64_t> excess(candidates.size(), kUnbounded);
    std::vector<char> exact(candidates.size(), 0);
    std::atomic<std::int64_t> best{kUnbounded};
    std::atomic<std::size_t> next{0};

    const int jobs = std::min<int>(resolve_jobs(options.jobs), static_cast<int>(candidates.size()));
    run_workers(jobs, [&] {
        for (std::size_t k = next++; k < candidates.size(); k = next++) {
            const std::int64_t bound = best.load(std::memory_order_relaxed);
            const std::int64_t value = detail::evaluate(n, candidates[k], bound, nullptr);
            excess[k] = value;
            if (value > bound) continue;
            exact[k] = 1;
            std::int64_t seen = best.load(std::memory_order_relaxed);
            while (value < seen && !best.compare_exchange_weak(seen, value)) {
            }
        }
    });

    SearchResult result{n, 0, {}, best.load()};
    for (std::size_t k = 0; k < candidates.size(); ++k) {
        if (!exact[k] || excess[k] != result.scaled) continue;
        const int tau = candidates[k];
        result.ties.push_back(tau);
        if (tau < n && n - tau != tau) result.ties.push_back(n - tau);
    }
    std::sort(result.ties.begin(), result.ties.end());
    result.ties.erase(std::unique(result.ties.begin(), result.ties.end()), result.ties.end());
    result.tau = result.ties.front();
    return result;
}

std::vector<SearchResult> search_range(int min_n, int max_n, const SearchOptions& options,
                                       const std::function<void(int, int)>& progress) {
    if (min_n < 1 || max_n > kMaxTaps || min_n > max_n)
        throw std::invalid_argument("tap range [" + std::to_string(min_n) + ", " +
                                    std::to_string(max_n) + "] is not within [1, " +
                                    std::to_string(kMaxTaps) + "]");
    const int total = max_n - min_n + 1;
    std::vector<SearchResult> results(static_cast<std::size_t>(total));
    // Largest n first: the costly searches start early and small ones fill the gaps.
    std::atomic<int> next{0};
    std::mutex progress_mutex;
    int done = 0;
    run_workers(std::min(resolve_jobs(options.jobs), total), [&] {
        for (int k = next++; k < total; k = next++) {
            const int n = max_n - k;
            results[static_cast<std::size_t>(n - min_n)] = search(n, SearchOptions{1});
            if (progress) {
                std::lock_guard lock(progress_mutex);
                progress(++done, total);
            }
        }
    });
    return results;
}

}  // namespace spiral
