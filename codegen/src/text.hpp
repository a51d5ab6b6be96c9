// Small text helpers shared by the formatters. Internal to spiral_codegen.
#pragma once

#include <spiral/codegen.hpp>

#include <string>
#include <string_view>

namespace spiral::codegen::detail {

// Printable ASCII only; anything else becomes '?', so a comment line can never
// be broken by a newline or by bytes a GLSL compiler refuses.
std::string printable_ascii(std::string_view text);

// The "generated" banner every commented file opens with: one `// ` line each.
// The command is wrapped in backticks so it never ends in a backslash, which
// would splice the next line into the comment in both C++ and GLSL.
std::string banner(const Provenance& provenance, std::string_view what, std::string_view inputs);

// The shortest decimal text that reads back as the same float, always with a
// '.' or an exponent so GLSL and C++ see a floating literal ("1" -> "1.0").
// -0 is written as 0.0.
std::string float_literal(float value);

// Shortest round-trip text of a double (JSON, CSV, Markdown).
std::string double_text(double value);

}  // namespace spiral::codegen::detail
