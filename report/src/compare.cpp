// The report's comparisons: error statistics of an estimate against its
// truth over a mask of pixels, the irradiance truths, and the open-surface
// counts.
#include "compare.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace deepgi::report {

namespace {

// The open-surface target (docs/deep-sao.md): pixels with nothing within r
// in the truth (AV >= 0.9999) must keep an estimate of at least 0.99.
bool is_open(const FloatImage& truth, std::size_t i) {
    return truth.pixels[i * std::size_t(truth.channels)] >= 0.9999f;
}

}  // namespace

FloatImage clamped_visibility(FloatImage image) {
    for (float& v : image.pixels) v = std::clamp(v, 0.0f, 1.0f);
    return image;
}

std::optional<FloatImage> reference_irradiance(const ReferenceImages& images) {
    if (images.irradiance.pixels.empty()) return std::nullopt;
    return images.irradiance;
}

std::optional<FloatImage> visible_irradiance(const ReferenceImages& images, int layers) {
    if (images.irradiance_layer0.pixels.empty()) return std::nullopt;
    FloatImage visible = images.irradiance_layer0;
    if (layers > 1) {
        for (std::size_t i = 0; i < visible.pixels.size(); ++i)
            visible.pixels[i] += images.irradiance_layer1.pixels[i];
    }
    return visible;
}

double masked_mean(const FloatImage& image, const std::vector<std::uint8_t>& mask) {
    const ErrorStats stats =
        compare_images(image,
                       FloatImage{image.width, image.height, image.channels,
                                  std::vector<float>(image.pixels.size(), 0.0f)},
                       mask);
    return stats.bias;
}

ErrorStats relative(ErrorStats stats, double scale) {
    if (!(scale > 0.0)) scale = std::numeric_limits<double>::quiet_NaN();
    stats.mae /= scale;
    stats.rmse /= scale;
    stats.bias /= scale;
    return stats;
}

FloatImage crop(const FloatImage& image, int guard, const std::vector<std::uint8_t>& mask) {
    FloatImage out;
    out.width = image.width - 2 * guard;
    out.height = image.height - 2 * guard;
    out.channels = 1;
    out.pixels.resize(std::size_t(out.width) * std::size_t(out.height));
    for (int y = 0; y < out.height; ++y) {
        for (int x = 0; x < out.width; ++x) {
            const std::size_t source =
                std::size_t(y + guard) * std::size_t(image.width) + std::size_t(x + guard);
            out.pixels[std::size_t(y) * std::size_t(out.width) + std::size_t(x)] =
                mask[source] ? image.pixels[source * std::size_t(image.channels)]
                             : std::numeric_limits<float>::quiet_NaN();
        }
    }
    return out;
}

std::vector<std::uint8_t> open_region(const FloatImage& truth, int reach) {
    const int w = truth.width, h = truth.height;
    std::vector<std::uint8_t> region(std::size_t(w) * std::size_t(h), 0);
    for (int y = 0; y < h; ++y) {
        for (int x = 0; x < w; ++x) {
            bool open = true;
            for (int v = std::max(0, y - reach); open && v <= std::min(h - 1, y + reach); ++v) {
                for (int u = std::max(0, x - reach); open && u <= std::min(w - 1, x + reach); ++u)
                    open = is_open(truth, std::size_t(v) * std::size_t(w) + std::size_t(u));
            }
            region[std::size_t(y) * std::size_t(w) + std::size_t(x)] = open ? 1 : 0;
        }
    }
    return region;
}

OpenCount count_open(const FloatImage& estimate, const std::vector<std::uint8_t>& mask,
                     const std::vector<std::uint8_t>& region) {
    OpenCount count;
    for (std::size_t i = 0; i < mask.size(); ++i) {
        if (!mask[i] || !region[i]) continue;
        ++count.pixels;
        count.below += estimate.pixels[i * std::size_t(estimate.channels)] < 0.99f;
    }
    return count;
}

ErrorStats compare_images(const FloatImage& estimate, const FloatImage& truth,
                          const std::vector<std::uint8_t>& mask) {
    if (estimate.width != truth.width || estimate.height != truth.height)
        throw std::invalid_argument(fmt::format("images differ in size: {}x{} and {}x{}",
                                                estimate.width, estimate.height, truth.width,
                                                truth.height));
    const std::size_t count = std::size_t(truth.width) * std::size_t(truth.height);
    if (mask.size() != count)
        throw std::invalid_argument(
            fmt::format("mask has {} values for {} pixels", mask.size(), count));
    const int estimate_channels = std::min(estimate.channels, 3);
    const int truth_channels = std::min(truth.channels, 3);
    auto value = [](const FloatImage& image, int channels, std::size_t i) {
        double sum = 0.0;
        for (int c = 0; c < channels; ++c) sum += image.pixels[i * std::size_t(image.channels) + c];
        return sum / channels;
    };
    ErrorStats stats;
    double sum_abs = 0.0, sum_squares = 0.0, sum = 0.0;
    for (std::size_t i = 0; i < count; ++i) {
        if (!mask[i]) continue;
        const double error =
            value(estimate, estimate_channels, i) - value(truth, truth_channels, i);
        sum_abs += std::abs(error);
        sum_squares += error * error;
        sum += error;
        ++stats.pixels;
    }
    if (stats.pixels == 0) {
        stats.mae = stats.rmse = stats.bias = std::numeric_limits<double>::quiet_NaN();
        return stats;
    }
    const double n = double(stats.pixels);
    stats.mae = sum_abs / n;
    stats.rmse = std::sqrt(sum_squares / n);
    stats.bias = sum / n;
    return stats;
}

}  // namespace deepgi::report
