// throng::protocol zstd codec (private) — wraps libzstd's one-shot API with the checks a decoder
// of untrusted input needs: one frame, declared content size equal to the expected one.
#include "zstd_codec.hpp"

#include <zstd.h>

namespace throng::protocol::detail {

std::vector<std::uint8_t> zstdCompress(std::span<const std::uint8_t> raw, int level) {
  std::vector<std::uint8_t> out(ZSTD_compressBound(raw.size()));
  const std::size_t n = ZSTD_compress(out.data(), out.size(), raw.data(), raw.size(), level);
  if (ZSTD_isError(n)) return {};
  out.resize(n);
  return out;
}

std::optional<std::vector<std::uint8_t>> zstdDecompress(std::span<const std::uint8_t> compressed,
                                                        std::size_t expectedSize, std::string& why) {
  const unsigned long long declared = ZSTD_getFrameContentSize(compressed.data(), compressed.size());
  if (declared == ZSTD_CONTENTSIZE_ERROR) {
    why = "not a zstd frame";
    return std::nullopt;
  }
  if (declared == ZSTD_CONTENTSIZE_UNKNOWN || declared != expectedSize) {
    why = "zstd frame declares " +
          (declared == ZSTD_CONTENTSIZE_UNKNOWN ? std::string("no content size") : std::to_string(declared) + " bytes") +
          " but the header says " + std::to_string(expectedSize);
    return std::nullopt;
  }
  const std::size_t frameSize = ZSTD_findFrameCompressedSize(compressed.data(), compressed.size());
  if (ZSTD_isError(frameSize) || frameSize != compressed.size()) {
    why = ZSTD_isError(frameSize) ? std::string("corrupt zstd frame: ") + ZSTD_getErrorName(frameSize)
                                  : "bytes after the zstd frame";
    return std::nullopt;
  }
  std::vector<std::uint8_t> out(expectedSize);
  const std::size_t n = ZSTD_decompress(out.data(), out.size(), compressed.data(), compressed.size());
  if (ZSTD_isError(n) || n != expectedSize) {
    why = ZSTD_isError(n) ? std::string("corrupt zstd frame: ") + ZSTD_getErrorName(n) : "zstd frame size mismatch";
    return std::nullopt;
  }
  return out;
}

}  // namespace throng::protocol::detail
