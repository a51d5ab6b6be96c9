// The C++ tau table the build wrote (tau_table.hpp) compiles, is usable in
// constant expressions, and agrees with search() for every n it covers.
#include <catch2/catch.hpp>

#include <tau_table.hpp>

#include "spiral/optimizer.hpp"

using spiral::generated::kSpiralTurns;
using spiral::generated::kSpiralTurnsMaxTaps;
using spiral::generated::kSpiralTurnsMinTaps;

static_assert(kSpiralTurns.size() == kSpiralTurnsMaxTaps + 1);
static_assert(kSpiralTurns[0] == 0, "entry 0 is unused");
static_assert(kSpiralTurns[1] == 1, "one tap: the only tau is 1");

TEST_CASE("generated table: the generated C++ table equals search() for every tabulated n",
          "[codegen][table]") {
    for (int n = 1; n < kSpiralTurnsMinTaps; ++n)
        CHECK(kSpiralTurns[static_cast<std::size_t>(n)] == 0);
    for (int n = kSpiralTurnsMinTaps; n <= kSpiralTurnsMaxTaps; ++n) {
        INFO("n = " << n);
        CHECK(kSpiralTurns[static_cast<std::size_t>(n)] == spiral::search(n).tau);
    }
}
