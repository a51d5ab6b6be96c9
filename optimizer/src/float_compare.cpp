// The exact search against the double-precision one, for every n up to a
// bound (spiral/float_compare.hpp).
#include "spiral/float_compare.hpp"

#include "spiral/optimizer.hpp"

#include <algorithm>
#include <atomic>
#include <stdexcept>
#include <string>
#include <thread>

namespace spiral_float {

std::vector<Choice> compare_float_search(int max_n, int jobs) {
    if (max_n < 1) throw std::invalid_argument("compare_float_search: max_n must be >= 1");
    const std::vector<spiral::SearchResult> exact =
        spiral::search_range(1, max_n, spiral::SearchOptions{jobs, 1});

    if (jobs <= 0) jobs = int(std::max(1u, std::thread::hardware_concurrency()));
    jobs = std::min(jobs, max_n);
    // Larger n cost more; hand them out one at a time, largest first, so the
    // workers finish together.
    std::vector<Pick> picks(std::size_t(max_n) + 1);
    std::atomic<int> next{max_n};
    auto work = [&] {
        for (int n = next--; n >= 1; n = next--) picks[std::size_t(n)] = search(n);
    };
    std::vector<std::thread> helpers;
    for (int i = 1; i < jobs; ++i) helpers.emplace_back(work);
    work();
    for (std::thread& helper : helpers) helper.join();

    std::vector<Choice> choices;
    choices.reserve(std::size_t(max_n));
    for (int n = 1; n <= max_n; ++n) {
        const spiral::SearchResult& e = exact[std::size_t(n - 1)];
        Choice c;
        c.n = n;
        c.exact_tau = e.tau;
        c.exact_k = e.scaled;
        c.float_tau = picks[std::size_t(n)].tau;
        c.float_tau_exact_k = spiral::discrepancy_scaled(n, c.float_tau);
        c.denominator = e.denominator();
        choices.push_back(c);
    }
    return choices;
}

}  // namespace spiral_float
