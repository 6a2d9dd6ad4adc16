// A hand-built world for GoalWriter and the group pass's steps (goals_test.cpp,
// group_pass_test.cpp): a 20 × 10 m room with two interest points (discs of 3 m at x = 5 and
// x = 15), one population visiting them in order, group 0 holding `rows` agents standing at
// (10, 5) with stable ids equal to their rows.
#pragma once
#include <gtest/gtest.h>

#include <memory>
#include <numeric>
#include <vector>

#include "goals.hpp"
#include "throng/nav/navmesh.hpp"

namespace throng::sim::test {

inline core::Polygon rect(float x0, float y0, float x1, float y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

struct GoalWorld {
  ScenarioDesc desc;
  GroupTable groups;
  std::vector<std::vector<std::uint32_t>> goalLists{{0, 1}};
  PointRegions regions;
  OpenChoices choices;
  AgentStore agents;
  std::vector<std::uint32_t> rowOfId;
  std::shared_ptr<const nav::NavMesh> mesh;
  std::unique_ptr<nav::NavQuery> query;
  std::vector<Event> events;

  /// `commonGround`: the agents have the Common Ground columns.
  explicit GoalWorld(std::size_t rows, bool commonGround = false) {
    agents.commonGround = commonGround;
    for (const float x : {5.0f, 15.0f}) {
      PointDesc p;
      p.position = {x, 5.0f};
      p.radius = 3.0f;
      desc.points.push_back(p);
      regions.add(p);
    }
    desc.populations.emplace_back();
    desc.populations[0].goals = {0, 1};
    GroupState g;
    g.expected = static_cast<std::uint32_t>(rows);
    groups.add(g);
    for (std::size_t i = 0; i < rows; ++i) {
      const std::size_t r = agents.addRow();
      agents.id[r] = static_cast<std::uint32_t>(r);
      agents.posX[r] = 10.0f;
      agents.posY[r] = 5.0f;
      agents.targetSub[r] = -1;
      if (commonGround) {
        agents.coordination[r] = kNoIndex;
        agents.desirePoint[r] = kNoPoint;
        agents.scriptClip[r] = kNoClip;
      }
      groups[0].members.push_back(agents.id[r]);
      rowOfId.push_back(static_cast<std::uint32_t>(r));
    }
    if (rows > 0) groups[0].leader = 0;
    auto built = nav::NavMesh::build(std::vector<core::Polygon>{rect(0, 0, 20, 10)}, {}, nav::NavMeshConfig{});
    EXPECT_TRUE(built.ok());
    mesh = std::move(built.value());
    query = std::make_unique<nav::NavQuery>(mesh);
  }
  [[nodiscard]] GoalWriter writer() { return {desc, groups, goalLists, regions, choices, agents, *query, 3, events}; }
  /// Agents targeting a sub-region of `point`.
  [[nodiscard]] std::uint32_t occupied(std::uint32_t point) const {
    return std::accumulate(regions.occupancy.begin() + regions.subOffset[point],
                           regions.occupancy.begin() + regions.subOffset[point + 1], 0u);
  }
};

}  // namespace throng::sim::test
