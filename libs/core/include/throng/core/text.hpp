// throng::core text — strings from input files made safe to echo: in a diagnostic
// (Diagnostic::format() passes every field through printable(), so a diagnostic is always one
// line of valid UTF-8), on a terminal, in a log or in a JSON string.
#pragma once
#include <cstddef>
#include <string>
#include <string_view>

namespace throng::core {

/// `text` made safe to echo on one line: control characters escaped ("\n", "\t", "\u0007", C1
/// controls too), bytes that are not UTF-8 shown as "\xNN", and at most `maxCodePoints` code
/// points kept (then "..." marks the cut; never inside a character).
[[nodiscard]] std::string printable(std::string_view text, std::size_t maxCodePoints = static_cast<std::size_t>(-1));

/// Whether `text` is well-formed UTF-8 (no overlong forms, surrogates or code points > U+10FFFF).
[[nodiscard]] bool isUtf8(std::string_view text);

}  // namespace throng::core
