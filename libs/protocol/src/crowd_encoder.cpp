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
  /// Keeps what the client will reconstruct from frame `number`, for deltas against it.
  void remember(std::uint32_t number, QView view, const CrowdView& sent) {
    history.emplace_back(number, std::move(view));
    jointCounts.push_back(sent.jointCount);
    ticks.push_back(sent.simTick);
    intervals.push_back(sent.animationInterval);
    while (history.size() > options.historyFrames) {
      history.pop_front();
      jointCounts.pop_front();
      ticks.pop_front();
      intervals.pop_front();
    }
    ++next;
  }
};

namespace {

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


/// The view quantized as the client will reconstruct it, in id order; an error for a view the
/// protocol cannot carry (too many agents or joints, X = 0, an id twice).
core::Result<QView> quantizeView(const CrowdView& view, std::uint8_t jointShift) {
  if (view.agents.size() > kMaxAgents) {
    return encodeError(std::to_string(view.agents.size()) + " agents in view", "at most " + std::to_string(kMaxAgents));
  }
  if (view.jointCount > kMaxJoints) {
    return encodeError("jointCount " + std::to_string(view.jointCount), "at most " + std::to_string(kMaxJoints));
  }
  if (view.animationInterval == 0) return encodeError("animationInterval 0", "X ≥ 1");
  QView target;
  target.reserve(view.agents.size());
  for (const AgentState& a : view.agents) target.push_back(detail::quantizeAgent(a, view.jointCount, jointShift));
  std::sort(target.begin(), target.end(), [](const QAgent& a, const QAgent& b) { return a.id < b.id; });
  for (std::size_t i = 1; i < target.size(); ++i) {
    if (target[i].id == target[i - 1].id) {
      return encodeError("duplicate agent id " + std::to_string(target[i].id), "each agent once per view");
    }
  }
  return target;
}

/// What a frame refreshes: a key frame everything; animation every X-th frame; far agents every
/// farInterval-th.
struct FrameKind {
  bool key = true;
  bool anim = true;
  bool far = true;
  std::uint8_t jointCount = 0;
  std::uint8_t shift = 0;  ///< joint angle precision dropped [bits]
};

/// One payload being written: the removals (ids as gaps), then one record per agent that changed,
/// column by column, and the pose table (distinct target poses, each coded against its first
/// user's base).
class PayloadWriter {
 public:
  explicit PayloadWriter(const FrameKind& kind) : kind_(kind) {}

  /// Agent `id` of the base left the view.
  void removal(std::uint32_t id) {
    ByteWriter(removals_).varint(removalCount_ == 0 ? id : id - lastRemoved_ - 1);
    lastRemoved_ = id;
    ++removalCount_;
  }

  /// Target agent `t` against what the client has (`st`: the base's agent when `known`, else
  /// new); `st` becomes what the client will have. Returns whether a record was written.
  bool agent(const QAgent& t, QAgent& st, bool known) {
    st.id = t.id;
    if (known && !kind_.far && st.tier == Tier::Far && t.tier == Tier::Far) return false;  // far, not refreshed
    const std::uint8_t mask = changes(t, st, known);
    if (mask == 0 && known) return false;  // unchanged: no record
    ByteWriter(ids_).varint(records_ == 0 ? t.id : t.id - lastRecord_ - 1);
    lastRecord_ = t.id;
    masks_.push_back(mask);
    ++records_;
    return true;
  }

  /// The payload: removals, records column by column, the pose table.
  [[nodiscard]] std::vector<std::uint8_t> finish() const {
    std::vector<std::uint8_t> p;
    ByteWriter w(p);
    w.varint(removalCount_);
    w.bytes(removals_);
    w.varint(records_);
    for (const auto* col : {&ids_, &masks_, &tiers_, &xs_, &ys_, &zs_, &yaws_, &clips_, &phases_, &poses_}) w.bytes(*col);
    w.varint(poseIndex_.size());
    w.bytes(table_);
    return p;
  }
  [[nodiscard]] std::size_t records() const { return records_; }
  [[nodiscard]] std::size_t removals() const { return removalCount_; }
  [[nodiscard]] std::size_t poses() const { return poseIndex_.size(); }

 private:
  /// Writes the fields of `t` that differ from `st` into their columns; returns the record's mask.
  std::uint8_t changes(const QAgent& t, QAgent& st, bool known) {
    std::uint8_t mask = 0;
    const bool tierChanged = st.tier != t.tier;
    if (tierChanged) {
      mask |= detail::kMaskTier;
      ByteWriter(tiers_).u8(static_cast<std::uint8_t>(t.tier));
    }
    detail::applyTierRules(st, t.tier, kind_.jointCount);
    if (t.x != st.x) { mask |= detail::kMaskX; ByteWriter(xs_).svarint(std::int64_t{t.x} - st.x); st.x = t.x; }
    if (t.y != st.y) { mask |= detail::kMaskY; ByteWriter(ys_).svarint(std::int64_t{t.y} - st.y); st.y = t.y; }
    if (t.z != st.z) { mask |= detail::kMaskZ; ByteWriter(zs_).svarint(std::int64_t{t.z} - st.z); st.z = t.z; }
    if (t.tier != Tier::Far && t.yaw != st.yaw) {
      mask |= detail::kMaskYaw;
      ByteWriter(yaws_).svarint(t.tier == Tier::Near ? wrapDelta(t.yaw, st.yaw, 16) : wrapDelta(t.yaw >> 8, st.yaw >> 8, 8));
      st.yaw = t.yaw;
    }
    const bool refreshAnim = kind_.anim || !known || tierChanged;
    if (t.tier != Tier::Far && refreshAnim) mask |= animation(t, st);
    return mask;
  }

  /// Clip, phase and (near agents) pose of `t` against `st`; returns their mask bits.
  std::uint8_t animation(const QAgent& t, QAgent& st) {
    std::uint8_t mask = 0;
    if (t.clip != st.clip) { mask |= detail::kMaskClip; ByteWriter(clips_).varint(t.clip); st.clip = t.clip; }
    if (t.phase != st.phase) { mask |= detail::kMaskPhase; ByteWriter(phases_).svarint(wrapDelta(t.phase, st.phase, 8)); st.phase = t.phase; }
    if (t.tier == Tier::Near && t.joints != st.joints) {
      mask |= detail::kMaskPose;
      auto [it, added] = poseIndex_.try_emplace(t.joints, static_cast<std::uint32_t>(poseIndex_.size()));
      if (added) {
        const int bits = 16 - kind_.shift;
        ByteWriter table(table_);
        for (std::size_t j = 0; j < t.joints.size(); ++j) {
          table.svarint(wrapDelta(detail::jointUnits(t.joints[j], kind_.shift), detail::jointUnits(st.joints[j], kind_.shift), bits));
        }
      }
      ByteWriter(poses_).varint(it->second);
      st.joints = t.joints;
    }
    return mask;
  }

  FrameKind kind_;
  std::vector<std::uint8_t> ids_, masks_, tiers_, xs_, ys_, zs_, yaws_, clips_, phases_, poses_, table_, removals_;
  std::map<std::vector<std::uint16_t>, std::uint32_t> poseIndex_;  ///< distinct target poses → index
  std::uint32_t lastRecord_ = 0, lastRemoved_ = 0;
  std::size_t records_ = 0, removalCount_ = 0;
};

/// Walks the target view against the base (both in id order): removals for base agents that left,
/// records for the others; returns what the client will have after the frame.
QView writeAgents(const QView& target, const QView& base, PayloadWriter& writer) {
  QView result;
  result.reserve(target.size());
  std::size_t bi = 0;
  for (const QAgent& t : target) {
    while (bi < base.size() && base[bi].id < t.id) writer.removal(base[bi++].id);  // left view
    const bool known = bi < base.size() && base[bi].id == t.id;
    QAgent st = known ? base[bi] : QAgent{};
    if (known) ++bi;
    writer.agent(t, st, known);
    result.push_back(std::move(st));
  }
  for (; bi < base.size(); ++bi) writer.removal(base[bi].id);
  return result;
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
  auto target = quantizeView(view, o.jointShift);
  if (!target) return std::move(target).takeErrors();

  const std::uint32_t frameNumber = s.next;
  const QView* base = ackedFrame != 0 ? s.find(ackedFrame) : nullptr;
  static const QView kEmpty;
  FrameKind kind;
  kind.key = base == nullptr;
  kind.anim = kind.key || frameNumber % view.animationInterval == 0;
  kind.far = kind.key || frameNumber % o.farInterval == 0;
  kind.jointCount = view.jointCount;
  kind.shift = o.jointShift;
  PayloadWriter writer(kind);
  QView result = writeAgents(target.value(), base ? *base : kEmpty, writer);

  CrowdFrame frame;
  frame.payload = writer.finish();
  const std::vector<std::uint8_t>& p = frame.payload;
  CrowdFrameHeader& h = frame.header;
  h.frameNumber = frameNumber;
  h.baseFrame = kind.key ? 0 : ackedFrame;
  h.farIncluded = kind.far;
  h.simTick = view.simTick;
  h.animationInterval = view.animationInterval;
  h.jointCount = kind.jointCount;
  h.jointShift = kind.shift;
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
  out.records = writer.records();
  out.removals = writer.removals();
  out.poses = writer.poses();
  s.remember(frameNumber, std::move(result), view);
  return out;
}

}  // namespace throng::protocol
