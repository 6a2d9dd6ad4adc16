// throng::protocol zstd codec (private) — one-shot compression of crowd payloads and world
// descriptions, and bounded decompression (the declared size must match the zstd frame's).
#pragma once
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace throng::protocol::detail {

/// One zstd frame with its content size recorded.
[[nodiscard]] std::vector<std::uint8_t> zstdCompress(std::span<const std::uint8_t> raw, int level);

/// Decompresses exactly `expectedSize` bytes (≤ the caller's limit); on failure returns nullopt
/// and `why` says what was wrong.
[[nodiscard]] std::optional<std::vector<std::uint8_t>> zstdDecompress(std::span<const std::uint8_t> compressed,
                                                                     std::size_t expectedSize, std::string& why);

}  // namespace throng::protocol::detail
