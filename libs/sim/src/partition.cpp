// partition — the steer phase shared between copies of one world (partition.hpp). Reads the
// agents' positions and the previous owners; writes the strip cuts, this tick's owner of every
// row, and, after the exchange, the steer outputs (prefVel, newVel, corner index, holdHeading, lookTurn) of the rows
// other ranks own. Every rank computes the same owners from the same replicated state, so the
// blocks carry no ids: rank q's block holds the records of q's rows in ascending row order.
#include <algorithm>
#include <cstring>

#include "throng/core/assert.hpp"
#include "world_impl.hpp"

namespace throng::sim {
namespace {

constexpr std::uint16_t kNoOwner = 0xffff;

}  // namespace

void World::setPartition(StepExchange* exchange, PartitionOptions options) {
  Impl& w = *impl_;
  w.partition.exchange = exchange;
  w.partition.options = options;
  w.partition.options.rebalanceTicks = std::max<std::uint32_t>(1, options.rebalanceTicks);
  w.partition.stats = {};
  w.partition.stats.ranks = exchange != nullptr ? exchange->ranks() : 1;
  w.partition.cuts.clear();
  w.partition.ownerOfId.clear();
  if (exchange != nullptr) THRONG_ASSERT(exchange->ranks() >= 1 && exchange->ranks() < kNoOwner && exchange->rank() < exchange->ranks());
}

const PartitionStats& World::partitionStats() const { return impl_->partition.stats; }

void World::Impl::assignOwners() {
  const std::uint32_t ranks = partition.exchange->ranks();
  const std::uint32_t me = partition.exchange->rank();
  const std::size_t n = agents.size();
  // Cuts at the quantiles of x: every strip gets n / ranks agents (ties go to the upper strip).
  const bool rebalance = partition.cuts.size() + 1 != ranks || partition.stats.ticks % partition.options.rebalanceTicks == 0;
  if (rebalance) {
    partition.cuts.assign(ranks - 1, 0.0f);
    if (n > 0) {
      std::vector<float> xs(agents.posX.begin(), agents.posX.end());
      auto from = xs.begin();
      for (std::uint32_t r = 1; r < ranks; ++r) {
        // Non-decreasing in r, and nth_element leaves [at, end) >= *at: the next search starts there.
        const auto at = xs.begin() + static_cast<std::ptrdiff_t>(static_cast<std::uint64_t>(r) * n / ranks);
        std::nth_element(from, at, xs.end());
        partition.cuts[r - 1] = *at;
        from = at;
      }
    }
  }
  if (partition.ownerOfId.size() < spawner.nextAgentId()) partition.ownerOfId.resize(spawner.nextAgentId(), kNoOwner);
  partition.rowOwner.resize(n);
  partition.ownedRows.clear();
  for (std::size_t row = 0; row < n; ++row) {
    const auto owner = static_cast<std::uint16_t>(std::upper_bound(partition.cuts.begin(), partition.cuts.end(), agents.posX[row]) - partition.cuts.begin());
    partition.rowOwner[row] = owner;
    if (owner == me) partition.ownedRows.push_back(static_cast<std::uint32_t>(row));
    std::uint16_t& previous = partition.ownerOfId[agents.id[row]];
    if (previous != kNoOwner && previous != owner) ++(rebalance ? partition.stats.rebalanceMoves : partition.stats.migrations);
    previous = owner;
  }
  ++partition.stats.ticks;
  partition.stats.agentSteps += n;
  partition.stats.ownedAgentSteps += partition.ownedRows.size();
}

void World::Impl::exchangeSteer() {
  const std::uint32_t ranks = partition.exchange->ranks();
  const std::uint32_t me = partition.exchange->rank();
  // Pack: prefVelX, prefVelY, newVelX, newVelY, corner index, holdHeading, lookTurn, per owned row in row order.
  partition.steerSend.resize(partition.ownedRows.size() * kSteerRecordBytes);
  std::byte* out = partition.steerSend.data();
  for (const std::uint32_t row : partition.ownedRows) {
    const float v[4] = {agents.prefVelX[row], agents.prefVelY[row], agents.newVelX[row], agents.newVelY[row]};
    std::memcpy(out, v, sizeof v);
    std::memcpy(out + sizeof v, &agents.corners[row].index, sizeof(std::uint32_t));
    out[sizeof v + sizeof(std::uint32_t)] = static_cast<std::byte>(agents.holdHeading[row]);
    out[sizeof v + sizeof(std::uint32_t) + 1] = static_cast<std::byte>(agents.lookTurn[row]);
    out += kSteerRecordBytes;
  }
  partition.steerSizes.assign(ranks, 0);
  for (const std::uint16_t owner : partition.rowOwner) partition.steerSizes[owner] += kSteerRecordBytes;
  THRONG_ASSERT(partition.steerSizes[me] == partition.steerSend.size());
  partition.exchange->allGather(partition.steerSend, partition.steerSizes, partition.steerGathered);
  partition.stats.sentBytes += partition.steerSend.size();
  partition.stats.gatheredBytes += partition.steerGathered.size();

  // Unpack every other rank's block: its rows are the rows it owns, in row order.
  std::vector<const std::byte*> cursor(ranks);
  std::vector<const std::byte*> blockEnd(ranks);
  const std::byte* at = partition.steerGathered.data();
  for (std::uint32_t r = 0; r < ranks; ++r) {
    cursor[r] = at;
    at += partition.steerSizes[r];
    blockEnd[r] = at;
  }
  THRONG_ASSERT(partition.steerGathered.size() == static_cast<std::size_t>(at - partition.steerGathered.data()));
  for (std::size_t row = 0; row < partition.rowOwner.size(); ++row) {
    const std::uint16_t owner = partition.rowOwner[row];
    if (owner == me) continue;
    const std::byte* in = cursor[owner];
    THRONG_ASSERT(in + kSteerRecordBytes <= blockEnd[owner]);  // the ranks disagree on the owners
    float v[4];
    std::memcpy(v, in, sizeof v);
    agents.prefVelX[row] = v[0];
    agents.prefVelY[row] = v[1];
    agents.newVelX[row] = v[2];
    agents.newVelY[row] = v[3];
    std::memcpy(&agents.corners[row].index, in + sizeof v, sizeof(std::uint32_t));
    agents.holdHeading[row] = static_cast<std::uint8_t>(in[sizeof v + sizeof(std::uint32_t)]);
    agents.lookTurn[row] = static_cast<std::int8_t>(in[sizeof v + sizeof(std::uint32_t) + 1]);
    cursor[owner] = in + kSteerRecordBytes;
  }
  for (std::uint32_t r = 0; r < ranks; ++r) THRONG_ASSERT(r == me || cursor[r] == blockEnd[r]);
}

}  // namespace throng::sim
