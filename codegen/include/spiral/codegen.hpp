// Turns the optimizer's results into text: the tau table in five formats, the
// GLSL headers the gathering and blur passes #include (docs/design.md, section 4),
// and an atomic file writer so no consumer ever sees half a file.
//
// Every formatter is a pure function of its arguments: the same arguments give
// the same bytes, on every machine and thread count. Files that carry comments
// (cpp, glsl, the headers) open with a comment saying they are generated and by
// which command, taken from Provenance.
#pragma once

#include <spiral/optimizer.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace spiral::codegen {

// The command that produced a file, as it should be quoted in the file's
// opening comment (e.g. "spiralgen header --pass ao --taps 11"). Leave out
// output paths: where a file is written does not change what it says, and
// keeping them out keeps the bytes independent of the build directory.
// Characters outside printable ASCII are written as '?'.
struct Provenance {
    std::string command;
};

// Quotes one argument for a POSIX shell, only when it needs quoting:
// "ao" -> ao, "deep radiosity" -> 'deep radiosity', "it's" -> 'it'\''s'.
std::string shell_quote(std::string_view argument);

// ---------------------------------------------------------------------------
// The tau table

enum class TableFormat { cpp, glsl, json, csv, md };

// "cpp", "glsl", "json", "csv", "md" (exact, lower case); nullopt otherwise.
std::optional<TableFormat> parse_table_format(std::string_view name);
std::string_view to_string(TableFormat format);

// Formats search results, which must be non-empty with n strictly ascending
// (gaps allowed); throws std::invalid_argument otherwise.
//   cpp  : a header with `inline constexpr std::array<int, max_n + 1>
//          spiral::generated::kSpiralTurns` indexed by n. Entry 0 and every n
//          not in `results` (below min_n, or a gap) hold 0, which is never a
//          valid tau, so a lookup can tell "not tabulated" from a value.
//   glsl : the same as `const int SPIRAL_TURNS[SPIRAL_TURNS_MAX_TAPS + 1]`.
//   json : [{"n":..,"tau":..,"ties":[..],"discrepancy":{"num":K,"den":4n^2,
//          "value":K/4n^2}}, ...], one object a line, doubles printed as the
//          shortest text that reads back to the same double.
//   csv  : header row `n,tau,ties,num,den,value`; ties separated by spaces.
//   md   : a Markdown table with columns n, tau, ties, K/4n^2 and its value.
// Only cpp and glsl carry the provenance comment: json and csv have no
// comment syntax, and md is meant to be read as it is.
std::string format_table(const std::vector<SearchResult>& results, TableFormat format,
                         const Provenance& provenance);

// ---------------------------------------------------------------------------
// Gather header (one per gathering pass)

// The macro prefix for a pass name: letters and digits upper-cased, every run
// of other characters one '_', leading and trailing '_' dropped
// ("ao" -> "AO", "deep radiosity" -> "DEEP_RADIOSITY"). Throws
// std::invalid_argument, with a message naming the problem, when the name is
// empty, longer than 64 characters, has characters outside printable ASCII,
// leaves no letter or digit, starts with a digit, or yields a prefix GLSL
// reserves (GL_...).
std::string macro_prefix(std::string_view pass_name);

// One tap of the unrotated pattern: tap i of n sits at radius alpha_i =
// (i + 1/2) / n and angle 2*pi*tau*alpha_i. Computed in double and rounded to
// float, which is what a shader stores.
struct Tap {
    float alpha = 0;
    float x = 0;  // alpha * cos(2 pi tau alpha)
    float y = 0;  // alpha * sin(2 pi tau alpha)
};

// The n taps for (n, tau); requires n >= 1, tau >= 1 (throws
// std::invalid_argument otherwise). The angle is reduced exactly before any
// floating point is involved (tap i is at ((2i+1) * tau mod 2n) / (2n) turns),
// so a large tau loses nothing and quarter turns give exact 0 and +-1.
// With a denominator m the spiral makes tau / m turns (tau is the numerator).
std::vector<Tap> spiral_taps(int n, std::int64_t tau, std::int64_t denominator = 1);

// What a gather header states. `chosen` is the pattern written out; `optimum`
// is what search(n) gives. When chosen.tau is not among optimum.ties the
// header says so, with both exact discrepancies and the difference.
struct GatherSpec {
    std::string pass;  // free text; see macro_prefix
    SearchResult optimum;
    Discrepancy chosen;  // chosen.n must equal optimum.n
};

// The GLSL header text. Symbols, with P = macro_prefix(pass):
//   #define P_NUM_TAPS n
//   #define P_NUM_SPIRAL_TURNS tau           (a float literal p/m when m > 1,
//   #define P_SPIRAL_TURNS_NUMERATOR p        with these two lines added)
//   #define P_SPIRAL_TURNS_DENOMINATOR m
//   const vec2  P_TAP_OFFSETS[P_NUM_TAPS]  unit offsets alpha_i * (cos, sin)
//   const float P_TAP_ALPHAS[P_NUM_TAPS]   alpha_i (radius fraction, for the MIP)
// inside an include guard SPIRAL_P_TAPS_GLSL. Throws std::invalid_argument on
// an invalid pass name or inconsistent spec.
std::string format_gather_header(const GatherSpec& spec, const Provenance& provenance);

// Runs the optimizer for exactly this n (and D(n, tau) when tau is given) and
// formats the header. tau, when given, may be any value >= 1: tau and
// tau + 2n give the same pattern, tau + n the same one turned by half a turn
// (so the same discrepancy), and the header states the tau as given. With a
// denominator m the search is over tau = p / m and `tau` is the numerator p.
std::string make_gather_header(std::string_view pass, int taps, std::optional<int> tau,
                               const Provenance& provenance, std::int64_t denominator = 1);

// ---------------------------------------------------------------------------
// Blur header

// The sigma used when none is given: radius / 2, so the kernel's ends
// (|k| = radius, two standard deviations out) weigh about e^-2 = 0.135 of the
// centre; the kernel is cut there rather than fading to nothing.
double default_blur_sigma(int radius);

// Widest blur kernel; a wider blur belongs in a different algorithm.
inline constexpr int kMaxBlurRadius = 1024;

// Most taps a gather header is generated for: every header records the exact
// optimum, whose search grows faster than n^2, so it stops where that is quick.
inline constexpr int kMaxGatherTaps = 4096;

// Normalised Gaussian weights for taps k = -radius..radius, stored at
// weights[k + radius]; symmetric, rounded to float, summing to 1 within float
// rounding. radius 0 is the identity kernel {1} whatever sigma is. Requires
// 0 <= radius <= kMaxBlurRadius and sigma > 0 and finite (when given); throws
// std::invalid_argument naming the problem otherwise.
struct BlurKernel {
    int radius = 0;
    double sigma = 0;
    std::vector<float> weights;
};
// Whether `sigma` can be the header's BLUR_SIGMA: positive and, rounded to
// float, finite and normal (so the literal is neither inf.0 nor 0.0).
bool valid_blur_sigma(double sigma);

BlurKernel gaussian_kernel(int radius, std::optional<double> sigma = std::nullopt);

// The GLSL header text:
//   #define BLUR_RADIUS R
//   #define BLUR_SIGMA s            (a float literal)
//   const float BLUR_WEIGHTS[2 * BLUR_RADIUS + 1]   tap k at [k + BLUR_RADIUS]
// inside the include guard SPIRAL_BLUR_KERNEL_GLSL.
std::string format_blur_header(const BlurKernel& kernel, const Provenance& provenance);

// ---------------------------------------------------------------------------
// Output

// Writes `contents` to a temporary file in the same directory as `path`,
// flushes it to disk and renames it over `path`, so readers see the old file
// or the new one, never a mix. On failure the temporary is removed, an
// existing `path` is left untouched, and std::runtime_error is thrown with a
// one-line message naming the path and the problem.
void write_file_atomically(const std::filesystem::path& path, std::string_view contents);

// Writes `contents` to standard output and flushes it, throwing
// std::runtime_error ("cannot write to standard output: <reason>") when the
// write or the flush fails, e.g. on a full disk or a closed pipe; stdio's
// buffering would otherwise lose the error and let the program exit 0.
void write_stdout(std::string_view contents);

}  // namespace spiral::codegen
