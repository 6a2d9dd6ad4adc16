// throng::io::parseCrowd against a running sim::World — its description, its navmesh (reachability)
// and the ids of the crowds it has. Kept apart from crowd_parser.cpp so that the parser alone needs
// no World (the fuzz targets link the parser without the simulation). Reads the World; writes
// nothing.
#include "throng/io/crowd_loader.hpp"

namespace throng::io {

core::Result<sim::CrowdDesc> parseCrowd(std::string_view text, const std::string& source, const sim::World& world) {
  CrowdOptions options;
  // The world outlives this call: a non-owning pointer to its navmesh.
  options.navmesh = std::shared_ptr<const nav::NavMesh>(std::shared_ptr<const nav::NavMesh>(), &world.navMesh());
  for (const sim::CrowdInfo& c : world.crowds()) {
    options.takenCrowdIds.push_back(c.id);
    // Queued crowds' parts are not in desc() yet; applied ones are.
  }
  return parseCrowd(text, source, world.desc(), options);
}

}  // namespace throng::io
