// Accuracy targets kept apart from regression bounds.
//
// A target is a value the design asks for (docs/ao-accuracy.md,
// docs/radiosity.md). Where the code meets it, it is a hard check at the
// target's own value. Where the code is known to miss it, the test names a
// regression bound taken from a measured value (so a change that makes the
// miss worse still fails) and the miss is listed in a table file. A ctest
// entry of its own (tests/runtime/print_targets.sh) prints that table, target
// beside measured, and reports itself skipped while any target is missed, so
// every ctest summary names the misses.
#pragma once

#include <catch2/catch.hpp>
#include <fmt/format.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <string>
#include <vector>

namespace spiral::test {

// A known miss: the regression bound (taken from a measured value, about 10%
// above it) and where that value was measured.
struct KnownMiss {
    double regression_bound = 0.0;
    std::string measured_as;
};

class TargetTable {
public:
    // `file` is written in the test's working directory; `misses` are keyed
    // "<case>/<quantity>/<stage>".
    TargetTable(std::string file, std::map<std::string, KnownMiss> misses)
        : file_(std::move(file)), misses_(std::move(misses)) {
        // No table from an earlier run survives this one.
        std::remove(file_.c_str());
    }

    // The target `value <= target` for one case, quantity and stage.
    void check_at_most(const std::string& name, const std::string& quantity,
                       const std::string& stage, double value, double target) {
        const std::string key = name + "/" + quantity + "/" + stage;
        INFO(key << ": measured " << value << ", target <= " << target);
        const auto miss = misses_.find(key);
        if (miss == misses_.end()) {
            // Met so far: a hard check at the target's value.
            CHECK(value <= target);
            rows_.push_back(
                row(name, quantity, stage, target, value, value <= target ? "met" : "FAILED", "-"));
            return;
        }
        // Known to be missed: the regression bound stays hard, the miss is listed.
        INFO("regression bound " << miss->second.regression_bound << " ("
                                 << miss->second.measured_as << ")");
        CHECK(value <= miss->second.regression_bound);
        rows_.push_back(row(name, quantity, stage, target, value,
                            value <= target ? "met (stale miss: make it a hard check)" : "missed",
                            fmt::format("{:.4g}", miss->second.regression_bound)));
    }

    // Rewrites the file with every row so far, so that what a run leaves is
    // that run's; a run that stops early leaves the rows it reached.
    void write() const {
        std::ofstream out(file_, std::ios::trunc);
        out << "| case | quantity | stage | target | measured | status | regression bound |\n"
            << "|---|---|---|--:|--:|---|--:|\n";
        for (const std::string& r : rows_) out << r << "\n";
    }

private:
    static std::string row(const std::string& name, const std::string& quantity,
                           const std::string& stage, double target, double value,
                           const std::string& status, const std::string& bound) {
        return fmt::format("| {} | {} | {} | <= {:.4g} | {:.4g} | {} | {} |", name, quantity, stage,
                           target, value, status, bound);
    }

    std::string file_;
    std::map<std::string, KnownMiss> misses_;
    std::vector<std::string> rows_;
};

}  // namespace spiral::test
