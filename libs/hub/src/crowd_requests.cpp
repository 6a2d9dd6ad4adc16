// Crowd requests (see crowd_requests.hpp): crowd file text → per-request limits → io::parseCrowd
// against the world's description → agent limit → World::insertCrowd; removal by id, by its owner →
// World::removeCrowd. Reads the world, writes its crowd queue; builds the reply texts.
#include "throng/hub/crowd_requests.hpp"

#include <algorithm>
#include <string>
#include <vector>

#include "throng/hub/text.hpp"
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

/// A key as one JSON pointer token ("~" → "~0", "/" → "~1"), printable and at most 64 bytes.
std::string pointerToken(std::string_view key) {
  std::string out;
  for (char ch : key) {
    if (ch == '~') out += "~0";
    else if (ch == '/') out += "~1";
    else out += ch;
  }
  return printable(out, 64);
}

/// The one-pass scanner of checkCrowdLimits: arrays and objects on a stack, values, keys and
/// positions (arrays of numbers only) counted as they come.
class LimitScanner {
 public:
  LimitScanner(std::string_view text, const std::string& source, const CrowdLimits& limits)
      : text_(text), source_(source), limits_(limits) {}

  core::Diagnostics run() {
    const std::size_t n = text_.size();
    std::size_t i = 0;
    while (i < n && problem_.empty()) {
      const char c = text_[i];
      switch (c) {
        case ' ': case '\t': case '\n': case '\r': case ',': case ':':
          ++i;
          break;
        case '{':
        case '[':
          beginValue(i, false);
          if (!problem_.empty()) break;
          if (stack_.size() + 1 > limits_.maxDepth) {
            fail(i, path(stack_.size()), "nesting deeper than " + std::to_string(limits_.maxDepth) + " levels",
                 "at most " + std::to_string(limits_.maxDepth) + " levels of arrays and objects per crowd request");
            break;
          }
          stack_.push_back({c == '[', 0, {}, true, 0, i});
          ++i;
          break;
        case '}':
          if (!stack_.empty() && !stack_.back().array) stack_.pop_back();
          ++i;
          break;
        case ']':
          if (!stack_.empty() && stack_.back().array) endArray();
          ++i;
          break;
        case '"': {
          std::size_t j = i + 1;
          while (j < n && text_[j] != '"') j += text_[j] == '\\' ? 2 : 1;
          const std::string_view body = text_.substr(i + 1, std::min(j, n) - i - 1);
          std::size_t k = j + 1;
          while (k < n && (text_[k] == ' ' || text_[k] == '\t' || text_[k] == '\n' || text_[k] == '\r')) ++k;
          if (k < n && text_[k] == ':' && !stack_.empty() && !stack_.back().array) {
            stack_.back().key = pointerToken(body.substr(0, 256));
            if (++keys_ > limits_.maxKeys) {
              fail(i, path(stack_.size()), "more than " + std::to_string(limits_.maxKeys) + " object keys",
                   "at most " + std::to_string(limits_.maxKeys) + " keys per crowd request (all objects together)");
            }
          } else {
            beginValue(i, false);
          }
          i = j + 1;
          break;
        }
        default: {
          beginValue(i, c == '-' || (c >= '0' && c <= '9'));
          while (i < n && std::string_view(" \t\n\r,:]}[{\"").find(text_[i]) == std::string_view::npos) ++i;
          break;
        }
      }
    }
    return std::move(problem_);
  }

 private:
  struct Frame {
    bool array = false;
    std::size_t count = 0;   ///< elements so far (arrays)
    std::string key;         ///< the current key (objects)
    bool numbers = true;     ///< only numbers so far (arrays): a position when it closes
    std::size_t positions = 0;  ///< positions among its elements (arrays)
    std::size_t start = 0;      ///< where it opened (its offset in the text)
  };

  /// The JSON pointer of the value being read in frame `depth - 1` (its current element or key).
  std::string path(std::size_t depth) const {
    std::string out;
    for (std::size_t k = 0; k < depth && k < stack_.size(); ++k) {
      const Frame& f = stack_[k];
      out += "/" + (f.array ? std::to_string(f.count == 0 ? 0 : f.count - 1) : f.key);
    }
    return out;
  }

  void beginValue(std::size_t at, bool number) {
    if (++values_ > limits_.maxValues) {
      if (!stack_.empty() && stack_.back().array) ++stack_.back().count;
      fail(at, path(stack_.size()), "more than " + std::to_string(limits_.maxValues) + " values",
           "at most " + std::to_string(limits_.maxValues) + " values (numbers, strings, arrays, objects) per crowd request");
      return;
    }
    if (stack_.empty() || !stack_.back().array) return;
    Frame& f = stack_.back();
    ++f.count;
    if (!number) f.numbers = false;
  }

  void endArray() {
    const Frame done = std::move(stack_.back());
    stack_.pop_back();
    if (done.count == 0 || !done.numbers) return;
    // A position ([x, y] or [x, y, z]): count it in the request and in the array holding it.
    const std::string where = path(stack_.size());
    const std::size_t at = done.start;
    if (++vertices_ > limits_.maxVertices) {
      fail(at, where, "more than " + std::to_string(limits_.maxVertices) + " positions",
           "at most " + std::to_string(limits_.maxVertices) + " positions (polygon vertices, points) per crowd request");
      return;
    }
    if (stack_.empty() || !stack_.back().array) return;
    if (++stack_.back().positions > limits_.maxPolygonVertices) {
      fail(at, where, "a polygon of more than " + std::to_string(limits_.maxPolygonVertices) + " vertices",
           "at most " + std::to_string(limits_.maxPolygonVertices) + " vertices per polygon in a crowd request",
           "simplify the polygon, or split it into several");
    }
  }

  void fail(std::size_t at, std::string pointer, std::string what, std::string expected, std::string hint = "") {
    int line = 1, column = 1;
    for (std::size_t k = 0; k < at && k < text_.size(); ++k) {
      const auto ch = static_cast<unsigned char>(text_[k]);
      if (ch == '\n') {
        ++line;
        column = 1;
      } else if ((ch & 0xC0u) != 0x80u) {
        ++column;
      }
    }
    problem_.push_back({source_, line, column, std::move(pointer), std::move(what), std::move(expected) + " (server limit)",
                        std::move(hint)});
  }

  std::string_view text_;
  const std::string& source_;
  const CrowdLimits& limits_;
  std::vector<Frame> stack_;
  std::size_t keys_ = 0, values_ = 0, vertices_ = 0;
  core::Diagnostics problem_;
};

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
    // Whatever a diagnostic quotes from the request, it goes back printable and valid UTF-8.
    const std::string line = printable(diagnostics[i].format(), maxBytes);
    const std::string candidate = text.empty() ? line : text + "\n" + line;
    const std::string suffix = i + 1 < n ? "\n" + more(n - i - 1) : "";
    if (candidate.size() + suffix.size() <= maxBytes) {
      text = candidate;
      continue;
    }
    if (text.empty()) {  // not even the first fits: cut it, keep the count
      const std::string rest = n > 1 ? "\n" + more(n - 1) : "";
      if (rest.size() >= maxBytes) return std::string(cutUtf8(line, maxBytes));
      return std::string(cutUtf8(line, maxBytes - rest.size())) + rest;
    }
    return text + "\n" + more(n - i);  // fits: the previous line was kept with room for it
  }
  return text;
}

core::Diagnostics checkCrowdLimits(std::string_view json, const std::string& source, const CrowdLimits& limits) {
  if (json.size() > limits.maxBytes) {
    return {{source, 0, 0, "", "the crowd file is " + std::to_string(json.size()) + " bytes",
             "at most " + std::to_string(limits.maxBytes) + " bytes per crowd request (server limit)", ""}};
  }
  if (const auto bad = invalidUtf8At(json)) {
    int line = 1, column = 1;
    for (std::size_t k = 0; k < *bad; ++k) {
      const auto ch = static_cast<unsigned char>(json[k]);
      if (ch == '\n') {
        ++line;
        column = 1;
      } else if ((ch & 0xC0u) != 0x80u) {
        ++column;
      }
    }
    return {{source, line, column, "", "not UTF-8: " + describeByte(json, *bad), "UTF-8 text (a crowd file is JSON)", ""}};
  }
  return LimitScanner(json, source, limits).run();
}

ParsedCrowd parseCrowdRequest(std::string_view json, const std::string& source, const sim::ScenarioDesc& world,
                              const io::CrowdOptions& options, std::uint64_t maxAgents, const CrowdLimits& limits) {
  ParsedCrowd out;
  if (core::Diagnostics over = checkCrowdLimits(json, source, limits); !over.empty()) {
    out.refusal = refused(std::move(over), {});
    return out;
  }
  auto crowd = io::parseCrowd(json, source, world, options);
  if (!crowd.ok()) {
    out.refusal = refused(crowd.errors(), {});
    return out;
  }
  if (crowd->maxAgents() > maxAgents) {
    core::Diagnostic d;
    d.source = source;
    d.pointer = "/populations";
    d.what = "the crowd may spawn " + std::to_string(crowd->maxAgents()) + " agents (groups × largest group size, summed)";
    d.expected = "at most " + std::to_string(maxAgents) + " agents per crowd insertion on this server";
    d.hint = "split it into several crowds";
    out.refusal = refused({std::move(d)}, crowd->id);
    return out;
  }
  out.crowd.emplace(std::move(crowd).value());
  return out;
}

CrowdOutcome queueCrowd(sim::World& world, const sim::CrowdDesc& crowd) {
  auto index = world.insertCrowd(crowd);
  if (!index.ok()) return refused(index.errors(), crowd.id);
  CrowdOutcome out;
  out.ok = true;
  out.index = index.value();
  out.id = crowd.id;
  out.maxAgents = crowd.maxAgents();
  out.text = "crowd '" + printable(out.id, 64) + "' inserted as " + std::to_string(out.index) + ": " +
             std::to_string(out.maxAgents) + " agents at most, from the next tick";
  return out;
}

CrowdOutcome insertCrowdJson(sim::World& world, std::string_view json, const std::string& source, std::uint64_t maxAgents,
                             const CrowdLimits& limits) {
  io::CrowdOptions options;
  // The world outlives this call: a non-owning pointer to its navmesh (as io::parseCrowd(World) does).
  options.navmesh = std::shared_ptr<const nav::NavMesh>(std::shared_ptr<const nav::NavMesh>(), &world.navMesh());
  for (const sim::CrowdInfo& c : world.crowds()) options.takenCrowdIds.push_back(c.id);
  ParsedCrowd parsed = parseCrowdRequest(json, source, world.desc(), options, maxAgents, limits);
  if (!parsed.crowd) return std::move(parsed.refusal);
  return queueCrowd(world, *parsed.crowd);
}

void CrowdOwners::add(const std::string& id, std::uint32_t participant, const std::string& name) {
  owners_[id] = {participant, name};
}

std::optional<std::uint32_t> CrowdOwners::owner(std::string_view id) const {
  const auto it = owners_.find(id);
  if (it == owners_.end()) return std::nullopt;
  return it->second.first;
}

std::optional<core::Diagnostic> CrowdOwners::refusal(std::string_view id, std::uint32_t participant) const {
  const auto it = owners_.find(id);
  if (it != owners_.end() && it->second.first == participant) return std::nullopt;
  core::Diagnostic d;
  d.source = "remove";
  d.pointer = "/crowdId";
  if (it == owners_.end()) {
    d.what = "crowd '" + printable(id, 64) + "' belongs to the scenario (its timeline inserted it)";
  } else {
    d.what = "crowd '" + printable(id, 64) + "' belongs to participant " + std::to_string(it->second.first) +
             (it->second.second.empty() ? std::string() : " ('" + printable(it->second.second, 64) + "')");
  }
  d.expected = "the id of a crowd this participant inserted (a crowd is removed only by whoever inserted it)";
  return d;
}

CrowdOutcome removeCrowdById(sim::World& world, std::string_view id, const CrowdOwners* owners, std::uint32_t participant) {
  CrowdOutcome out;
  out.id = std::string(id);
  const std::vector<sim::CrowdInfo> crowds = world.crowds();
  auto it = std::find_if(crowds.begin(), crowds.end(), [&](const sim::CrowdInfo& c) { return c.id == id; });
  if (it != crowds.end()) out.index = it->index;
  if (it != crowds.end() && !it->removed && owners != nullptr) {
    if (auto why = owners->refusal(id, participant)) {
      CrowdOutcome r = refused({std::move(*why)}, out.id);
      r.index = out.index;
      return r;
    }
  }
  if (it != crowds.end() && !it->removed && world.removeCrowd(id)) {
    out.ok = true;
    out.text = "crowd '" + printable(out.id, 64) + "' (" + std::to_string(out.index) + ") removed: its agents leave at the next tick";
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
    d.what = "crowd '" + printable(out.id, 64) + "' was removed already";
  } else {
    d.what = "no crowd '" + printable(out.id, 64) + "' present";
  }
  d.expected = present.empty() ? std::string("the id of an inserted crowd (none is present)")
                                : "the id of a crowd present (" + std::to_string(present.size()) + " present)";
  if (const std::string m = core::closestMatch(out.id, present); !m.empty()) d.hint = "did you mean '" + printable(m, 64) + "'?";
  CrowdOutcome r = refused({std::move(d)}, out.id);
  r.index = out.index;
  return r;
}

}  // namespace throng::hub
