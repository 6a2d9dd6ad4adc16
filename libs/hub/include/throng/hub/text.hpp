// throng::hub text checks — what the server does with strings a client sent before it keeps,
// relays or echoes them: UTF-8 validation at entry (names, crowd ids, crowd files) and a printable
// form for echoing (control characters and invalid bytes escaped, length capped at a character
// boundary). Pure functions; no I/O.
#pragma once
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>

namespace throng::hub {

/// The offset of the first byte of `text` that does not belong to a well-formed UTF-8 sequence
/// (overlong forms, surrogates and code points above U+10FFFF are ill-formed); nothing when all
/// of it is UTF-8.
[[nodiscard]] std::optional<std::size_t> invalidUtf8At(std::string_view text);

/// "byte N (0xHH)" for the diagnostics that name an invalid byte.
[[nodiscard]] std::string describeByte(std::string_view text, std::size_t offset);

/// `text` as it may be echoed in a message, a log line or a terminal: valid UTF-8 kept, control
/// characters (U+0000..U+001F, U+007F) and bytes of ill-formed sequences written as \xHH, at most
/// `maxBytes` bytes (cut at a character boundary, ending in "..." when cut; maxBytes >= 3).
[[nodiscard]] std::string printable(std::string_view text, std::size_t maxBytes);

/// `text` with every byte of an ill-formed UTF-8 sequence replaced by U+FFFD (what a JSON writer
/// or reader can always take).
[[nodiscard]] std::string validUtf8(std::string_view text);

/// The longest prefix of `text` of at most `maxBytes` bytes that does not cut a UTF-8 sequence.
[[nodiscard]] std::string_view cutUtf8(std::string_view text, std::size_t maxBytes);

}  // namespace throng::hub
