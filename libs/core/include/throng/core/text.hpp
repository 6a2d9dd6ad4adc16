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

/// Length of the well-formed UTF-8 sequence starting at text[i] (1 for ASCII); 0 when it is not
/// one (stray continuation byte, overlong form, surrogate, beyond U+10FFFF, cut short).
[[nodiscard]] std::size_t utf8SequenceLength(std::string_view text, std::size_t i);

/// Whether `text` is well-formed UTF-8 (no overlong forms, surrogates or code points > U+10FFFF).
[[nodiscard]] bool isUtf8(std::string_view text);

}  // namespace throng::core
