// throng::protocol::CrowdDecoder — reads CrowdFrame messages, writes reconstructed CrowdViews:
// parses the payload columns (docs/protocol.md "Crowd payload") with bounds and range checks,
// merges removals and records into the base frame's agents, resolves the pose table, checks the
// header's tier counts, and keeps the last frames as bases for the next ones.
#include "throng/protocol/crowd_decoder.hpp"

#include <algorithm>
#include <deque>
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
  const QView& base = basePtr ? *basePtr : kEmpty;
  const std::uint8_t J = h.jointCount;
  const std::uint8_t shift = h.jointShift;

  ByteReader r(frame.payload, "CrowdFrame", "payload byte");
  std::vector<std::uint32_t> removed, ids;
  readIds(r, static_cast<std::size_t>(r.varint("removalCount", kMaxAgents)), "removals", removed);
  const std::size_t n = static_cast<std::size_t>(r.varint("recordCount", kMaxAgents));
  if (r.ok() && n > r.remaining()) {
    r.fail("recordCount", std::to_string(n) + " records in " + std::to_string(r.remaining()) + " bytes", "at least 2 bytes per record");
  }
  readIds(r, r.ok() ? n : 0, "records", ids);
  std::vector<Record> recs(r.ok() ? n : 0);
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
  std::size_t at = r.offset();
  const std::size_t poseCount = static_cast<std::size_t>(r.varint("poseCount", kMaxAgents));
  if (r.ok() && poseCount > poseRecords) {
    r.fail("poseCount", at, std::to_string(poseCount) + " poses for " + std::to_string(poseRecords) + " records with a pose",
           "at most one pose per record with a pose");
  }
  const std::size_t comps = std::size_t{3} * J;
  if (r.ok() && poseCount * comps > r.remaining()) {
    r.fail("poseCount", at, std::to_string(poseCount) + " poses in " + std::to_string(r.remaining()) + " bytes",
           "at least one byte per joint angle");
  }
  const std::int64_t half = std::int64_t{1} << (15 - shift);
  std::vector<std::int64_t> table(r.ok() ? poseCount * comps : 0);
  for (auto& d : table) d = r.svarint("poseTable", -half, half - 1);
  r.expectEnd();
  if (!r.ok()) return r.error();

  // Merge: base minus removals, plus records.
  QView out;
  out.reserve(base.size() + recs.size());
  std::vector<std::vector<std::uint16_t>> resolved(poseCount);
  std::vector<bool> used(poseCount, false);
  std::size_t bi = 0;
  auto fail = [&](std::string what, std::string expected) { return frameError(h.frameNumber, std::move(what), std::move(expected)); };
  for (const std::uint32_t id : removed) {
    while (bi < base.size() && base[bi].id < id) out.push_back(base[bi++]);
    if (bi == base.size() || base[bi].id != id) {
      return fail("removal of agent " + std::to_string(id) + " that is not in base frame " + std::to_string(h.baseFrame),
                  "removals of agents present in the base frame");
    }
    ++bi;
  }
  for (; bi < base.size(); ++bi) out.push_back(base[bi]);
  QView merged;
  merged.reserve(out.size() + recs.size());
  std::size_t oi = 0;
  const std::uint32_t mask16 = 0xffffu >> shift;
  for (const Record& rec : recs) {
    while (oi < out.size() && out[oi].id < rec.id) merged.push_back(std::move(out[oi++]));
    if (std::binary_search(removed.begin(), removed.end(), rec.id)) {
      return fail("agent " + std::to_string(rec.id) + " both removed and updated", "an agent either removed or updated");
    }
    QAgent a;
    if (oi < out.size() && out[oi].id == rec.id) a = std::move(out[oi++]);
    a.id = rec.id;
    const Tier tier = (rec.mask & detail::kMaskTier) ? rec.tier : a.tier;
    detail::applyTierRules(a, tier, J);
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
      if (rec.pose >= poseCount) {
        return fail(who + ": pose " + std::to_string(rec.pose) + " beyond the table of " + std::to_string(poseCount),
                    "an index into the pose table");
      }
      auto& pose = resolved[rec.pose];
      if (!used[rec.pose]) {  // first user: the entry is a delta against its base
        used[rec.pose] = true;
        pose.resize(comps);
        for (std::size_t j = 0; j < comps; ++j) {
          const std::uint32_t u = (detail::jointUnits(a.joints[j], shift) + static_cast<std::uint32_t>(table[rec.pose * comps + j])) & mask16;
          pose[j] = static_cast<std::uint16_t>(u << shift);
        }
      }
      a.joints = pose;
    }
    merged.push_back(std::move(a));
  }
  for (; oi < out.size(); ++oi) merged.push_back(std::move(out[oi]));
  for (std::size_t k = 0; k < poseCount; ++k) {
    if (!used[k]) {
      return fail("pose " + std::to_string(k) + " of the table is never used", "every pose table entry used by a record");
    }
  }

  DecodedCrowdFrame result;
  result.header = h;
  std::uint32_t counts[3] = {0, 0, 0};
  for (const QAgent& a : merged) ++counts[static_cast<int>(a.tier)];
  if (counts[0] != h.nearCount || counts[1] != h.middleCount || counts[2] != h.farCount) {
    return fail("tier counts " + std::to_string(counts[0]) + "/" + std::to_string(counts[1]) + "/" + std::to_string(counts[2]) +
                    " after applying the frame",
                "the header's near/middle/far counts " + std::to_string(h.nearCount) + "/" + std::to_string(h.middleCount) + "/" +
                    std::to_string(h.farCount));
  }
  result.view.simTick = h.simTick;
  result.view.animationInterval = h.animationInterval;
  result.view.jointCount = J;
  result.view.agents.reserve(merged.size());
  for (const QAgent& a : merged) result.view.agents.push_back(detail::dequantizeAgent(a));

  s.history.emplace_back(h.frameNumber, std::move(merged));
  while (s.history.size() > s.historyFrames) s.history.pop_front();
  s.newest = std::max(s.newest, h.frameNumber);
  return result;
}

}  // namespace throng::protocol
