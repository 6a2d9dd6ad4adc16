// throng::sim::Frame — an immutable snapshot the `emit` phase publishes. Consumers (the recorder
// on its own thread, the server, the CLI's progress bar) read frames and never touch the World.
// Agents are named by stable spawn-order ids (0, 1, 2 … in spawn order), never by row or slot.
#pragma once
#include <cstdint>
#include <memory>
#include <vector>

namespace throng::sim {

/// What an agent is doing, as the animation layer would play it.
enum class AgentMode : std::uint8_t {
  Walking = 0,
  Waiting = 1,  ///< standing (no path yet, or nothing to do)
  Acting = 2,   ///< stopped at an action point, playing its action
};

enum class EventKind : std::uint8_t {
  Spawn = 0,        ///< a = population index, b = group id
  Exit = 1,         ///< a = exit point index
  GoalReached = 2,  ///< a = point index
  ActionStart = 3,  ///< a = point index
  ActionEnd = 4,    ///< a = point index
  PathPartial = 5,  ///< a = point index the agent could not fully reach; it walks to the closest point
  GroupWaitStart = 6,  ///< first member of a group arrived and waits; a = point, b = group
  GroupRelease = 7,    ///< every member arrived, the group goes on; a = point, b = group
  GroupTimeout = 8,    ///< the wait timed out, present members go on; a = point, b = members missing
  FollowStart = 9,     ///< agent = leader of the following group; a = following group, b = followed group
  FollowEnd = 10,      ///< a = following group, b = followed group
  GuideStart = 11,     ///< agent = the group's leader; a = group
  GuideEnd = 12,       ///< a = group
  JoinGroup = 13,      ///< sociological: agent changed group; a = old group, b = new group
  FollowAgent = 14,    ///< sociological: agent follows another agent for a while; a = that agent's id
  FollowAgentEnd = 15, ///< a = the agent it followed
  LeaderChange = 16,   ///< agent = new leader; a = group
  PathFallback = 17,   ///< no valid Bézier curve: the navmesh path is used; a = point index
};

struct Event {
  std::uint64_t tick = 0;
  std::uint32_t agent = 0;  ///< stable id
  EventKind kind = EventKind::Spawn;
  std::uint32_t a = 0;
  std::uint32_t b = 0;
};

struct Frame {
  std::uint64_t tick = 0;
  double time = 0.0;  ///< tick * dt [s]
  std::vector<std::uint32_t> ids;  ///< stable ids of the agents present, ascending
  std::vector<float> posX, posY;   ///< [m]
  std::vector<float> velX, velY;   ///< [m/s]
  std::vector<float> oriX, oriY;   ///< unit heading
  std::vector<AgentMode> mode;
  std::vector<std::uint16_t> clip; ///< motion clip playing: index into animationClips(scenario)
  std::vector<float> phase;        ///< position in that clip, [0, 1)
  std::vector<Event> events;       ///< everything that happened since the previous frame, in order

  [[nodiscard]] std::size_t size() const { return ids.size(); }
};

using FramePtr = std::shared_ptr<const Frame>;

}  // namespace throng::sim
