// throng::protocol fragments — splitMessage (server side) and Reassembler (client side); see
// fragments.hpp and docs/protocol.md "Fragment".
#include "throng/protocol/fragments.hpp"

#include <algorithm>
#include <string>
#include <utility>

namespace throng::protocol {
namespace {

std::size_t varintLength(std::uint64_t v) {
  std::size_t n = 1;
  while (v >= 0x80) {
    v >>= 7;
    ++n;
  }
  return n;
}

}  // namespace

std::size_t maxFragmentedSize(std::size_t datagramBytes) {
  if (datagramBytes < kMinFragmentDatagram) return 0;
  return std::min(kMaxMessageSize, kMaxFragments * (datagramBytes - kMaxFragmentHeader));
}

std::vector<Bytes> splitMessage(std::span<const std::uint8_t> message, std::uint64_t messageId, std::size_t datagramBytes) {
  if (datagramBytes < kMinFragmentDatagram || message.size() <= datagramBytes ||
      message.size() > maxFragmentedSize(datagramBytes)) {
    return {};
  }
  // Header: magic, type, messageId, index (< count) and count; count ≤ 8192 needs ≤ 2 bytes.
  const std::size_t header = 2 + varintLength(messageId) + 2 * varintLength(kMaxFragments - 1);
  const std::size_t chunk = datagramBytes - header;
  const std::size_t count = (message.size() + chunk - 1) / chunk;
  std::vector<Bytes> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    Fragment f;
    f.messageId = messageId;
    f.index = static_cast<std::uint32_t>(i);
    f.count = static_cast<std::uint32_t>(count);
    const std::size_t begin = i * chunk, end = std::min(message.size(), begin + chunk);
    f.payload.assign(message.begin() + static_cast<std::ptrdiff_t>(begin), message.begin() + static_cast<std::ptrdiff_t>(end));
    out.push_back(encode(f));
  }
  return out;
}

core::Diagnostic Reassembler::drop(std::uint64_t messageId, std::string what, std::string expected) {
  if (pending_.erase(messageId) > 0) ++dropped_;
  core::Diagnostic d;
  d.pointer = "/Fragment/messageId";
  d.what = "fragmented message " + std::to_string(messageId) + ": " + std::move(what);
  d.expected = std::move(expected);
  return d;
}

core::Result<std::optional<Bytes>> Reassembler::add(const Fragment& f) {
  if (f.count < kMinFragments || f.count > kMaxFragments || f.index >= f.count) {
    core::Diagnostic d;
    d.pointer = "/Fragment/count";
    d.what = "fragment " + std::to_string(f.index) + " of " + std::to_string(f.count);
    d.expected = "a count of " + std::to_string(kMinFragments) + ".." + std::to_string(kMaxFragments) + " and an index below it";
    return d;
  }
  if (f.messageId < finishedBelow_) return std::optional<Bytes>{};  // completed or dropped already
  auto it = pending_.find(f.messageId);
  if (it == pending_.end()) {
    if (pending_.size() >= kMaxInProgress) {
      // Make room: drop the oldest incomplete message (and forget everything before it).
      const std::uint64_t oldest = pending_.begin()->first;
      if (f.messageId < oldest) return std::optional<Bytes>{};  // older than all in progress: stale
      pending_.erase(pending_.begin());
      ++dropped_;
      finishedBelow_ = std::max(finishedBelow_, oldest + 1);
    }
    it = pending_.emplace(f.messageId, Pending{}).first;
    it->second.count = f.count;
    it->second.pieces.resize(f.count);
  }
  Pending& p = it->second;
  if (p.count != f.count) {
    return drop(f.messageId, "fragment " + std::to_string(f.index) + " says " + std::to_string(f.count) + " fragments",
                std::to_string(p.count) + " fragments, as its first fragment said");
  }
  if (p.pieces[f.index]) return std::optional<Bytes>{};  // a duplicate: ignored
  if (p.bytes + f.payload.size() > kMaxMessageSize) {
    return drop(f.messageId, "more than " + std::to_string(kMaxMessageSize) + " bytes",
                "at most " + std::to_string(kMaxMessageSize) + " bytes in all");
  }
  p.bytes += f.payload.size();
  p.pieces[f.index] = f.payload;
  if (++p.received < p.count) return std::optional<Bytes>{};

  Bytes whole;
  whole.reserve(p.bytes);
  for (const auto& piece : p.pieces) whole.insert(whole.end(), piece->begin(), piece->end());
  const std::uint64_t id = f.messageId;
  if (whole.size() >= 2 && whole[0] == kMagic && whole[1] == static_cast<std::uint8_t>(MessageType::Fragment)) {
    auto d = drop(id, "the reassembled message is itself a Fragment", "a whole message of another type");
    finishedBelow_ = std::max(finishedBelow_, id + 1);
    return d;
  }
  pending_.erase(it);
  // Everything older that is still incomplete lost a piece (or is overtaken): drop it.
  while (!pending_.empty() && pending_.begin()->first < id) {
    pending_.erase(pending_.begin());
    ++dropped_;
  }
  finishedBelow_ = std::max(finishedBelow_, id + 1);
  return std::optional<Bytes>(std::move(whole));
}

}  // namespace throng::protocol
