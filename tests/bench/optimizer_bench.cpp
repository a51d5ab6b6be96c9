// Speed of the optimizer: the tau table at growing ranges (integer turns and
// tau = p/8), the fast evaluator against the brute-force oracle, and peak
// memory. Prints Markdown for docs/performance.md. Timings are medians of repeated runs
// in this one process; the tables run on 2 threads, like `spiralgen table
// --jobs 2` on the 2-core build machine.
//
//   optimizer_bench [--quick] [--full]   (--full adds the table 1..4096 once)
//   optimizer_bench --targets [--reps R] [--reps-4096 S]
//       the three speed targets only: tables 1..1024 and 1..256 with m = 8,
//       R times each (default 5), and 1..4096, S times (default 1; 0 skips
//       it), with medians and peak memory
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include <fmt/core.h>

#include "spiral/optimizer.hpp"

namespace {

struct Sample {
    double wall = 0;
    double cpu = 0;
};

double process_cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + double(t.tv_nsec) * 1e-9;
}

Sample measure_once(const std::function<void()>& work) {
    const double cpu0 = process_cpu_seconds();
    const auto wall0 = std::chrono::steady_clock::now();
    work();
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    return {wall, process_cpu_seconds() - cpu0};
}

Sample median(const std::function<void()>& work, int repetitions) {
    std::vector<Sample> samples;
    for (int r = 0; r < repetitions; ++r) samples.push_back(measure_once(work));
    auto mid = [&](auto field) {
        std::vector<double> v;
        for (const auto& s : samples) v.push_back(s.*field);
        std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
        return v[v.size() / 2];
    };
    return {mid(&Sample::wall), mid(&Sample::cpu)};
}

long peak_rss_kib() {
    rusage usage{};
    getrusage(RUSAGE_SELF, &usage);
    return usage.ru_maxrss;
}

// The three speed targets, as `spiralgen table ... --jobs 2` runs them. Peak
// resident memory is that of this process so far (it only grows), so the
// last row's figure covers all three.
int run_targets(int repetitions, int big_repetitions) {
    struct Target {
        int max_n;
        std::int64_t m;
        double limit_s;
    };
    fmt::print(
        "| command | runs | median wall (s) | median CPU (s) | target wall (s) | peak RSS so far "
        "(MiB) |\n|:--|--:|--:|--:|--:|--:|\n");
    for (const Target t : {Target{1024, 1, 3}, Target{256, 8, 60}, Target{4096, 1, 120}}) {
        const int runs = t.max_n == 4096 ? big_repetitions : repetitions;
        if (runs == 0) continue;
        const Sample s = median(
            [&] {
                spiral::search_range(1, t.max_n, spiral::SearchOptions{2, t.m});
            },
            runs);
        const std::string command =
            fmt::format("table --max-n {}{} --jobs 2", t.max_n,
                        t.m > 1 ? fmt::format(" --denominator {}", t.m) : std::string());
        fmt::print("| `{}` | {} | {:.2f} | {:.2f} | {:.0f} | {:.1f} |\n", command, runs, s.wall,
                   s.cpu, t.limit_s, double(peak_rss_kib()) / 1024.0);
        std::fflush(stdout);
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    bool quick = false, full = false, targets = false;
    int repetitions = 5, big_repetitions = 1;
    for (int a = 1; a < argc; ++a) {
        quick = quick || std::strcmp(argv[a], "--quick") == 0;
        full = full || std::strcmp(argv[a], "--full") == 0;
        targets = targets || std::strcmp(argv[a], "--targets") == 0;
        if (std::strcmp(argv[a], "--reps") == 0 && a + 1 < argc)
            repetitions = std::max(1, std::atoi(argv[++a]));
        if (std::strcmp(argv[a], "--reps-4096") == 0 && a + 1 < argc)
            big_repetitions = std::max(0, std::atoi(argv[++a]));
    }
    if (targets) return run_targets(repetitions, big_repetitions);
    const unsigned threads = std::max(1u, std::thread::hardware_concurrency());
    fmt::print("hardware threads: {}\n\n", threads);

    fmt::print(
        "| table range | m | jobs | repetitions | median wall (s) | median CPU (s) |\n"
        "|:--|--:|--:|--:|--:|--:|\n");
    struct Row {
        int max_n;
        std::int64_t m;
        int reps;
    };
    std::vector<Row> rows{
        {99, 1, 15}, {256, 1, 7}, {1024, 1, quick ? 1 : 5}, {256, 8, quick ? 1 : 3}};
    if (full) rows.push_back({4096, 1, 1});
    for (const Row& row : rows) {
        const Sample s = median(
            [&] {
                spiral::search_range(1, row.max_n, spiral::SearchOptions{2, row.m});
            },
            row.reps);
        fmt::print("| 1..{} | {} | 2 | {} | {:.3f} | {:.3f} |\n", row.max_n, row.m, row.reps,
                   s.wall, s.cpu);
    }

    fmt::print(
        "\n| n | brute force, one tau (ms) | fast, one tau (ms) | ratio |\n|--:|--:|--:|--:|\n");
    for (int n : {16, 32, 64, 99}) {
        const int tau = spiral::search(n).tau;
        const int reps = n >= 64 ? 3 : 9;
        const Sample brute = median([&] { spiral::discrepancy_brute_force(n, tau); }, reps);
        const Sample fast = median(
            [&] {
                for (int k = 0; k < 100; ++k) spiral::discrepancy(n, tau);
            },
            reps);
        const double fast_ms = fast.wall * 1e3 / 100;
        fmt::print("| {} | {:.2f} | {:.4f} | {:.0f} |\n", n, brute.wall * 1e3, fast_ms,
                   brute.wall * 1e3 / fast_ms);
    }

    // The whole exhaustive table by brute force, as the oracle would compute it.
    const int brute_max = quick ? 24 : 40;
    const Sample brute_table = measure_once([&] {
        for (int n = 1; n <= brute_max; ++n)
            for (int tau = 1; tau <= n; ++tau) spiral::discrepancy_brute_force(n, tau);
    });
    const Sample fast_table =
        median([&] { spiral::search_range(1, brute_max, spiral::SearchOptions{1}); }, 9);
    fmt::print(
        "\ntable 1..{} on one thread: brute force {:.2f} CPU s, search {:.4f} CPU s ({:.0f}x)\n",
        brute_max, brute_table.cpu, fast_table.cpu, brute_table.cpu / fast_table.cpu);

    const Sample big = measure_once([] { spiral::search(4096); });
    fmt::print(
        "search(4096): {:.2f} s wall, {:.2f} s CPU; peak resident memory of this process: {:.1f} "
        "MiB\n",
        big.wall, big.cpu, double(peak_rss_kib()) / 1024.0);
    return 0;
}
