#include "deepgi/frame_limits.hpp"

#include "deepgi/errors.hpp"

#include <fmt/format.h>

namespace deepgi {

std::uint64_t estimate_frame_bytes(const RenderSettings& settings) {
    const FrameLayout layout = frame_layout(settings);
    const std::uint64_t internal =
        std::uint64_t(layout.internal_width) * std::uint64_t(layout.internal_height);
    const std::uint64_t viewport = std::uint64_t(settings.width) * std::uint64_t(settings.height);
    const std::uint64_t shadow =
        std::uint64_t(settings.shadow_map_size) * std::uint64_t(settings.shadow_map_size);
    // Bytes per internal pixel: G-buffer (two layers each of normal RG16F,
    // albedo RGBA8, emissive R11G11B10F, motion RG16F, depth 32F) 40, its
    // reference depth 4, direct light (two layers of RGBA16F) 16, compose 4, depth
    // pyramid RG32F with its MIP chain 11 (RGBA32F, 22, for the thick spiral),
    // SAO R16F 2, blur (two R16F) 4.
    // Delay and predict add a third layer to every G-buffer attachment: the
    // prediction's depth (4), and normal, albedo, emissive and motion (4 + 4 +
    // 4 + 8) that layered rendering needs but nothing writes.
    const std::uint64_t prediction_layer =
        generator_predicts_next_frame(settings.generator) ? 4 + 4 + 4 + 4 + 8 : 0;
    const std::uint64_t pyramid = settings.ao.method == AoMethod::spiral_thick ? 22 : 11;
    const std::uint64_t per_internal_pixel = 40 + 4 + 16 + 4 + pyramid + 2 + 4 + prediction_layer;
    // Tonemap RGBA8 and its read-back copy.
    const std::uint64_t per_viewport_pixel = 4 + 4;
    return per_internal_pixel * internal + per_viewport_pixel * viewport + 4 * shadow;
}

void check_frame_limits(const RenderSettings& settings, std::uint64_t max_bytes) {
    const FrameLayout layout = frame_layout(settings);
    if (layout.internal_width > limits::max_internal_side ||
        layout.internal_height > limits::max_internal_side) {
        throw InputError(fmt::format(
            "--size {}x{} with --guard-band {} needs internal buffers of {}x{}, above the GL "
            "limit of {} per side (use a smaller size or guard band)",
            settings.width, settings.height, settings.guard_band_fraction, layout.internal_width,
            layout.internal_height, limits::max_internal_side));
    }
    const std::uint64_t bytes = estimate_frame_bytes(settings);
    if (bytes > max_bytes) {
        constexpr std::uint64_t mib = 1 << 20;
        throw InputError(fmt::format(
            "--size {}x{} with --guard-band {} needs about {} MiB of render targets, above "
            "--max-gpu-memory {} MiB",
            settings.width, settings.height, settings.guard_band_fraction, (bytes + mib - 1) / mib,
            max_bytes / mib));
    }
}

}  // namespace deepgi
