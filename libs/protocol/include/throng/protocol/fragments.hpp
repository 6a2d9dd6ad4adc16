// throng::protocol fragments — splitting one encoded server → client message that is too large for
// a UDP datagram into Fragment datagrams (splitMessage), and putting them back together on the
// client (Reassembler). Pure data: reads bytes, writes bytes. Rules: docs/protocol.md "Fragment".
#pragma once
#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <vector>

#include "throng/core/result.hpp"
#include "throng/protocol/messages.hpp"

namespace throng::protocol {

/// The largest Fragment header: magic, type, messageId (10-byte varint), index and count (2 each).
inline constexpr std::size_t kMaxFragmentHeader = 16;
/// The smallest datagram splitMessage accepts [bytes]: a header and at least some payload.
inline constexpr std::size_t kMinFragmentDatagram = 64;

/// The largest message that splits into at most kMaxFragments datagrams of `datagramBytes` each
/// (≤ kMaxMessageSize) [bytes]; 0 when datagramBytes < kMinFragmentDatagram.
[[nodiscard]] std::size_t maxFragmentedSize(std::size_t datagramBytes);

/// The encoded Fragment datagrams (each ≤ datagramBytes bytes) carrying `message` as message
/// `messageId`: empty when the message fits one datagram (send it whole), is larger than
/// maxFragmentedSize(datagramBytes), or datagramBytes < kMinFragmentDatagram.
[[nodiscard]] std::vector<Bytes> splitMessage(std::span<const std::uint8_t> message, std::uint64_t messageId,
                                              std::size_t datagramBytes);

/// Collects the Fragments of one peer. At most kMaxInProgress messages are incomplete at once (a
/// new one drops the oldest); when a message completes, every incomplete one with a smaller
/// messageId is dropped (it is older: UDP lost or reordered a piece of it). Duplicates are
/// ignored; a messageId already completed or dropped is ignored too.
class Reassembler {
 public:
  static constexpr std::size_t kMaxInProgress = 4;

  /// Adds one fragment. Returns the whole message once its last fragment arrived, nullopt while
  /// incomplete (or when the fragment is ignored), an error (pointer "/Fragment/…") when the
  /// fragment contradicts the others of its message (count differs, total over kMaxMessageSize,
  /// the whole is a Fragment itself); that message is then dropped.
  core::Result<std::optional<Bytes>> add(const Fragment& fragment);

  /// Incomplete messages dropped so far (too many in progress, older than a completed one, or bad).
  [[nodiscard]] std::uint64_t droppedMessages() const { return dropped_; }
  /// Messages in progress now.
  [[nodiscard]] std::size_t inProgress() const { return pending_.size(); }

 private:
  struct Pending {
    std::uint32_t count = 0;
    std::uint32_t received = 0;
    std::size_t bytes = 0;
    std::vector<std::optional<Bytes>> pieces;  ///< by index
  };
  core::Diagnostic drop(std::uint64_t messageId, std::string what, std::string expected);

  std::map<std::uint64_t, Pending> pending_;  ///< by messageId
  std::uint64_t finishedBelow_ = 0;  ///< every messageId below this one completed or was dropped
  std::uint64_t dropped_ = 0;
};

}  // namespace throng::protocol
