// The blur header: a normalised, symmetric Gaussian kernel.
#include "text.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace spiral::codegen {

double default_blur_sigma(int radius) {
    return radius > 0 ? radius / 2.0 : 0.5;
}

bool valid_blur_sigma(double sigma) {
    // Rounded to float, it must stay finite and normal (not 0, not denormal).
    if (!(sigma > 0) || !(sigma <= double(std::numeric_limits<float>::max()))) return false;
    return std::isnormal(static_cast<float>(sigma));
}

BlurKernel gaussian_kernel(int radius, std::optional<double> sigma) {
    if (radius < 0 || radius > kMaxBlurRadius)
        throw std::invalid_argument(
            fmt::format("blur radius must be in [0, {}], got {}", kMaxBlurRadius, radius));
    if (sigma && !valid_blur_sigma(*sigma))
        throw std::invalid_argument(
            fmt::format("blur sigma must be a normal float > 0, got {}", *sigma));
    BlurKernel kernel;
    kernel.radius = radius;
    kernel.sigma = sigma.value_or(default_blur_sigma(radius));
    // Weights by |k| so the kernel is symmetric bit for bit; normalised in
    // double, so the only error left is the final rounding to float.
    std::vector<double> exact(static_cast<std::size_t>(2 * radius + 1));
    double sum = 0;
    for (int k = -radius; k <= radius; ++k) {
        const double distance = std::abs(k) / kernel.sigma;
        const double weight = std::exp(-0.5 * distance * distance);
        exact[static_cast<std::size_t>(k + radius)] = weight;
        sum += weight;
    }
    kernel.weights.reserve(exact.size());
    for (double weight : exact) kernel.weights.push_back(static_cast<float>(weight / sum));
    return kernel;
}

std::string format_blur_header(const BlurKernel& kernel, const Provenance& provenance) {
    const int radius = kernel.radius;
    if (radius < 0 || kernel.weights.size() != static_cast<std::size_t>(2 * radius + 1))
        throw std::invalid_argument(fmt::format("blur header: radius {} needs {} weights, got {}",
                                                radius, 2 * radius + 1, kernel.weights.size()));
    std::string out = detail::banner(
        provenance, "Gaussian blur kernel",
        fmt::format("radius {}, sigma {}", radius, detail::double_text(kernel.sigma)));
    out +=
        "//\n"
        "// BLUR_WEIGHTS[k + BLUR_RADIUS] weighs the tap k pixels from the centre,\n"
        "// k = -BLUR_RADIUS..BLUR_RADIUS: exp(-k^2 / (2 sigma^2)) normalised to sum 1 in\n"
        "// double, then rounded to float (so the sum is 1 within float rounding).\n"
        "// Radius 0 is the identity kernel. A bilateral blur multiplies each weight by\n"
        "// its depth/normal agreement and renormalises.\n"
        "#ifndef SPIRAL_BLUR_KERNEL_GLSL\n"
        "#define SPIRAL_BLUR_KERNEL_GLSL\n"
        "\n";
    out += fmt::format(
        "#define BLUR_RADIUS {}\n"
        "#define BLUR_SIGMA {}\n"
        "\n"
        "const float BLUR_WEIGHTS[2 * BLUR_RADIUS + 1] = float[](\n",
        radius, detail::float_literal(static_cast<float>(kernel.sigma)));
    for (int k = -radius; k <= radius; ++k)
        out +=
            fmt::format("    {}{}  // k = {}\n",
                        detail::float_literal(kernel.weights[static_cast<std::size_t>(k + radius)]),
                        k < radius ? "," : "", k);
    out += ");\n\n#endif  // SPIRAL_BLUR_KERNEL_GLSL\n";
    return out;
}

}  // namespace spiral::codegen
