#pragma once
// The report's tie table (docs/report.md, "Ties"): for each tap count of the
// run whose D(n, tau) has several exact minimisers, every minimiser and the
// one the tie-break picks (docs/design.md, "Ties"), computed by the exact
// search; and, when --ties-from names the verdicts a tie_error_study run
// wrote, whether the pick samples worse than the best other tie beyond that
// run's spread, for those tap counts and every other n the study measured.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace deepgi::report {

// One tap count of the tie study: every tied tau's sampling error (MAE) in
// each repeat. In one repeat every tau saw the same rotations, so two tau
// are compared repeat by repeat.
struct TieErrors {
    int n = 0;
    int pick = 0;                            // the tie-break's tau, a key of mae
    std::map<int, std::vector<double>> mae;  // tau -> MAE per repeat, equal lengths
};

// The pick's mirror pair against the best other pair. Tau and n - tau are
// the same spiral reflected: no rule of evenness separates them, and which
// of the two samples better depends on how the per-pixel rotations meet the
// reflection, so a pair is judged by the mean of its members.
struct TieVerdict {
    int n = 0;
    int pairs = 0;  // mirror pairs (tau, n - tau) among the ties
    int pick = 0;
    int other = 0;            // the best other pair's smaller tau; 0 with one pair
    double pick_mae = 0.0;    // the pick's pair, mean over its members and the repeats
    double other_mae = 0.0;   // the best other pair's (lowest of the other pairs)
    double difference = 0.0;  // pick - other, mean of the per-repeat differences
    double spread = 0.0;      // range of the per-repeat differences
    // The larger |mae(tau) - mae(n - tau)| of the two pairs (means over the
    // repeats): a difference no tie-break can cause, since none chooses
    // between reflections. It was the only measure of a pattern's meeting
    // with the per-pixel rotations while the study's repeats kept one field;
    // with re-seeded repeats it still decides verdicts at three repeats
    // (docs/optimizer.md, "Ties").
    double mirror_spread = 0.0;
    int repeats = 0;
    // The report's rule (docs/report.md, "Noise"): a difference no larger
    // than its noise, the larger of spread and mirror_spread, names no
    // winner; one repeat decides nothing; one pair leaves nothing to choose.
    std::string verdict;
};

inline constexpr const char* kTieWithinSpread = "pick not worse (within spread)";
inline constexpr const char* kTieWorse = "pick worse beyond spread";
inline constexpr const char* kTieBetter = "pick better beyond spread";
inline constexpr const char* kTieNotMeasured = "noise not measured";
inline constexpr const char* kTieOnePair = "one mirror pair (nothing to choose)";

// Throws std::invalid_argument for fewer than two tau, a pick not among
// them, or repeats of unequal or zero count.
TieVerdict judge_ties(const TieErrors& errors);

// The verdicts file tie_error_study --verdicts-csv writes and --ties-from reads.
std::string format_verdict_csv(const std::vector<TieVerdict>& verdicts);

struct TieOptions {
    // tie_error_study --verdicts-csv output; empty: the exact columns only.
    std::filesystem::path verdicts_from;
};

// Throws InputError when verdicts_from is given but cannot be read or is not
// a verdicts file.
void validate(const TieOptions& options);

// ties.csv: one row per n of `taps` with several minimisers and per n of the
// verdicts file (in_run tells which), ascending; the verdict columns are
// empty where the file has no row for n. study_pick is the pick the study
// judged; where it is not this build's pick the verdict is of another rule.
std::string format_tie_csv(const std::vector<int>& taps, const TieOptions& options);

// Writes ties.csv into `directory`.
void write_tie_table(const std::filesystem::path& directory, const std::vector<int>& taps,
                     const TieOptions& options);

}  // namespace deepgi::report
