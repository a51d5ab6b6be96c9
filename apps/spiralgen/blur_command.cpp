// spiralgen blur: the GLSL header holding the bilateral blur's Gaussian weights.
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <string>

#include <fmt/core.h>

#include "commands.hpp"
#include "spiral/codegen.hpp"

namespace spiralgen {
namespace {

struct BlurArgs {
    int radius = -1;
    std::optional<double> sigma;
    std::string out;
};

void run_blur(const BlurArgs& args) {
    namespace codegen = spiral::codegen;
    if (args.radius < 0 || args.radius > spiral::codegen::kMaxBlurRadius)
        throw UsageError(fmt::format("--radius {} is outside [0, {}]", args.radius,
                                     spiral::codegen::kMaxBlurRadius));
    // BLUR_SIGMA is a GLSL float: outside the normal float range it would
    // be written as inf.0 or 0.0, and the header would not compile (or mean 0).
    if (args.sigma && !codegen::valid_blur_sigma(*args.sigma))
        throw UsageError(fmt::format("--sigma {} is not between {} and {} (a normal float)",
                                     *args.sigma, std::numeric_limits<float>::min(),
                                     std::numeric_limits<float>::max()));
    const codegen::BlurKernel kernel = codegen::gaussian_kernel(args.radius, args.sigma);
    // Recorded canonically and without --out, like every generated file.
    std::string command = fmt::format("spiralgen blur --radius {}", args.radius);
    if (args.sigma) command += fmt::format(" --sigma {}", *args.sigma);

    const std::string text = codegen::format_blur_header(kernel, codegen::Provenance{command});
    if (args.out.empty())
        codegen::write_stdout(text);
    else
        codegen::write_file_atomically(args.out, text);
}

}  // namespace

void add_blur_command(CLI::App& app) {
    auto args = std::make_shared<BlurArgs>();
    CLI::App* command = app.add_subcommand(
        "blur", "Write the GLSL header with the normalised Gaussian weights of the blur");
    command->add_option("--radius", args->radius, "Kernel radius in pixels (taps -R..R), 0 to 1024")
        ->required();
    command->add_option("--sigma", args->sigma, "Standard deviation of the Gaussian, in pixels")
        ->default_str("radius / 2 pixels");
    command
        ->add_option("--out", args->out,
                     "Write to this file (atomically) instead of standard output ('-')")
        ->check(non_empty_path)
        ->default_str("standard output");
    command->callback([args] { run_blur(*args); });
}

}  // namespace spiralgen
