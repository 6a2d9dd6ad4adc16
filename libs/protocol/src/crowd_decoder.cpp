// throng::protocol::CrowdDecoder — reads CrowdFrame messages, writes reconstructed CrowdViews:
// parses the payload columns (docs/protocol.md "Crowd payload") with bounds and range checks,
// merges removals and records into the base frame's agents, resolves the pose table, checks the
// header's tier counts, and keeps the last frames as bases for the next ones.
#include "throng/protocol/crowd_decoder.hpp"

#include <algorithm>
#include <deque>
#include <optional>
#include <variant>

#include "byte_io.hpp"
#include "crowd_state.hpp"
#include "throng/protocol/messages.hpp"

namespace throng::protocol {

using detail::ByteReader;
using detail::QAgent;
using detail::QView;

struct CrowdDecoder::Impl {
  std::size_t historyFrames = 64;
  std::deque<std::pair<std::uint32_t, QView>> history;  ///< decode order, oldest first
  std::uint32_t newest = 0;

  const QView* find(std::uint32_t frame) const {
    for (const auto& [n, v] : history) {
      if (n == frame) return &v;
    }
    return nullptr;
  }
};

namespace {

struct Record {
  std::uint32_t id = 0;
  std::uint8_t mask = 0;
  Tier tier = Tier::Near;
  std::int64_t dx = 0, dy = 0, dz = 0, dyaw = 0, dphase = 0;
  std::uint16_t clip = 0;
  std::uint32_t pose = 0;
};

/// Reads `n` ascending ids coded as gaps.
bool readIds(ByteReader& r, std::size_t n, const char* field, std::vector<std::uint32_t>& ids) {
  ids.resize(n);
  std::uint64_t prev = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t at = r.offset();
    const std::uint64_t gap = r.varint(field, 0xffffffffu);
    const std::uint64_t id = i == 0 ? gap : prev + 1 + gap;
    if (r.ok() && id > 0xffffffffu) {
      r.fail(field, at, "agent id " + std::to_string(id) + " beyond 32 bits", "ids < 2^32, ascending");
    }
    if (!r.ok()) return false;
    ids[i] = static_cast<std::uint32_t>(id);
    prev = id;
  }
  return true;
}

core::Diagnostic frameError(std::uint32_t frame, std::string what, std::string expected) {
  core::Diagnostic d;
  d.pointer = "/CrowdFrame/" + std::to_string(frame);
  d.what = std::move(what);
  d.expected = std::move(expected);
  return d;
}


/// The payload's columns, read and range-checked (docs/protocol.md "Crowd payload").
struct Payload {
  std::vector<std::uint32_t> removed;  ///< ascending ids
  std::vector<Record> records;         ///< ascending ids
  std::size_t poseCount = 0;
  std::vector<std::int64_t> poseTable;  ///< poseCount × 3J joint deltas
};

/// Each record's mask, then each field's column for the records whose mask has it; returns how
/// many records carry a pose.
std::size_t readRecordColumns(ByteReader& r, std::vector<Record>& recs, const std::vector<std::uint32_t>& ids) {
  for (std::size_t i = 0; i < recs.size(); ++i) {
    recs[i].id = ids[i];
    recs[i].mask = r.u8("masks");
  }
  for (Record& rec : recs) {
    if (!(rec.mask & detail::kMaskTier)) continue;
    const std::size_t at = r.offset();
    const std::uint8_t t = r.u8("tiers");
    if (t > 2) r.fail("tiers", at, "unknown tier " + std::to_string(t), "0 (near), 1 (middle) or 2 (far)");
    rec.tier = static_cast<Tier>(t);
  }
  constexpr std::int64_t kPosMax = std::int64_t{1} << 32;
  for (Record& rec : recs) if (rec.mask & detail::kMaskX) rec.dx = r.svarint("x", -kPosMax, kPosMax);
  for (Record& rec : recs) if (rec.mask & detail::kMaskY) rec.dy = r.svarint("y", -kPosMax, kPosMax);
  for (Record& rec : recs) if (rec.mask & detail::kMaskZ) rec.dz = r.svarint("z", -kPosMax, kPosMax);
  for (Record& rec : recs) if (rec.mask & detail::kMaskYaw) rec.dyaw = r.svarint("yaw", -32768, 32767);
  for (Record& rec : recs) if (rec.mask & detail::kMaskClip) rec.clip = static_cast<std::uint16_t>(r.varint("clip", 0xffff));
  for (Record& rec : recs) if (rec.mask & detail::kMaskPhase) rec.dphase = r.svarint("phase", -128, 127);
  std::size_t poseRecords = 0;
  for (Record& rec : recs) {
    if (rec.mask & detail::kMaskPose) {
      rec.pose = static_cast<std::uint32_t>(r.varint("poses", kMaxAgents));
      ++poseRecords;
    }
  }
  return poseRecords;
}

/// The pose table: at most one entry per record with a pose, each 3J joint deltas at `shift`.
void readPoseTable(ByteReader& r, std::size_t poseRecords, std::uint8_t jointCount, std::uint8_t shift, Payload& p) {
  const std::size_t at = r.offset();
  p.poseCount = static_cast<std::size_t>(r.varint("poseCount", kMaxAgents));
  if (r.ok() && p.poseCount > poseRecords) {
    r.fail("poseCount", at, std::to_string(p.poseCount) + " poses for " + std::to_string(poseRecords) + " records with a pose",
           "at most one pose per record with a pose");
  }
  const std::size_t comps = std::size_t{3} * jointCount;
  if (r.ok() && p.poseCount * comps > r.remaining()) {
    r.fail("poseCount", at, std::to_string(p.poseCount) + " poses in " + std::to_string(r.remaining()) + " bytes",
           "at least one byte per joint angle");
  }
  const std::int64_t half = std::int64_t{1} << (15 - shift);
  p.poseTable.assign(r.ok() ? p.poseCount * comps : 0, 0);
  for (auto& d : p.poseTable) d = r.svarint("poseTable", -half, half - 1);
}

core::Result<Payload> readPayload(const CrowdFrame& frame) {
  const CrowdFrameHeader& h = frame.header;
  ByteReader r(frame.payload, "CrowdFrame", "payload byte");
  Payload p;
  std::vector<std::uint32_t> ids;
  readIds(r, static_cast<std::size_t>(r.varint("removalCount", kMaxAgents)), "removals", p.removed);
  const std::size_t n = static_cast<std::size_t>(r.varint("recordCount", kMaxAgents));
  if (r.ok() && n > r.remaining()) {
    r.fail("recordCount", std::to_string(n) + " records in " + std::to_string(r.remaining()) + " bytes", "at least 2 bytes per record");
  }
  readIds(r, r.ok() ? n : 0, "records", ids);
  p.records.resize(r.ok() ? n : 0);
  const std::size_t poseRecords = readRecordColumns(r, p.records, ids);
  readPoseTable(r, poseRecords, h.jointCount, h.jointShift, p);
  r.expectEnd();
  if (!r.ok()) return r.error();
  return p;
}

/// The base frame's agents without the removed ones.
core::Result<QView> removeFromBase(const QView& base, const std::vector<std::uint32_t>& removed, const CrowdFrameHeader& h) {
  QView out;
  out.reserve(base.size());
  std::size_t bi = 0;
  for (const std::uint32_t id : removed) {
    while (bi < base.size() && base[bi].id < id) out.push_back(base[bi++]);
    if (bi == base.size() || base[bi].id != id) {
      return frameError(h.frameNumber,
                        "removal of agent " + std::to_string(id) + " that is not in base frame " + std::to_string(h.baseFrame),
                        "removals of agents present in the base frame");
    }
    ++bi;
  }
  for (; bi < base.size(); ++bi) out.push_back(base[bi]);
  return out;
}

/// The frame's pose table resolved: an entry is a delta against the joints of the first record
/// that uses it; later users share the result.
class PoseResolver {
 public:
  PoseResolver(const std::vector<std::int64_t>& table, std::size_t count, std::uint8_t jointCount, std::uint8_t shift)
      : table_(table), comps_(std::size_t{3} * jointCount), shift_(shift), resolved_(count), used_(count, false) {}

  [[nodiscard]] std::size_t size() const { return resolved_.size(); }
  /// Entry `index` (< size()) for an agent whose joints were `joints`.
  const std::vector<std::uint16_t>& resolve(std::uint32_t index, const std::vector<std::uint16_t>& joints) {
    auto& pose = resolved_[index];
    if (!used_[index]) {  // first user: the entry is a delta against its base
      used_[index] = true;
      const std::uint32_t mask16 = 0xffffu >> shift_;
      pose.resize(comps_);
      for (std::size_t j = 0; j < comps_; ++j) {
        const std::uint32_t u = (detail::jointUnits(joints[j], shift_) + static_cast<std::uint32_t>(table_[index * comps_ + j])) & mask16;
        pose[j] = static_cast<std::uint16_t>(u << shift_);
      }
    }
    return pose;
  }
  /// The first entry no record used, if any.
  [[nodiscard]] std::optional<std::size_t> firstUnused() const {
    for (std::size_t k = 0; k < used_.size(); ++k) {
      if (!used_[k]) return k;
    }
    return std::nullopt;
  }

 private:
  const std::vector<std::int64_t>& table_;
  std::size_t comps_;
  std::uint8_t shift_;
  std::vector<std::vector<std::uint16_t>> resolved_;
  std::vector<bool> used_;
};

/// Applies one record to its agent (from the base, or new): tier rules, position, yaw, clip,
/// phase and pose; an error for what its tier may not carry or a value out of range.
std::optional<core::Diagnostic> applyRecord(QAgent& a, const Record& rec, const CrowdFrameHeader& h, PoseResolver& poses) {
  auto fail = [&](std::string what, std::string expected) { return frameError(h.frameNumber, std::move(what), std::move(expected)); };
  a.id = rec.id;
  const Tier tier = (rec.mask & detail::kMaskTier) ? rec.tier : a.tier;
  detail::applyTierRules(a, tier, h.jointCount);
  const std::string who = "agent " + std::to_string(rec.id);
  if (tier == Tier::Far && (rec.mask & (detail::kMaskYaw | detail::kMaskClip | detail::kMaskPhase | detail::kMaskPose))) {
    return fail(who + ": far agent with yaw, clip, phase or pose", "position only for far agents");
  }
  if (tier == Tier::Middle && (rec.mask & detail::kMaskPose)) return fail(who + ": middle agent with a pose", "poses for near agents only");
  if (tier == Tier::Middle && (rec.dyaw < -128 || rec.dyaw > 127)) {
    return fail(who + ": middle yaw delta " + std::to_string(rec.dyaw), "a delta in [-128, 127] (1/256 turn)");
  }
  const std::int64_t x = a.x + rec.dx, y = a.y + rec.dy, z = a.z + rec.dz;
  constexpr std::int64_t kMin = INT32_MIN, kMax = INT32_MAX;
  if (x < kMin || x > kMax || y < kMin || y > kMax || z < kMin || z > kMax) {
    return fail(who + ": position outside the int32 cm range", "positions within ±2^31 cm");
  }
  a.x = static_cast<std::int32_t>(x);
  a.y = static_cast<std::int32_t>(y);
  a.z = static_cast<std::int32_t>(z);
  if (rec.mask & detail::kMaskYaw) {
    a.yaw = tier == Tier::Near ? static_cast<std::uint16_t>(a.yaw + rec.dyaw)
                               : static_cast<std::uint16_t>(((a.yaw >> 8) + rec.dyaw) & 0xff) << 8;
  }
  if (rec.mask & detail::kMaskClip) a.clip = rec.clip;
  if (rec.mask & detail::kMaskPhase) a.phase = static_cast<std::uint8_t>(a.phase + rec.dphase);
  if (rec.mask & detail::kMaskPose) {
    if (rec.pose >= poses.size()) {
      return fail(who + ": pose " + std::to_string(rec.pose) + " beyond the table of " + std::to_string(poses.size()),
                  "an index into the pose table");
    }
    a.joints = poses.resolve(rec.pose, a.joints);
  }
  return std::nullopt;
}

/// The base's remaining agents merged with the records, in id order.
core::Result<QView> mergeRecords(QView out, const Payload& p, const CrowdFrameHeader& h) {
  QView merged;
  merged.reserve(out.size() + p.records.size());
  PoseResolver poses(p.poseTable, p.poseCount, h.jointCount, h.jointShift);
  std::size_t oi = 0;
  for (const Record& rec : p.records) {
    while (oi < out.size() && out[oi].id < rec.id) merged.push_back(std::move(out[oi++]));
    if (std::binary_search(p.removed.begin(), p.removed.end(), rec.id)) {
      return frameError(h.frameNumber, "agent " + std::to_string(rec.id) + " both removed and updated",
                        "an agent either removed or updated");
    }
    QAgent a;
    if (oi < out.size() && out[oi].id == rec.id) a = std::move(out[oi++]);
    if (auto error = applyRecord(a, rec, h, poses)) return std::move(*error);
    merged.push_back(std::move(a));
  }
  for (; oi < out.size(); ++oi) merged.push_back(std::move(out[oi]));
  if (const auto k = poses.firstUnused()) {
    return frameError(h.frameNumber, "pose " + std::to_string(*k) + " of the table is never used",
                      "every pose table entry used by a record");
  }
  return merged;
}

/// The header's near/middle/far counts must match the agents after the frame.
std::optional<core::Diagnostic> checkTierCounts(const QView& merged, const CrowdFrameHeader& h) {
  std::uint32_t counts[3] = {0, 0, 0};
  for (const QAgent& a : merged) ++counts[static_cast<int>(a.tier)];
  if (counts[0] == h.nearCount && counts[1] == h.middleCount && counts[2] == h.farCount) return std::nullopt;
  return frameError(h.frameNumber,
                    "tier counts " + std::to_string(counts[0]) + "/" + std::to_string(counts[1]) + "/" + std::to_string(counts[2]) +
                        " after applying the frame",
                    "the header's near/middle/far counts " + std::to_string(h.nearCount) + "/" + std::to_string(h.middleCount) +
                        "/" + std::to_string(h.farCount));
}

}  // namespace

CrowdDecoder::CrowdDecoder(std::size_t historyFrames) : impl_(std::make_unique<Impl>()) {
  impl_->historyFrames = std::clamp<std::size_t>(historyFrames, 1, 4096);
}
CrowdDecoder::~CrowdDecoder() = default;
CrowdDecoder::CrowdDecoder(CrowdDecoder&&) noexcept = default;
CrowdDecoder& CrowdDecoder::operator=(CrowdDecoder&&) noexcept = default;

std::uint32_t CrowdDecoder::newestFrame() const { return impl_->newest; }
bool CrowdDecoder::hasFrame(std::uint32_t frameNumber) const { return impl_->find(frameNumber) != nullptr; }
void CrowdDecoder::reset() {
  impl_->history.clear();
  impl_->newest = 0;
}

core::Result<DecodedCrowdFrame> CrowdDecoder::decode(std::span<const std::uint8_t> bytes) {
  auto m = decodeAny(bytes);
  if (!m) return std::move(m).takeErrors();
  if (!std::holds_alternative<CrowdFrame>(m.value())) {
    return frameError(0, std::string("a ") + messageTypeName(messageType(m.value())) + " message", "a CrowdFrame");
  }
  return apply(std::get<CrowdFrame>(m.value()));
}

core::Result<DecodedCrowdFrame> CrowdDecoder::apply(const CrowdFrame& frame) {
  Impl& s = *impl_;
  const CrowdFrameHeader& h = frame.header;
  const QView* basePtr = nullptr;
  if (h.baseFrame != 0) {
    basePtr = s.find(h.baseFrame);
    if (!basePtr) {
      return frameError(h.frameNumber, "base frame " + std::to_string(h.baseFrame) + " unknown (never decoded, or older than the last " +
                                           std::to_string(s.historyFrames) + " frames)",
                        "a key frame or a delta against a frame this client acknowledged");
    }
  }
  static const QView kEmpty;
  auto payload = readPayload(frame);
  if (!payload) return std::move(payload).takeErrors();
  // Merge: base minus removals, plus records.
  auto kept = removeFromBase(basePtr ? *basePtr : kEmpty, payload->removed, h);
  if (!kept) return std::move(kept).takeErrors();
  auto merged = mergeRecords(std::move(kept).value(), payload.value(), h);
  if (!merged) return std::move(merged).takeErrors();
  if (auto error = checkTierCounts(merged.value(), h)) return std::move(*error);

  DecodedCrowdFrame result;
  result.header = h;
  result.view.simTick = h.simTick;
  result.view.animationInterval = h.animationInterval;
  result.view.jointCount = h.jointCount;
  result.view.agents.reserve(merged->size());
  for (const QAgent& a : merged.value()) result.view.agents.push_back(detail::dequantizeAgent(a));

  s.history.emplace_back(h.frameNumber, std::move(merged).value());
  while (s.history.size() > s.historyFrames) s.history.pop_front();
  s.newest = std::max(s.newest, h.frameNumber);
  return result;
}

}  // namespace throng::protocol
