// throng::protocol::CrowdEncoder — reads the server's CrowdView of a tick and the client's newest
// ack, writes one CrowdFrame message: the payload columns (docs/protocol.md "Crowd payload") built
// by merging the base frame's reconstructed agents with the quantized view, then stores what the
// client will reconstruct so later frames can delta against it.
#include "throng/protocol/crowd_encoder.hpp"

#include <algorithm>
#include <map>

#include "byte_io.hpp"
#include "crowd_frame_codec.hpp"
#include "crowd_state.hpp"
#include "zstd_codec.hpp"

namespace throng::protocol {

using detail::ByteWriter;
using detail::QAgent;
using detail::QView;

struct CrowdEncoder::Impl {
  CrowdEncoderOptions options;
  std::uint32_t next = 1;
  std::deque<std::pair<std::uint32_t, QView>> history;  ///< oldest first
  std::deque<std::uint8_t> jointCounts;                 ///< per history entry
  std::deque<std::uint64_t> ticks;
  std::deque<std::uint8_t> intervals;

  const QView* find(std::uint32_t frame) const {
    for (const auto& [n, v] : history) {
      if (n == frame) return &v;
    }
    return nullptr;
  }
};

namespace {

/// Column writers of one payload.
struct Columns {
  std::vector<std::uint8_t> ids, masks, tiers, xs, ys, zs, yaws, clips, phases, poses, table;
  std::uint32_t lastId = 0;
  bool first = true;
  std::size_t records = 0;
};

core::Diagnostic encodeError(std::string what, std::string expected) {
  core::Diagnostic d;
  d.pointer = "/CrowdView";
  d.what = std::move(what);
  d.expected = std::move(expected);
  return d;
}

std::int64_t wrapDelta(std::uint32_t target, std::uint32_t base, int bits) {
  const std::uint32_t mask = (1u << bits) - 1;
  std::uint32_t d = (target - base) & mask;
  return d >= (1u << (bits - 1)) ? static_cast<std::int64_t>(d) - (std::int64_t{1} << bits) : d;
}

}  // namespace

CrowdEncoder::CrowdEncoder(CrowdEncoderOptions options) : impl_(std::make_unique<Impl>()) {
  options.historyFrames = std::clamp<std::size_t>(options.historyFrames, 1, 4096);
  options.farInterval = std::max<std::uint32_t>(options.farInterval, 1);
  options.jointShift = std::min<std::uint8_t>(options.jointShift, detail::kMaxJointShift);
  options.compressionLevel = std::clamp(options.compressionLevel, 1, 22);
  impl_->options = options;
}
CrowdEncoder::~CrowdEncoder() = default;
CrowdEncoder::CrowdEncoder(CrowdEncoder&&) noexcept = default;
CrowdEncoder& CrowdEncoder::operator=(CrowdEncoder&&) noexcept = default;

void CrowdEncoder::reset() {
  impl_->history.clear();
  impl_->jointCounts.clear();
  impl_->ticks.clear();
  impl_->intervals.clear();
}

std::uint32_t CrowdEncoder::nextFrameNumber() const { return impl_->next; }
const CrowdEncoderOptions& CrowdEncoder::options() const { return impl_->options; }

std::optional<CrowdView> CrowdEncoder::sentView(std::uint32_t frameNumber) const {
  for (std::size_t i = 0; i < impl_->history.size(); ++i) {
    if (impl_->history[i].first != frameNumber) continue;
    CrowdView v;
    v.simTick = impl_->ticks[i];
    v.animationInterval = impl_->intervals[i];
    v.jointCount = impl_->jointCounts[i];
    for (const QAgent& q : impl_->history[i].second) v.agents.push_back(detail::dequantizeAgent(q));
    return v;
  }
  return std::nullopt;
}

core::Result<EncodedCrowdFrame> CrowdEncoder::encode(const CrowdView& view, std::uint32_t ackedFrame) {
  Impl& s = *impl_;
  const CrowdEncoderOptions& o = s.options;
  if (view.agents.size() > kMaxAgents) {
    return encodeError(std::to_string(view.agents.size()) + " agents in view", "at most " + std::to_string(kMaxAgents));
  }
  if (view.jointCount > kMaxJoints) {
    return encodeError("jointCount " + std::to_string(view.jointCount), "at most " + std::to_string(kMaxJoints));
  }
  if (view.animationInterval == 0) return encodeError("animationInterval 0", "X ≥ 1");

  QView target;
  target.reserve(view.agents.size());
  for (const AgentState& a : view.agents) target.push_back(detail::quantizeAgent(a, view.jointCount, o.jointShift));
  std::sort(target.begin(), target.end(), [](const QAgent& a, const QAgent& b) { return a.id < b.id; });
  for (std::size_t i = 1; i < target.size(); ++i) {
    if (target[i].id == target[i - 1].id) {
      return encodeError("duplicate agent id " + std::to_string(target[i].id), "each agent once per view");
    }
  }

  const std::uint32_t frameNumber = s.next;
  const QView* base = ackedFrame != 0 ? s.find(ackedFrame) : nullptr;
  static const QView kEmpty;
  const QView& b = base ? *base : kEmpty;
  const bool key = base == nullptr;
  const bool animFrame = key || frameNumber % view.animationInterval == 0;
  const bool farFrame = key || frameNumber % o.farInterval == 0;
  const std::uint8_t J = view.jointCount;
  const std::uint8_t shift = o.jointShift;

  Columns c;
  std::vector<std::uint8_t> removals;
  std::size_t removalCount = 0;
  std::uint32_t lastRemoved = 0;
  QView result;
  result.reserve(target.size());
  // Pose table: distinct target poses → index; each entry coded against its first user's base.
  std::map<std::vector<std::uint16_t>, std::uint32_t> poseIndex;
  ByteWriter wIds(c.ids), wTiers(c.tiers), wX(c.xs), wY(c.ys), wZ(c.zs), wYaw(c.yaws), wClip(c.clips),
      wPhase(c.phases), wPose(c.poses), wTable(c.table), wRem(removals);
  std::uint32_t lastRecord = 0;

  std::size_t bi = 0;
  for (const QAgent& t : target) {
    while (bi < b.size() && b[bi].id < t.id) {  // left view
      wRem.varint(removalCount == 0 ? b[bi].id : b[bi].id - lastRemoved - 1);
      lastRemoved = b[bi].id;
      ++removalCount;
      ++bi;
    }
    const bool known = bi < b.size() && b[bi].id == t.id;
    QAgent st = known ? b[bi] : QAgent{};
    if (known) ++bi;
    st.id = t.id;
    if (known && !farFrame && st.tier == Tier::Far && t.tier == Tier::Far) {  // far, not refreshed
      result.push_back(std::move(st));
      continue;
    }
    std::uint8_t mask = 0;
    const bool tierChanged = st.tier != t.tier;
    if (tierChanged) {
      mask |= detail::kMaskTier;
      wTiers.u8(static_cast<std::uint8_t>(t.tier));
    }
    detail::applyTierRules(st, t.tier, J);
    if (t.x != st.x) { mask |= detail::kMaskX; wX.svarint(std::int64_t{t.x} - st.x); st.x = t.x; }
    if (t.y != st.y) { mask |= detail::kMaskY; wY.svarint(std::int64_t{t.y} - st.y); st.y = t.y; }
    if (t.z != st.z) { mask |= detail::kMaskZ; wZ.svarint(std::int64_t{t.z} - st.z); st.z = t.z; }
    if (t.tier != Tier::Far && t.yaw != st.yaw) {
      mask |= detail::kMaskYaw;
      if (t.tier == Tier::Near) {
        wYaw.svarint(wrapDelta(t.yaw, st.yaw, 16));
      } else {
        wYaw.svarint(wrapDelta(t.yaw >> 8, st.yaw >> 8, 8));
      }
      st.yaw = t.yaw;
    }
    const bool refreshAnim = animFrame || !known || tierChanged;
    if (t.tier != Tier::Far && refreshAnim) {
      if (t.clip != st.clip) { mask |= detail::kMaskClip; wClip.varint(t.clip); st.clip = t.clip; }
      if (t.phase != st.phase) { mask |= detail::kMaskPhase; wPhase.svarint(wrapDelta(t.phase, st.phase, 8)); st.phase = t.phase; }
      if (t.tier == Tier::Near && t.joints != st.joints) {
        mask |= detail::kMaskPose;
        auto [it, added] = poseIndex.try_emplace(t.joints, static_cast<std::uint32_t>(poseIndex.size()));
        if (added) {
          const int bits = 16 - shift;
          for (std::size_t j = 0; j < t.joints.size(); ++j) {
            wTable.svarint(wrapDelta(detail::jointUnits(t.joints[j], shift), detail::jointUnits(st.joints[j], shift), bits));
          }
        }
        wPose.varint(it->second);
        st.joints = t.joints;
      }
    }
    if (mask == 0 && known) {  // unchanged: no record
      result.push_back(std::move(st));
      continue;
    }
    wIds.varint(c.records == 0 ? t.id : t.id - lastRecord - 1);
    lastRecord = t.id;
    c.masks.push_back(mask);
    ++c.records;
    result.push_back(std::move(st));
  }
  for (; bi < b.size(); ++bi) {
    wRem.varint(removalCount == 0 ? b[bi].id : b[bi].id - lastRemoved - 1);
    lastRemoved = b[bi].id;
    ++removalCount;
  }

  CrowdFrame frame;
  std::vector<std::uint8_t>& p = frame.payload;
  ByteWriter w(p);
  w.varint(removalCount);
  w.bytes(removals);
  w.varint(c.records);
  for (const auto* col : {&c.ids, &c.masks, &c.tiers, &c.xs, &c.ys, &c.zs, &c.yaws, &c.clips, &c.phases, &c.poses}) {
    w.bytes(*col);
  }
  w.varint(poseIndex.size());
  w.bytes(c.table);

  CrowdFrameHeader& h = frame.header;
  h.frameNumber = frameNumber;
  h.baseFrame = key ? 0 : ackedFrame;
  h.farIncluded = farFrame;
  h.simTick = view.simTick;
  h.animationInterval = view.animationInterval;
  h.jointCount = J;
  h.jointShift = shift;
  for (const QAgent& a : result) {
    (a.tier == Tier::Near ? h.nearCount : a.tier == Tier::Middle ? h.middleCount : h.farCount)++;
  }
  h.payloadSize = static_cast<std::uint32_t>(p.size());
  std::vector<std::uint8_t> compressed;
  if (p.size() >= o.compressMinBytes) {
    compressed = detail::zstdCompress(p, o.compressionLevel);
    h.compressed = !compressed.empty() && compressed.size() < p.size();
  }

  EncodedCrowdFrame out;
  out.bytes = detail::encodeCrowdFrame(frame, h.compressed ? &compressed : nullptr);
  out.header = h;
  out.records = c.records;
  out.removals = removalCount;
  out.poses = poseIndex.size();

  s.history.emplace_back(frameNumber, std::move(result));
  s.jointCounts.push_back(J);
  s.ticks.push_back(view.simTick);
  s.intervals.push_back(view.animationInterval);
  while (s.history.size() > o.historyFrames) {
    s.history.pop_front();
    s.jointCounts.pop_front();
    s.ticks.pop_front();
    s.intervals.pop_front();
  }
  ++s.next;
  return out;
}

}  // namespace throng::protocol
