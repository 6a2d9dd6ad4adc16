// throng::io glTF scene reading — tinygltf model → GltfScene (gltf_scene.hpp): node world
// transforms (matrix or translation/rotation/scale), extras as JSON text, triangles of every
// triangle primitive (lists, strips, fans; indexed or not), each accessor read with bounds checks.
// The one translation unit that compiles tinygltf's implementation, without its image support.
#define TINYGLTF_IMPLEMENTATION
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_EXTERNAL_IMAGE
#include <tiny_gltf.h>

#include "gltf_scene.hpp"

#include "confined_path.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <filesystem>
#include <functional>

namespace throng::io {

namespace {

constexpr Mat4d kIdentity{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

Mat4d multiply(const Mat4d& a, const Mat4d& b) {
  Mat4d r{};
  for (int c = 0; c < 4; ++c) {
    for (int row = 0; row < 4; ++row) {
      double s = 0;
      for (int k = 0; k < 4; ++k) s += a[static_cast<std::size_t>(k * 4 + row)] * b[static_cast<std::size_t>(c * 4 + k)];
      r[static_cast<std::size_t>(c * 4 + row)] = s;
    }
  }
  return r;
}

Mat4d localMatrix(const tinygltf::Node& n) {
  if (n.matrix.size() == 16) {
    Mat4d m{};
    for (std::size_t i = 0; i < 16; ++i) m[i] = n.matrix[i];
    return m;
  }
  Mat4d m = kIdentity;
  double qx = 0, qy = 0, qz = 0, qw = 1;
  if (n.rotation.size() == 4) {
    qx = n.rotation[0], qy = n.rotation[1], qz = n.rotation[2], qw = n.rotation[3];
    const double len = std::sqrt(qx * qx + qy * qy + qz * qz + qw * qw);
    if (len > 1e-12 && std::isfinite(len)) qx /= len, qy /= len, qz /= len, qw /= len;
    else qx = qy = qz = 0, qw = 1;
  }
  // Rotation matrix columns (column-major).
  m[0] = 1 - 2 * (qy * qy + qz * qz), m[1] = 2 * (qx * qy + qz * qw), m[2] = 2 * (qx * qz - qy * qw);
  m[4] = 2 * (qx * qy - qz * qw), m[5] = 1 - 2 * (qx * qx + qz * qz), m[6] = 2 * (qy * qz + qx * qw);
  m[8] = 2 * (qx * qz + qy * qw), m[9] = 2 * (qy * qz - qx * qw), m[10] = 1 - 2 * (qx * qx + qy * qy);
  if (n.scale.size() == 3) {
    for (int c = 0; c < 3; ++c) {
      for (int r = 0; r < 3; ++r) m[static_cast<std::size_t>(c * 4 + r)] *= n.scale[static_cast<std::size_t>(c)];
    }
  }
  if (n.translation.size() == 3) m[12] = n.translation[0], m[13] = n.translation[1], m[14] = n.translation[2];
  return m;
}

/// Byte span of element `i` of an accessor, or nullptr when outside its buffer.
const unsigned char* element(const tinygltf::Model& model, const tinygltf::Accessor& acc, std::size_t i,
                             std::size_t elementSize, std::string& problem) {
  if (acc.bufferView < 0 || static_cast<std::size_t>(acc.bufferView) >= model.bufferViews.size()) {
    problem = "accessor without a valid bufferView";
    return nullptr;
  }
  const tinygltf::BufferView& view = model.bufferViews[static_cast<std::size_t>(acc.bufferView)];
  if (view.buffer < 0 || static_cast<std::size_t>(view.buffer) >= model.buffers.size()) {
    problem = "bufferView without a valid buffer";
    return nullptr;
  }
  const std::vector<unsigned char>& data = model.buffers[static_cast<std::size_t>(view.buffer)].data;
  const std::size_t stride = view.byteStride != 0 ? view.byteStride : elementSize;
  const std::size_t start = view.byteOffset + acc.byteOffset + i * stride;
  if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset ||
      acc.byteOffset + i * stride + elementSize > view.byteLength || start + elementSize > data.size()) {
    problem = "accessor data outside its buffer";
    return nullptr;
  }
  return data.data() + start;
}

bool readPositions(const tinygltf::Model& model, int index, std::vector<Vec3d>& out, std::string& problem) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
    problem = "POSITION accessor index out of range";
    return false;
  }
  const tinygltf::Accessor& acc = model.accessors[static_cast<std::size_t>(index)];
  if (acc.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT || acc.type != TINYGLTF_TYPE_VEC3 || acc.sparse.isSparse) {
    problem = "POSITION must be a non-sparse VEC3 of FLOAT";
    return false;
  }
  if (acc.count > kMaxWorldTriangles * 3) {
    problem = "too many vertices";
    return false;
  }
  out.resize(acc.count);
  for (std::size_t i = 0; i < acc.count; ++i) {
    const unsigned char* p = element(model, acc, i, 12, problem);
    if (p == nullptr) return false;
    float f[3];
    std::memcpy(f, p, 12);
    if (!std::isfinite(f[0]) || !std::isfinite(f[1]) || !std::isfinite(f[2])) {
      problem = "non-finite vertex position";
      return false;
    }
    out[i] = {f[0], f[1], f[2]};
  }
  return true;
}

bool readIndices(const tinygltf::Model& model, int index, std::vector<std::uint32_t>& out, std::string& problem) {
  if (index < 0 || static_cast<std::size_t>(index) >= model.accessors.size()) {
    problem = "indices accessor index out of range";
    return false;
  }
  const tinygltf::Accessor& acc = model.accessors[static_cast<std::size_t>(index)];
  std::size_t size = 0;
  switch (acc.componentType) {
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: size = 1; break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: size = 2; break;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: size = 4; break;
    default: problem = "indices must be unsigned bytes, shorts or ints"; return false;
  }
  if (acc.type != TINYGLTF_TYPE_SCALAR || acc.sparse.isSparse || acc.count > kMaxWorldTriangles * 3) {
    problem = "indices must be a non-sparse SCALAR accessor of at most " + std::to_string(kMaxWorldTriangles * 3) + " entries";
    return false;
  }
  out.resize(acc.count);
  for (std::size_t i = 0; i < acc.count; ++i) {
    const unsigned char* p = element(model, acc, i, size, problem);
    if (p == nullptr) return false;
    if (size == 1) out[i] = *p;
    else if (size == 2) {
      std::uint16_t v;
      std::memcpy(&v, p, 2);
      out[i] = v;
    } else std::memcpy(&out[i], p, 4);
  }
  return true;
}

/// Appends the world-space triangles of a mesh; false (with `problem`) when it cannot be read.
bool meshTriangles(const tinygltf::Model& model, int meshIndex, const Mat4d& world, std::size_t& budget,
                   std::vector<std::array<Vec3d, 3>>& out, std::string& problem) {
  if (meshIndex < 0 || static_cast<std::size_t>(meshIndex) >= model.meshes.size()) {
    problem = "mesh index out of range";
    return false;
  }
  for (const tinygltf::Primitive& prim : model.meshes[static_cast<std::size_t>(meshIndex)].primitives) {
    const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
    if (mode != TINYGLTF_MODE_TRIANGLES && mode != TINYGLTF_MODE_TRIANGLE_STRIP && mode != TINYGLTF_MODE_TRIANGLE_FAN) {
      continue;  // points and lines have no surface
    }
    const auto pos = prim.attributes.find("POSITION");
    if (pos == prim.attributes.end()) {
      problem = "a primitive without POSITION";
      return false;
    }
    std::vector<Vec3d> vertices;
    if (!readPositions(model, pos->second, vertices, problem)) return false;
    std::vector<std::uint32_t> indices;
    if (prim.indices >= 0) {
      if (!readIndices(model, prim.indices, indices, problem)) return false;
    } else {
      indices.resize(vertices.size());
      for (std::size_t i = 0; i < indices.size(); ++i) indices[i] = static_cast<std::uint32_t>(i);
    }
    for (const std::uint32_t i : indices) {
      if (i >= vertices.size()) {
        problem = "vertex index " + std::to_string(i) + " out of range";
        return false;
      }
    }
    auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
      if (budget == 0) return false;
      --budget;
      out.push_back({transformPoint(world, vertices[a]), transformPoint(world, vertices[b]), transformPoint(world, vertices[c])});
      return true;
    };
    const std::size_t n = indices.size();
    for (std::size_t i = 0; i + 2 < n; i += (mode == TINYGLTF_MODE_TRIANGLES ? 3 : 1)) {
      bool ok = true;
      if (mode == TINYGLTF_MODE_TRIANGLES) ok = add(indices[i], indices[i + 1], indices[i + 2]);
      else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)
        ok = (i % 2 == 0) ? add(indices[i], indices[i + 1], indices[i + 2]) : add(indices[i + 1], indices[i], indices[i + 2]);
      else ok = add(indices[0], indices[i + 1], indices[i + 2]);
      if (!ok) {
        problem = "the world has more than " + std::to_string(kMaxWorldTriangles) + " triangles";
        return false;
      }
    }
  }
  return true;
}

bool ignoreImage(tinygltf::Image*, const int, std::string*, std::string*, int, int, const unsigned char*, int, void*) {
  return true;  // images are never needed: a world is geometry and properties
}

/// External files a .gltf names (buffers) are read only from the world file's directory and below:
/// a world from the network or a shared folder must not make throng read "../../etc/passwd" or an
/// absolute path. No "~" or variable expansion either (tinygltf's default runs wordexp).
struct Confinement {
  std::filesystem::path root;  ///< canonical directory of the world file
  std::string baseDir;         ///< as tinygltf joins it to a URI (it also tries "." after it)
  std::string refused;         ///< the first path refused, for the diagnostic

  /// The URI as the file wrote it: the refused path without the search directory tinygltf added.
  [[nodiscard]] std::string refusedUri() const {
    for (const std::string& prefix : {baseDir.empty() ? std::string() : baseDir + "/", std::string("./")}) {
      if (!prefix.empty() && refused.rfind(prefix, 0) == 0) return refused.substr(prefix.size());
    }
    return refused;
  }
};

constexpr std::uintmax_t kMaxExternalFile = 512ull << 20;  // [bytes]

bool confined(const std::string& file, Confinement& c) {
  const bool inside = detail::insideDirectory(c.root, std::filesystem::path(file));
  if (!inside && c.refused.empty()) c.refused = file;
  return inside;
}

bool confinedExists(const std::string& file, void* user) {
  auto& c = *static_cast<Confinement*>(user);
  std::error_code ec;
  return confined(file, c) && std::filesystem::is_regular_file(file, ec);
}

std::string noExpansion(const std::string& path, void*) { return path; }

bool confinedRead(std::vector<unsigned char>* out, std::string* err, const std::string& file, void* user) {
  auto& c = *static_cast<Confinement*>(user);
  if (!confined(file, c)) {
    if (err) *err += "refused to read " + file + " (outside the world file's directory)\n";
    return false;
  }
  std::error_code ec;
  const auto size = std::filesystem::file_size(file, ec);
  if (ec || size > kMaxExternalFile) {
    if (err) *err += "cannot read " + file + (ec ? std::string() : " (larger than 512 MiB)") + "\n";
    return false;
  }
  std::ifstream in(file, std::ios::binary);
  out->resize(static_cast<std::size_t>(size));
  if (size > 0) in.read(reinterpret_cast<char*>(out->data()), static_cast<std::streamsize>(size));
  if (!in) {
    if (err) *err += "cannot read " + file + "\n";
    return false;
  }
  return true;
}

bool neverWrite(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "throng never writes glTF files\n";
  return false;
}

/// Deepest node nesting accepted (a scene root is at depth 0).
constexpr int kMaxNodeDepth = 64;

std::string nodeName(const tinygltf::Model& model, std::size_t i) {
  std::string name = model.nodes[i].name.substr(0, 60);
  for (char& c : name) {
    if (static_cast<unsigned char>(c) < 0x20) c = '?';
  }
  return "node " + std::to_string(i) + (name.empty() ? "" : " \"" + name + "\"");
}

/// The node hierarchy glTF 2.0 requires and tinygltf does not check (§3.5.2, §3.5.3): "scene"
/// names a scene; scene roots and children name nodes; each node has at most one parent, a scene
/// root has none; no node is its own ancestor; at most kMaxNodeDepth levels. One diagnostic per
/// fault, at its JSON pointer with the node named; false when there is any.
bool checkHierarchy(const tinygltf::Model& model, const std::string& source, core::Diagnostics& diagnostics) {
  const std::size_t before = diagnostics.size();
  auto error = [&](std::string pointer, std::string what, std::string expected) {
    if (diagnostics.size() - before < 50) diagnostics.push_back({source, 0, 0, std::move(pointer), std::move(what), std::move(expected), ""});
  };
  const std::size_t n = model.nodes.size();
  const std::string nodeRange = n == 0 ? "no node index (the file has no nodes)" : "a node index 0 … " + std::to_string(n - 1);
  if (model.defaultScene < -1 || (model.defaultScene >= 0 && static_cast<std::size_t>(model.defaultScene) >= model.scenes.size())) {
    error("/scene", "scene " + std::to_string(model.defaultScene) + " does not exist (the file has " +
                        std::to_string(model.scenes.size()) + " scene" + (model.scenes.size() == 1 ? "" : "s") + ")",
          model.scenes.empty() ? "no \"scene\" (the file has no scenes)"
                               : "a scene index 0 … " + std::to_string(model.scenes.size() - 1));
  }
  // Parents, from the children lists.
  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::vector<std::size_t> parent(n, kNone);
  for (std::size_t p = 0; p < n; ++p) {
    const std::vector<int>& children = model.nodes[p].children;
    for (std::size_t k = 0; k < children.size(); ++k) {
      const std::string ptr = "/nodes/" + std::to_string(p) + "/children/" + std::to_string(k);
      const int c = children[k];
      if (c < 0 || static_cast<std::size_t>(c) >= n) {
        error(ptr, nodeName(model, p) + " names child " + std::to_string(c) + ", which does not exist", nodeRange);
        continue;
      }
      const auto child = static_cast<std::size_t>(c);
      if (parent[child] != kNone) {
        error(ptr, nodeName(model, child) + " is a child of " + nodeName(model, parent[child]) + " already, and of " +
                       nodeName(model, p),
              "each node a child of at most one node (a tree)");
        continue;
      }
      parent[child] = p;
    }
  }
  // Cycles: walk up from every node; reaching a node of the same walk closes a cycle.
  std::vector<std::size_t> walk(n, kNone);  // the walk that reached each node first
  for (std::size_t start = 0; start < n; ++start) {
    if (walk[start] != kNone) continue;
    std::size_t at = start;
    while (at != kNone && walk[at] == kNone) {
      walk[at] = start;
      at = parent[at];
    }
    if (at == kNone || walk[at] != start) continue;  // reached a root, or a chain checked before
    // `at` is on a cycle: name it in order, report it at the children entry that closes it.
    std::string chain = std::to_string(at);
    for (std::size_t c = parent[at]; c != at; c = parent[c]) chain = std::to_string(c) + " → " + chain;
    chain = std::to_string(at) + " → " + chain;
    const std::vector<int>& siblings = model.nodes[parent[at]].children;
    const auto k = static_cast<std::size_t>(std::find(siblings.begin(), siblings.end(), static_cast<int>(at)) - siblings.begin());
    error("/nodes/" + std::to_string(parent[at]) + "/children/" + std::to_string(k),
          nodeName(model, at) + " is its own ancestor (children cycle " + chain + ")",
          "a node hierarchy without cycles (a tree)");
  }
  // Depth (only meaningful without cycles).
  if (diagnostics.size() == before) {
    for (std::size_t i = 0; i < n; ++i) {
      int d = 0;
      for (std::size_t a = parent[i]; a != kNone && d <= kMaxNodeDepth; a = parent[a]) ++d;
      if (d > kMaxNodeDepth) {
        error("/nodes/" + std::to_string(i), nodeName(model, i) + " is nested more than " + std::to_string(kMaxNodeDepth) + " levels deep",
              "at most " + std::to_string(kMaxNodeDepth) + " levels of child nodes");
        break;
      }
    }
  }
  for (std::size_t s = 0; s < model.scenes.size(); ++s) {
    const std::vector<int>& roots = model.scenes[s].nodes;
    for (std::size_t k = 0; k < roots.size(); ++k) {
      const std::string ptr = "/scenes/" + std::to_string(s) + "/nodes/" + std::to_string(k);
      const int r = roots[k];
      if (r < 0 || static_cast<std::size_t>(r) >= n) {
        error(ptr, "scene " + std::to_string(s) + " names node " + std::to_string(r) + ", which does not exist", nodeRange);
      } else if (parent[static_cast<std::size_t>(r)] != kNone) {
        error(ptr, "scene " + std::to_string(s) + " names " + nodeName(model, static_cast<std::size_t>(r)) +
                       " as a root, but it is a child of " + nodeName(model, parent[static_cast<std::size_t>(r)]),
              "root nodes of a scene without a parent");
      }
    }
  }
  return diagnostics.size() == before;
}

}  // namespace

Vec3d transformPoint(const Mat4d& m, const Vec3d& p) {
  return {m[0] * p[0] + m[4] * p[1] + m[8] * p[2] + m[12], m[1] * p[0] + m[5] * p[1] + m[9] * p[2] + m[13],
          m[2] * p[0] + m[6] * p[1] + m[10] * p[2] + m[14]};
}

Vec3d transformDirection(const Mat4d& m, const Vec3d& d) {
  return {m[0] * d[0] + m[4] * d[1] + m[8] * d[2], m[1] * d[0] + m[5] * d[1] + m[9] * d[2],
          m[2] * d[0] + m[6] * d[1] + m[10] * d[2]};
}

bool readGltfScene(const std::string& bytes, const std::string& source, const std::string& baseDir, GltfScene& out,
                   core::Diagnostics& diagnostics,
                   const std::function<bool(const std::string&, const std::string&)>& wantTriangles) {
  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(ignoreImage, nullptr);
  loader.SetStoreOriginalJSONForExtrasAndExtensions(true);
  Confinement confinement;
  confinement.baseDir = baseDir;
  confinement.root = detail::canonicalDirectory(baseDir);
  loader.SetFsCallbacks({&confinedExists, &noExpansion, &confinedRead, &neverWrite, &confinement});
  tinygltf::Model model;
  std::string err, warn;
  const bool binary = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  bool ok = false;
  if (binary) {
    ok = loader.LoadBinaryFromMemory(&model, &err, &warn, reinterpret_cast<const unsigned char*>(bytes.data()),
                                     static_cast<unsigned int>(bytes.size()), baseDir);
  } else {
    ok = loader.LoadASCIIFromString(&model, &err, &warn, bytes.data(), static_cast<unsigned int>(bytes.size()), baseDir);
  }
  if (!ok && !confinement.refused.empty()) {
    diagnostics.push_back({source, 0, 0, "/buffers",
                           "a buffer names \"" + confinement.refusedUri() + "\", outside the world file's directory",
                           "buffer files next to the world file (or below it), or data: URIs", ""});
    return false;
  }
  if (!ok) {
    while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
    diagnostics.push_back({source, 0, 0, "", "not a valid glTF 2.0 file: " + (err.empty() ? std::string("unknown error") : err),
                           "a glTF 2.0 file (.gltf JSON or .glb binary)", ""});
    return false;
  }
  if (!checkHierarchy(model, source, diagnostics)) return false;
  // The default scene (or the first); without scenes every node that is nobody's child is a root.
  std::vector<int> roots;
  if (!model.scenes.empty()) {
    out.sceneIndex = model.defaultScene >= 0 ? model.defaultScene : 0;
    const tinygltf::Scene& scene = model.scenes[static_cast<std::size_t>(out.sceneIndex)];
    roots = scene.nodes;
    out.sceneExtrasJson = scene.extras_json_string;
  } else {
    std::vector<bool> child(model.nodes.size(), false);
    for (const auto& n : model.nodes) {
      for (const int c : n.children) {
        if (c >= 0 && static_cast<std::size_t>(c) < child.size()) child[static_cast<std::size_t>(c)] = true;
      }
    }
    for (std::size_t i = 0; i < child.size(); ++i) {
      if (!child[i]) roots.push_back(static_cast<int>(i));
    }
  }
  // checkHierarchy made it a forest of at most kMaxNodeDepth levels: each node is visited once.
  std::vector<bool> visited(model.nodes.size(), false);
  std::size_t budget = kMaxWorldTriangles;
  std::function<void(int, const Mat4d&, int)> visit = [&](int index, const Mat4d& parent, int depth) {
    if (index < 0 || static_cast<std::size_t>(index) >= model.nodes.size() || visited[static_cast<std::size_t>(index)] ||
        depth > kMaxNodeDepth) {
      return;  // cannot happen after checkHierarchy; kept so that a mistake there cannot recurse forever
    }
    visited[static_cast<std::size_t>(index)] = true;
    const tinygltf::Node& n = model.nodes[static_cast<std::size_t>(index)];
    GltfNode node;
    node.index = index;
    node.name = n.name;
    node.world = multiply(parent, localMatrix(n));
    node.extrasJson = n.extras_json_string;
    node.hasMesh = n.mesh >= 0;
    if (node.hasMesh && wantTriangles(node.name, node.extrasJson)) meshTriangles(model, n.mesh, node.world, budget, node.triangles, node.meshProblem);
    const Mat4d world = node.world;
    out.nodes.push_back(std::move(node));
    for (const int c : n.children) visit(c, world, depth + 1);
  };
  for (const int r : roots) visit(r, kIdentity, 0);
  return true;
}

}  // namespace throng::io
