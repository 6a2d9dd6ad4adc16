// throng::protocol crowd frame codec (private) — the CrowdFrame message's uncompressed header and
// its payload's compression; the payload's contents are CrowdEncoder's / CrowdDecoder's business.
#pragma once
#include <cstdint>
#include <vector>

#include "byte_io.hpp"
#include "throng/protocol/crowd_frame.hpp"

namespace throng::protocol::detail {

inline constexpr std::uint8_t kCrowdFlagCompressed = 1;
inline constexpr std::uint8_t kCrowdFlagFarIncluded = 2;
inline constexpr std::uint8_t kMaxJointShift = 8;
inline constexpr int kCrowdZstdLevel = 3;

/// The whole message: magic, type, header, payload (zstd-compressed when header.compressed).
/// `compressed`: the payload already compressed (saves compressing twice); computed when null.
[[nodiscard]] std::vector<std::uint8_t> encodeCrowdFrame(const CrowdFrame& frame,
                                                   const std::vector<std::uint8_t>* compressed = nullptr);

/// Reads header and payload after the 2-byte message header (decompressing it).
[[nodiscard]] CrowdFrame decodeCrowdFrame(ByteReader& r);

}  // namespace throng::protocol::detail
