// --size near the limits: the guard band is part of the internal size, and the
// render targets' memory is estimated before any GL object is made.
#include "../support/process.hpp"
#include "deepgi/errors.hpp"
#include "deepgi/frame_limits.hpp"

#include <catch2/catch.hpp>
#include <fmt/format.h>

using spiral::test::run_command;

namespace {

deepgi::RenderSettings sized(int width, int height, float guard_band) {
    deepgi::RenderSettings settings;
    settings.width = width;
    settings.height = height;
    settings.guard_band_fraction = guard_band;
    return settings;
}

}  // namespace

TEST_CASE("frame limits: the guard band counts towards the 16384 internal limit",
          "[runtime][limits]") {
    const std::uint64_t plenty = std::uint64_t(1) << 40;
    // 16384 + 2 * round(0.1 * 720) = 16528 wide; 13655 + 2 * 1366 = 16387 high.
    REQUIRE_THROWS_AS(deepgi::check_frame_limits(sized(16384, 720, 0.1f), plenty),
                      deepgi::InputError);
    REQUIRE_THROWS_AS(deepgi::check_frame_limits(sized(1, 13655, 0.1f), plenty),
                      deepgi::InputError);
    // Exactly 16384 is allowed: 16384 + 2 * 0, and 13654 + 2 * 1365.
    REQUIRE_NOTHROW(deepgi::check_frame_limits(sized(16384, 720, 0.0f), plenty));
    REQUIRE_NOTHROW(deepgi::check_frame_limits(sized(1, 13654, 0.1f), plenty));
}

TEST_CASE("frame limits: the memory estimate grows with the internal area and is enforced",
          "[runtime][limits]") {
    const auto small = sized(1280, 720, 0.1f);
    const auto huge = sized(4096, 4096, 1.0f);  // 12288 x 12288 internal
    // At least the G-buffer's 40 bytes per internal pixel: 4096^2 with guard
    // band 1 (nine times the area) needs more than 5.6 GiB for it alone.
    REQUIRE(deepgi::estimate_frame_bytes(huge) >= 40ull * 12288 * 12288);
    REQUIRE(deepgi::estimate_frame_bytes(small) >= 40ull * 1536 * 976);
    REQUIRE(deepgi::estimate_frame_bytes(small) < (256ull << 20));
    REQUIRE_THROWS_AS(deepgi::check_frame_limits(huge, 4096ull << 20), deepgi::InputError);
    const std::uint64_t needed = deepgi::estimate_frame_bytes(small);
    REQUIRE_NOTHROW(deepgi::check_frame_limits(small, needed));
    REQUIRE_THROWS_AS(deepgi::check_frame_limits(small, needed - 1), deepgi::InputError);
}

TEST_CASE("deepgi: sizes beyond the limits exit 2 before rendering", "[runtime][limits][cli]") {
    for (const char* arguments :
         {"--size 16384x720", "--size 1x13655", "--size 4096x4096 --guard-band 1",
          "--size 1280x720 --max-gpu-memory 10"}) {
        INFO(arguments);
        const auto result = run_command(fmt::format(
            "{} --headless {} --output /nonexistent-dir/x.png", DEEPGI_EXECUTABLE, arguments));
        REQUIRE(result.status == 2);
        const bool named = result.err.find("16384 per side") != std::string::npos ||
                           result.err.find("--max-gpu-memory") != std::string::npos;
        REQUIRE(named);
    }
}
