// GroupTable (group_table.hpp): adding groups, cold parts, routes and the busy set.
#include "group_table.hpp"

#include <algorithm>

namespace throng::sim {

std::uint32_t GroupTable::add(GroupState g) {
  groups_.push_back(std::move(g));
  return static_cast<std::uint32_t>(groups_.size() - 1);
}

void GroupTable::reserve(std::size_t groups, std::size_t extras) {
  // Exact at start-up (no doubling slack: docs/performance.md, "Memory per agent"); at least
  // doubling afterwards, so many small run-time insertions stay linear.
  const auto grow = [](auto& v, std::size_t n) {
    if (n > v.capacity()) v.reserve(v.empty() ? n : std::max(n, 2 * v.capacity()));
  };
  grow(groups_, groups);
  grow(extras_, extras);
}

void GroupTable::giveExtra(std::uint32_t gid) {
  GroupState& g = groups_[gid];
  if (g.extra != kNoIndex) return;
  g.extra = static_cast<std::uint32_t>(extras_.size());
  extras_.emplace_back();
}

void GroupTable::markBusy(std::uint32_t gid) {
  GroupState& g = groups_[gid];
  if (!g.busy) {
    g.busy = true;
    busyDirty_ = true;
  }
  giveExtra(gid);
}

GroupRoute& GroupTable::routeFor(std::uint32_t gid) {
  markBusy(gid);
  GroupExtra& x = extras_[groups_[gid].extra];
  if (x.route == kNoIndex) {
    x.route = static_cast<std::uint32_t>(routes_.size());
    routes_.emplace_back();
  }
  return routes_[x.route];
}

void GroupTable::refreshBusy() {
  if (!busyDirty_) return;
  busy_.clear();
  for (std::uint32_t gid = 0; gid < groups_.size(); ++gid) {
    if (groups_[gid].busy) busy_.push_back(gid);
  }
  busyDirty_ = false;
}

}  // namespace throng::sim
