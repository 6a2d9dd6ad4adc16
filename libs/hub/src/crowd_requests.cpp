// Crowd requests (see crowd_requests.hpp): crowd file text → io::parseCrowd against the running
// world → agent limit → World::insertCrowd; removal by id → World::removeCrowd. Reads the world,
// writes its crowd queue; builds the reply texts.
#include "throng/hub/crowd_requests.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "throng/io/crowd_loader.hpp"

namespace throng::hub {
namespace {

CrowdOutcome refused(core::Diagnostics diagnostics, std::string id) {
  CrowdOutcome out;
  out.id = std::move(id);
  out.tooLarge = isAgentLimit(diagnostics);
  out.text = diagnostics.empty() ? std::string("refused") : diagnostics.front().format();
  if (diagnostics.size() > 1) out.text += " (and " + std::to_string(diagnostics.size() - 1) + " more)";
  out.diagnostics = std::move(diagnostics);
  return out;
}

}  // namespace

bool isAgentLimit(const core::Diagnostics& diagnostics) {
  return std::any_of(diagnostics.begin(), diagnostics.end(), [](const core::Diagnostic& d) {
    return d.expected.find("agents per") != std::string::npos || d.what.find("agents per") != std::string::npos ||
           d.expected.find("inserted agents") != std::string::npos;
  });
}

std::string diagnosticsText(const core::Diagnostics& diagnostics, std::size_t maxBytes) {
  const std::size_t n = diagnostics.size();
  auto more = [](std::size_t k) { return "(and " + std::to_string(k) + " more)"; };
  std::string text;
  for (std::size_t i = 0; i < n; ++i) {
    const std::string line = diagnostics[i].format();
    const std::string candidate = text.empty() ? line : text + "\n" + line;
    const std::string suffix = i + 1 < n ? "\n" + more(n - i - 1) : "";
    if (candidate.size() + suffix.size() <= maxBytes) {
      text = candidate;
      continue;
    }
    if (text.empty()) {  // not even the first fits: cut it, keep the count
      const std::string rest = n > 1 ? "\n" + more(n - 1) : "";
      if (rest.size() >= maxBytes) return line.substr(0, maxBytes);
      return line.substr(0, maxBytes - rest.size()) + rest;
    }
    return text + "\n" + more(n - i);  // fits: the previous line was kept with room for it
  }
  return text;
}

CrowdOutcome insertCrowdJson(sim::World& world, std::string_view json, const std::string& source, std::uint64_t maxAgents) {
  auto crowd = io::parseCrowd(json, source, world);
  if (!crowd.ok()) return refused(crowd.errors(), {});
  if (crowd->maxAgents() > maxAgents) {
    core::Diagnostic d;
    d.source = source;
    d.pointer = "/populations";
    d.what = "the crowd may spawn " + std::to_string(crowd->maxAgents()) + " agents (groups × largest group size, summed)";
    d.expected = "at most " + std::to_string(maxAgents) + " agents per crowd insertion on this server";
    d.hint = "split it into several crowds";
    return refused({std::move(d)}, crowd->id);
  }
  auto index = world.insertCrowd(crowd.value());
  if (!index.ok()) return refused(index.errors(), crowd->id);
  CrowdOutcome out;
  out.ok = true;
  out.index = index.value();
  out.id = crowd->id;
  out.maxAgents = crowd->maxAgents();
  out.text = "crowd '" + out.id + "' inserted as " + std::to_string(out.index) + ": " + std::to_string(out.maxAgents) +
             " agents at most, from the next tick";
  return out;
}

CrowdOutcome removeCrowdById(sim::World& world, std::string_view id) {
  CrowdOutcome out;
  out.id = std::string(id);
  const std::vector<sim::CrowdInfo> crowds = world.crowds();
  auto it = std::find_if(crowds.begin(), crowds.end(), [&](const sim::CrowdInfo& c) { return c.id == id; });
  if (it != crowds.end()) out.index = it->index;
  if (it != crowds.end() && !it->removed && world.removeCrowd(id)) {
    out.ok = true;
    out.text = "crowd '" + out.id + "' (" + std::to_string(out.index) + ") removed: its agents leave at the next tick";
    return out;
  }
  core::Diagnostic d;
  d.source = "remove";
  d.pointer = "/crowdId";
  std::vector<std::string> present;
  for (const sim::CrowdInfo& c : crowds) {
    if (!c.removed) present.push_back(c.id);
  }
  if (it != crowds.end()) {
    d.what = "crowd '" + out.id + "' was removed already";
  } else {
    d.what = "no crowd '" + out.id + "' present";
  }
  d.expected = present.empty() ? std::string("the id of an inserted crowd (none is present)")
                                : "the id of a crowd present (" + std::to_string(present.size()) + " present)";
  if (const std::string m = core::closestMatch(out.id, present); !m.empty()) d.hint = "did you mean '" + m + "'?";
  CrowdOutcome r = refused({std::move(d)}, out.id);
  r.index = out.index;
  return r;
}

}  // namespace throng::hub
