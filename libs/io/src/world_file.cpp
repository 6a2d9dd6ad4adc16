// throng::io world files — glTF nodes → scenario JSON by the naming rules of docs/world-files.md,
// then the scenario parser and validator; their diagnostics are mapped back from the generated
// document's JSON pointers to the glTF node (and its extras key) they came from. Reads the file
// (gltf_scene) and, through parseScenario, the clips and crowd files it names; writes nothing.
#include "throng/io/world_file.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <limits>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>

#include "gltf_scene.hpp"
#include "throng/core/footprint.hpp"

namespace throng::io {

namespace {

using Json = nlohmann::ordered_json;

enum class Role { None, Walkable, Obstacle, Interest, Action, Exit, Crowd };

const std::vector<std::string> kPrefixes = {"interest", "action", "exit", "crowd"};
const std::vector<std::string> kSurfaceWords = {"walkable", "obstacle"};
/// Scenario keys that come from the nodes, never from the scene's extras.
const std::vector<std::string> kNodeKeys = {"format", "$schema", "walkable", "obstacles", "terrain", "points", "populations"};
/// Walkable triangles whose heights all lie within this band [m] make a flat (one-level) world:
/// the 2D path of walkable/obstacle polygons, exactly as before multi-level worlds.
constexpr double kFlatTolerance = 0.05;

std::string quote(const std::string& s) { return "\"" + s.substr(0, 80) + (s.size() > 80 ? "...\"" : "\""); }

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

/// Where a part of the generated scenario came from.
struct Origin {
  std::string label;            ///< `node 7 "crowd:visitors"`, `scene 0`, ...
  std::set<std::string> extras; ///< top-level keys copied from its extras.throng
  std::string generated;        ///< what the other keys were made from (for the message)
};

class WorldBuilder {
 public:
  WorldBuilder(const std::string& source, core::Diagnostics& diags) : source_(source), diags_(diags) {}

  static bool wantsTriangles(const std::string& name, const std::string& extras) {
    const std::string n = lower(name);
    return n.rfind("walkable", 0) == 0 || n.rfind("obstacle", 0) == 0 || extras.find("walkable") != std::string::npos ||
           extras.find("obstacle") != std::string::npos;
  }

  Json build(const GltfScene& scene) {
    Json root = Json::object();
    root["format"] = "throng/1";
    root["name"] = std::filesystem::path(source_).stem().string();
    readSceneExtras(scene, root);
    // Flat or multi-level: decided by the walkable triangles' heights before any point is read
    // (points and crowds carry heights only on multi-level worlds).
    for (const GltfNode& node : scene.nodes) prescanHeights(node);
    multiLevel_ = maxHeight_ - minHeight_ > kFlatTolerance;
    for (const GltfNode& node : scene.nodes) readNode(node);
    if (walkableNodes_.empty()) {
      error("", "the world has no walkable surface", "a mesh node named \"walkable...\" or with extras {\"throng\": {\"walkable\": true}}");
    }
    if (multiLevel_) {
      root["terrain"] = terrainJson();
      root["points"] = std::move(points_);
      root["populations"] = std::move(populations_);
      return root;
    }
    core::Footprint floor = core::unionOfTriangles(floorTriangles_);
    if (!walkableNodes_.empty() && floor.outer.empty()) {
      error("", "the walkable meshes cover no area on the ground plane", "floor triangles that are not vertical");
    }
    std::string nodes;
    for (const GltfNode* n : walkableNodes_) nodes += (nodes.empty() ? "" : ", ") + std::to_string(n->index);
    Json walkable = Json::array(), obstacles = Json::array();
    for (const core::Polygon& p : floor.outer) {
      origins_["/walkable/" + std::to_string(walkable.size())] = {"walkable surface " + std::to_string(walkable.size()) +
                                                                      " (union of nodes " + nodes + ")", {}, ""};
      walkable.push_back(polygonJson(p));
    }
    for (const core::Polygon& p : floor.holes) {
      origins_["/obstacles/" + std::to_string(obstacles.size())] = {"a hole in the walkable surface (nodes " + nodes + ")", {}, ""};
      obstacles.push_back(polygonJson(p));
    }
    for (const auto& [label, fp] : obstacleFootprints_) {
      for (const core::Polygon& p : fp.outer) {
        origins_["/obstacles/" + std::to_string(obstacles.size())] = {label, {}, "its mesh's footprint"};
        obstacles.push_back(polygonJson(p));
      }
    }
    root["walkable"] = std::move(walkable);
    root["obstacles"] = std::move(obstacles);
    root["points"] = std::move(points_);
    root["populations"] = std::move(populations_);
    return root;
  }

  /// Rewrites a diagnostic of the generated document to name the node it came from.
  void remap(core::Diagnostic& d) const {
    if (d.source != source_) return;
    d.line = d.column = 0;
    const std::string& ptr = d.pointer;
    if (ptr.rfind("/terrain", 0) == 0) {
      d.pointer = terrainOrigin(ptr);
      return;
    }
    const std::pair<const std::string, Origin>* best = nullptr;
    for (const auto& entry : origins_) {
      const std::string& prefix = entry.first;
      if (ptr.compare(0, prefix.size(), prefix) == 0 && (ptr.size() == prefix.size() || ptr[prefix.size()] == '/') &&
          (best == nullptr || prefix.size() > best->first.size())) {
        best = &entry;
      }
    }
    if (best == nullptr) {
      if (!ptr.empty()) {  // a scenario-level key from the scene's extras
        d.pointer = sceneLabel_ + " /extras/throng" + ptr;
      }
      return;
    }
    const std::string rest = ptr.substr(best->first.size());
    const std::string key = rest.empty() ? "" : rest.substr(1, rest.find('/', 1) == std::string::npos ? std::string::npos : rest.find('/', 1) - 1);
    if (!key.empty() && best->second.extras.count(key) != 0) d.pointer = best->second.label + " /extras/throng" + rest;
    else if (!key.empty() && !best->second.generated.empty())
      d.pointer = best->second.label + " (" + key + ": " + best->second.generated + ")";
    else d.pointer = best->second.label;
  }

 private:
  void error(const std::string& where, std::string what, std::string expected, std::string hint = {}) {
    diags_.push_back({source_, 0, 0, where, std::move(what), std::move(expected), std::move(hint)});
  }

  /// A walkable node's triangle heights, before the nodes are read (nodes with a bad role or
  /// mesh are reported by readNode and give no heights).
  void prescanHeights(const GltfNode& n) {
    if (!n.hasMesh || !n.meshProblem.empty()) return;
    const std::string l = lower(n.name);
    bool walkable = l.rfind("walkable", 0) == 0;
    if (!walkable && !n.extrasJson.empty() && n.name.find(':') == std::string::npos) {
      const Json extras = Json::parse(n.extrasJson, nullptr, false);
      walkable = extras.is_object() && extras.contains("throng") && extras["throng"].is_object() &&
                 extras["throng"].value("walkable", false) == true;
    }
    if (!walkable) return;
    for (const auto& tri : n.triangles) {
      for (const Vec3d& v : tri) {
        minHeight_ = std::min(minHeight_, v[1]);
        maxHeight_ = std::max(maxHeight_, v[1]);
      }
    }
  }

  /// Index of a terrain vertex (ground x, y, height z), shared by equal vertices.
  std::uint32_t terrainVertex(const Vec3d& p) {
    const double lim = 1e9;
    const std::array<float, 3> v = {static_cast<float>(std::clamp(p[0], -lim, lim)),
                                     static_cast<float>(std::clamp(-p[2], -lim, lim)),
                                     static_cast<float>(std::clamp(p[1], -lim, lim))};
    const auto [it, fresh] = vertexIndex_.emplace(v, static_cast<std::uint32_t>(vertices_.size()));
    if (fresh) vertices_.push_back(v);
    return it->second;
  }

  /// A node's triangles as terrain triangles (degenerate ones dropped); records which node they came from.
  void addTerrainTriangles(const GltfNode& n, const std::string& label, bool walkable) {
    auto& tris = walkable ? walkTris_ : obstTris_;
    (walkable ? walkOrigins_ : obstOrigins_).emplace_back(tris.size(), label);
    for (const auto& tri : n.triangles) {
      const std::array<std::uint32_t, 3> t = {terrainVertex(tri[0]), terrainVertex(tri[1]), terrainVertex(tri[2])};
      if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2]) continue;
      tris.push_back(t);
    }
  }

  Json terrainJson() const {
    Json vertices = Json::array(), walkable = Json::array(), obstacles = Json::array();
    for (const auto& v : vertices_) vertices.push_back({v[0], v[1], v[2]});
    for (const auto& t : walkTris_) walkable.push_back({t[0], t[1], t[2]});
    for (const auto& t : obstTris_) obstacles.push_back({t[0], t[1], t[2]});
    Json terrain = Json::object();
    terrain["vertices"] = std::move(vertices);
    terrain["walkable"] = std::move(walkable);
    terrain["obstacles"] = std::move(obstacles);
    return terrain;
  }

  /// The node a /terrain pointer's triangle came from ("/terrain/walkable/12" → the 12th walkable
  /// triangle's node); the whole terrain otherwise.
  std::string terrainOrigin(const std::string& ptr) const {
    for (const bool walkable : {true, false}) {
      const std::string prefix = walkable ? "/terrain/walkable/" : "/terrain/obstacles/";
      if (ptr.compare(0, prefix.size(), prefix) != 0) continue;
      const std::size_t index = std::strtoull(ptr.c_str() + prefix.size(), nullptr, 10);
      const auto& origins = walkable ? walkOrigins_ : obstOrigins_;
      std::string label;
      for (const auto& [first, l] : origins) {
        if (first <= index) label = l;
      }
      if (!label.empty()) return label + " (triangle " + std::to_string(index) + " of the terrain)";
    }
    std::string nodes;
    for (const GltfNode* n : walkableNodes_) nodes += (nodes.empty() ? "" : ", ") + std::to_string(n->index);
    return "the terrain (walkable nodes " + nodes + ")" + (ptr == "/terrain" ? "" : " " + ptr);
  }

  static std::string nodeLabel(const GltfNode& n) { return "node " + std::to_string(n.index) + " " + quote(n.name); }

  static Json polygonJson(const core::Polygon& p) {
    Json a = Json::array();
    for (const core::Vec2& v : p) a.push_back({v.x, v.y});
    return a;
  }

  /// The node's extras.throng object (null when absent); false after a diagnostic.
  bool throngExtras(const std::string& json, const std::string& label, Json& out) {
    out = nullptr;
    if (json.empty()) return true;
    Json extras = Json::parse(json, nullptr, false);
    if (extras.is_discarded()) {
      error(label + " /extras", "extras are not valid JSON", "a JSON object");
      return false;
    }
    if (!extras.is_object() || !extras.contains("throng")) return true;
    out = extras["throng"];
    if (!out.is_object()) {
      error(label + " /extras/throng", "wrong type: " + std::string(out.type_name()), "an object of throng properties");
      out = nullptr;
      return false;
    }
    return true;
  }

  void readSceneExtras(const GltfScene& scene, Json& root) {
    sceneLabel_ = scene.sceneIndex >= 0 ? "scene " + std::to_string(scene.sceneIndex) : "the scene";
    Json t;
    if (!throngExtras(scene.sceneExtrasJson, sceneLabel_, t) || t.is_null()) return;
    for (auto& [key, value] : t.items()) {
      if (std::find(kNodeKeys.begin(), kNodeKeys.end(), key) != kNodeKeys.end()) {
        error(sceneLabel_ + " /extras/throng/" + key, "key " + quote(key) + " is not set in a world's scene extras",
              "scenario-level keys only (name, seed, duration, dt, steering, navCellSize, social, timeline)",
              "geometry, points and crowds come from the nodes (docs/world-files.md)");
        continue;
      }
      root[key] = value;
    }
  }

  /// The role a node's name gives it; reports names that look like a misspelt throng name.
  Role roleFromName(const GltfNode& n, bool hasThrong, std::string& id) {
    const std::string label = nodeLabel(n);
    const std::size_t colon = n.name.find(':');
    if (colon != std::string::npos) {
      const std::string prefix = n.name.substr(0, colon);
      id = n.name.substr(colon + 1);
      for (std::size_t i = 0; i < kPrefixes.size(); ++i) {
        if (prefix != kPrefixes[i]) continue;
        if (id.empty()) {
          error(label, "empty id after " + quote(prefix + ":"), "a name " + quote(prefix + ":<id>") + " with a non-empty id");
          return Role::None;
        }
        return static_cast<Role>(static_cast<int>(Role::Interest) + static_cast<int>(i));
      }
      const std::string match = core::closestMatch(prefix, kPrefixes);
      if (!match.empty() || hasThrong) {
        error(label, "unknown node kind " + quote(prefix), "a name starting \"interest:\", \"action:\", \"exit:\" or \"crowd:\"",
              match.empty() ? "" : "did you mean " + quote(match + ":") + "?");
      }
      return Role::None;
    }
    const std::string l = lower(n.name);
    if (l.rfind("walkable", 0) == 0) return Role::Walkable;
    if (l.rfind("obstacle", 0) == 0) return Role::Obstacle;
    std::string word;
    for (const char c : l) {
      if (!std::isalpha(static_cast<unsigned char>(c))) break;
      word += c;
    }
    const std::string match = word.size() >= 6 ? core::closestMatch(word, kSurfaceWords) : "";
    if (!match.empty()) {
      error(label, "name " + quote(n.name) + " looks like a misspelt " + quote(match + "...") + " node",
            "a name starting \"walkable\" or \"obstacle\" (or a name throng ignores)", "did you mean " + quote(match) + "?");
    }
    return Role::None;
  }

  void checkKeys(const Json& t, const std::string& label, const std::vector<std::string>& allowed, const std::string& what) {
    for (const auto& [key, value] : t.items()) {
      if (std::find(allowed.begin(), allowed.end(), key) != allowed.end()) continue;
      std::string list;
      for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
      const std::string match = core::closestMatch(key, allowed);
      error(label + " /extras/throng/" + key, "unknown key " + quote(key) + " for " + what, "one of: " + list,
            match.empty() ? "" : "did you mean " + quote(match) + "?");
    }
  }

  void readNode(const GltfNode& n) {
    const std::string label = nodeLabel(n);
    Json t;
    if (!throngExtras(n.extrasJson, label, t)) return;
    const bool hasThrong = !t.is_null();
    std::string id;
    const Role named = roleFromName(n, hasThrong, id);
    // Surface flags in the extras; contradictions with each other or with the name are errors.
    bool walkFlag = false, obstFlag = false, flagsOk = true;
    for (const char* key : {"walkable", "obstacle"}) {
      if (!hasThrong || !t.contains(key)) continue;
      if (!t[key].is_boolean()) {
        error(label + " /extras/throng/" + key, "wrong type: " + std::string(t[key].type_name()), "true or false");
        flagsOk = false;
        continue;
      }
      (std::string(key) == "walkable" ? walkFlag : obstFlag) = t[key].get<bool>();
      const bool value = t[key].get<bool>();
      const Role flagRole = std::string(key) == "walkable" ? Role::Walkable : Role::Obstacle;
      if (!value && named == flagRole) {
        error(label + " /extras/throng/" + key, "contradictory properties: the name makes it " + std::string(key) +
                                                     " but extras say " + key + ": false",
              "a name and extras that agree");
        flagsOk = false;
      }
      if (value && named != Role::None && named != flagRole) {
        error(label + " /extras/throng/" + key, "contradictory properties: " + std::string(key) + ": true on a node whose name makes it " +
                                                     (named == Role::Walkable ? "walkable" : named == Role::Obstacle ? "an obstacle" : "a point or crowd"),
              "one role per node");
        flagsOk = false;
      }
    }
    if (walkFlag && obstFlag) {
      error(label + " /extras/throng", "contradictory properties: both walkable and obstacle", "one role per node");
      flagsOk = false;
    }
    if (!flagsOk) return;
    Role role = named;
    if (role == Role::None && walkFlag) role = Role::Walkable;
    if (role == Role::None && obstFlag) role = Role::Obstacle;
    switch (role) {
      case Role::None:
        if (hasThrong) {
          error(label + " /extras/throng", "throng properties on a node with no throng role",
                "a name \"walkable...\", \"obstacle...\", \"interest:<id>\", \"action:<id>\", \"exit:<id>\" or \"crowd:<id>\", "
                "or extras {\"throng\": {\"walkable\": true}} / {\"obstacle\": true}");
        }
        return;
      case Role::Walkable:
      case Role::Obstacle: readSurface(n, label, role, hasThrong ? t : Json::object()); return;
      case Role::Crowd: readCrowd(n, label, id, hasThrong ? t : Json::object()); return;
      default: readPoint(n, label, role, id, hasThrong ? t : Json::object()); return;
    }
  }

  void readSurface(const GltfNode& n, const std::string& label, Role role, const Json& t) {
    checkKeys(t, label, {"walkable", "obstacle"}, role == Role::Walkable ? "a walkable mesh" : "an obstacle mesh");
    const char* what = role == Role::Walkable ? "walkable" : "obstacle";
    if (!n.hasMesh) {
      error(label, std::string("a ") + what + " node without a mesh", "a node with a triangle mesh");
      return;
    }
    if (!n.meshProblem.empty()) {
      error(label, "cannot read its mesh: " + n.meshProblem, "triangles with FLOAT VEC3 positions inside their buffers");
      return;
    }
    if (multiLevel_) {
      if (role == Role::Walkable) walkableNodes_.push_back(&n);
      addTerrainTriangles(n, label, role == Role::Walkable);
      return;
    }
    std::vector<std::array<core::Vec2, 3>> tris;
    tris.reserve(n.triangles.size());
    for (const auto& tri : n.triangles) {
      std::array<core::Vec2, 3> t2;
      for (std::size_t k = 0; k < 3; ++k) t2[k] = ground(tri[k]);
      tris.push_back(t2);
    }
    if (role == Role::Walkable) {
      walkableNodes_.push_back(&n);
      floorTriangles_.insert(floorTriangles_.end(), tris.begin(), tris.end());
    } else {
      core::Footprint fp = core::unionOfTriangles(tris);
      if (fp.outer.empty()) error(label, "the obstacle mesh covers no area on the ground plane", "a mesh with a footprint");
      obstacleFootprints_.emplace_back(label, std::move(fp));
    }
  }

  /// glTF is Y-up: ground coordinates are (x, −z); the height y is dropped.
  static core::Vec2 ground(const Vec3d& p) {
    const double lim = 1e9;
    return {static_cast<float>(std::clamp(p[0], -lim, lim)), static_cast<float>(std::clamp(-p[2], -lim, lim))};
  }

  /// The node's position: [x, y] on a flat world, [x, y, height] on a multi-level one.
  Json position(const GltfNode& n) const {
    const core::Vec2 g = ground({n.world[12], n.world[13], n.world[14]});
    if (multiLevel_) return Json::array({g.x, g.y, nodeHeight(n)});
    return Json::array({g.x, g.y});
  }

  /// glTF y of the node's origin: the height of the floor it stands on.
  static float nodeHeight(const GltfNode& n) {
    return static_cast<float>(std::clamp(n.world[13], -1e9, 1e9));
  }

  /// Copies extras keys (except the ones the node itself gives) into `obj`; records the origin.
  Origin copyExtras(const Json& t, const std::string& label, const std::vector<std::string>& fromNode, Json& obj,
                    const std::string& generated) {
    Origin origin{label, {}, generated};
    for (const auto& [key, value] : t.items()) {
      if (std::find(fromNode.begin(), fromNode.end(), key) != fromNode.end()) {
        error(label + " /extras/throng/" + key, "key " + quote(key) + " comes from the node itself",
              "no " + quote(key) + " in the extras", "the id comes from the name, the position from the node's translation");
        continue;
      }
      if (key == "walkable" || key == "obstacle") continue;  // checked (false) by readNode
      obj[key] = value;
      origin.extras.insert(key);
    }
    return origin;
  }

  void readPoint(const GltfNode& n, const std::string& label, Role role, const std::string& id, const Json& t) {
    Json p = Json::object();
    p["id"] = id;
    p["kind"] = role == Role::Action ? "action" : role == Role::Exit ? "exit" : "interest";
    Origin origin = copyExtras(t, label, {"id", "kind", "position"}, p, "the node's name and translation");
    if (!p.contains("polygon")) p["position"] = position(n);
    else if (multiLevel_ && !p.contains("height")) p["height"] = nodeHeight(n);
    if (role == Role::Action && !p.contains("orientation")) {
      // Facing: the node's local +Z axis (glTF's "forward") on the ground.
      const Vec3d f = transformDirection(n.world, {0, 0, 1});
      const double len = std::hypot(f[0], f[2]);
      if (len > 1e-9) p["orientation"] = Json::array({f[0] / len, -f[2] / len});
    }
    origins_["/points/" + std::to_string(points_.size())] = std::move(origin);
    points_.push_back(std::move(p));
  }

  void readCrowd(const GltfNode& n, const std::string& label, const std::string& id, const Json& t) {
    Json pop = Json::object();
    pop["id"] = id;
    Origin origin = copyExtras(t, label, {"id"}, pop, "the node's name and transform");
    if (!pop.contains("spawn")) {
      // The node's unit square (x, z in [-1, 1]) on the ground: scale and rotate the node to shape it.
      Json square = Json::array();
      for (const auto& [x, z] : {std::pair{-1.0, 1.0}, {1.0, 1.0}, {1.0, -1.0}, {-1.0, -1.0}}) {
        const core::Vec2 g = ground(transformPoint(n.world, {x, 0, z}));
        square.push_back({g.x, g.y});
      }
      pop["spawn"] = {{"polygon", std::move(square)}};
      if (multiLevel_) pop["spawn"]["height"] = nodeHeight(n);
    }
    origins_["/populations/" + std::to_string(populations_.size())] = std::move(origin);
    populations_.push_back(std::move(pop));
  }

  const std::string& source_;
  core::Diagnostics& diags_;
  std::string sceneLabel_ = "the scene";
  std::vector<const GltfNode*> walkableNodes_;
  std::vector<std::array<core::Vec2, 3>> floorTriangles_;
  std::vector<std::pair<std::string, core::Footprint>> obstacleFootprints_;
  // Multi-level worlds: walkable heights seen, and the terrain (ground x, y, height z).
  double minHeight_ = std::numeric_limits<double>::infinity();
  double maxHeight_ = -std::numeric_limits<double>::infinity();
  bool multiLevel_ = false;
  std::map<std::array<float, 3>, std::uint32_t> vertexIndex_;
  std::vector<std::array<float, 3>> vertices_;
  std::vector<std::array<std::uint32_t, 3>> walkTris_, obstTris_;
  std::vector<std::pair<std::size_t, std::string>> walkOrigins_, obstOrigins_;  ///< first triangle, node label
  Json points_ = Json::array();
  Json populations_ = Json::array();
  std::map<std::string, Origin> origins_;
};

}  // namespace

bool isWorldFile(std::string_view path) {
  const std::string l = lower(std::string(path));
  auto ends = [&l](const char* ext) {
    const std::size_t n = std::strlen(ext);
    return l.size() >= n && l.compare(l.size() - n, n, ext) == 0;
  };
  return ends(".gltf") || ends(".glb");
}

core::Result<LoadedScenario> parseWorld(std::string_view bytes, const std::string& source, const LoadOptions& options) {
  try {
    core::Diagnostics diags;
    GltfScene scene;
    const std::string baseDir = std::filesystem::path(source).parent_path().string();
    if (!readGltfScene(std::string(bytes), source, baseDir, scene, diags, WorldBuilder::wantsTriangles)) return diags;
    WorldBuilder builder(source, diags);
    const Json root = builder.build(scene);
    if (!diags.empty()) return diags;
    auto loaded = parseScenario(root.dump(1), source, options);
    if (loaded.ok()) return loaded;
    core::Diagnostics errors = loaded.errors();
    for (core::Diagnostic& d : errors) builder.remap(d);
    return errors;
  } catch (const std::exception& e) {
    return core::Diagnostic{source, 0, 0, "", std::string("internal error while loading the world: ") + e.what(), "", ""};
  }
}

core::Result<LoadedScenario> loadWorldFile(const std::string& path, const LoadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    return core::Diagnostic{path, 0, 0, "", std::string("cannot open file: ") + std::strerror(errno), "a readable glTF world file", ""};
  }
  std::ostringstream bytes;
  bytes << in.rdbuf();
  if (in.bad()) return core::Diagnostic{path, 0, 0, "", "cannot read file", "a readable glTF world file", ""};
  return parseWorld(bytes.str(), path, options);
}

}  // namespace throng::io
