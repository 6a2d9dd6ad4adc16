// throng::io scenario model parser — a population's "model": the operational (avoidance) model it
// walks with, by name ("orca"), or an object {"name": "orca", <parameters of that model>}. Names and
// parameters (units, limits, defaults) come from the core's catalogue (throng/sim/models.hpp), so
// a new model needs no change here. Reads the JSON value; writes sim::ModelDesc and diagnostics.
// Private to throng_io.
#include <string>
#include <vector>

#include "scenario_reader.hpp"
#include "throng/sim/models.hpp"

namespace throng::io::detail {
namespace {

std::vector<std::string> modelNames() {
  std::vector<std::string> names;
  for (const sim::ModelInfo& m : sim::modelCatalogue()) names.emplace_back(m.name);
  return names;
}

std::string list(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i == 0 ? "" : i + 1 == items.size() ? " or " : ", ") + quote(items[i]);
  return out;
}

/// The model (other than `self`) that has a parameter called `key`, or nullptr.
const sim::ModelInfo* ownerOf(const std::string& key, sim::ModelKind self) {
  for (const sim::ModelInfo& m : sim::modelCatalogue()) {
    if (m.kind == self) continue;
    for (const sim::ModelParameter& p : m.parameters) {
      if (p.key == key) return &m;
    }
  }
  return nullptr;
}

const sim::ModelParameter* parameterOf(const sim::ModelInfo& info, std::string_view key) {
  for (const sim::ModelParameter& p : info.parameters) {
    if (p.key == key) return &p;
  }
  return nullptr;
}

}  // namespace

bool ScenarioReader::readModel(const Json& v, const std::string& ptr, sim::ModelDesc& m) {
  const std::vector<std::string> names = modelNames();
  const std::string expected = "a model name (" + list(names) + ") or {\"name\": ..., <its parameters>}";
  const Json* nameValue = &v;
  std::string namePtr = ptr;
  if (v.is_object()) {
    nameValue = require(v, ptr, "name", "the model's name: " + list(names));
    if (nameValue == nullptr) return false;
    namePtr = ptr + "/name";
  } else if (!v.is_string()) {
    error(ptr, "wrong type: " + describeType(v), expected);
    return false;
  }
  std::size_t index = 0;
  if (!readChoice(*nameValue, namePtr, names, "model", index)) return false;
  const sim::ModelInfo& info = sim::modelCatalogue()[index];
  m = sim::ModelDesc(info.kind);
  if (!v.is_object()) return true;
  std::vector<std::string> keys{"name"};
  for (const sim::ModelParameter& p : info.parameters) keys.emplace_back(p.key);
  bool ok = true;
  for (const auto& [key, value] : v.items()) {
    if (key == "name") continue;
    const std::string kptr = ptr + "/" + escapePointerToken(key);
    if (const sim::ModelParameter* p = parameterOf(info, key)) {
      const Range range{p->min, p->max, p->minExclusive, std::string(p->unit == "1" ? "" : p->unit)};
      double d = 0.0;
      const bool read = p->integer ? readInteger(value, kptr, p->min, p->max, std::string(p->unit), d)
                                   : readNumber(value, kptr, range, d);
      if (read) m.set(key, static_cast<float>(d));
      ok = read && ok;
      continue;
    }
    ok = false;
    std::string parameters;
    for (std::size_t i = 1; i < keys.size(); ++i) parameters += (i == 1 ? "" : ", ") + keys[i];
    const std::string expectedKeys = "one of: " + (parameters.empty() ? std::string("none") : parameters) +
                                     " (the parameters of " + quote(std::string(info.name)) + ")";
    if (const sim::ModelInfo* owner = ownerOf(key, info.kind)) {
      error(kptr, "parameter " + quote(key) + " belongs to model " + quote(std::string(owner->name)) + ", not " +
                      quote(std::string(info.name)),
            expectedKeys, "set \"name\": " + quote(std::string(owner->name)) + " to use it", true);
    } else {
      const std::string match = core::closestMatch(key, keys);
      error(kptr, "unknown parameter " + quote(key) + " of model " + quote(std::string(info.name)), expectedKeys,
            match.empty() ? "" : "did you mean " + quote(match) + "?", true);
    }
  }
  return ok;
}

}  // namespace throng::io::detail
