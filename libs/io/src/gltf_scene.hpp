// throng::io glTF scene reading — a glTF 2.0 file (JSON .gltf or binary .glb, through Debian's
// tinygltf) → the plain node list the world-file naming rules work on: each node of the default
// scene with its name, world transform, the JSON text of its extras and, for mesh nodes, its
// triangles in world coordinates (metres, glTF's Y-up frame). Reads the bytes given and the
// buffers they name (relative to the file's directory); images are never decoded. Private to throng_io.
#pragma once
#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "throng/core/diagnostic.hpp"

namespace throng::io {

using Vec3d = std::array<double, 3>;
/// Column-major 4×4 matrix, as glTF writes them.
using Mat4d = std::array<double, 16>;

struct GltfNode {
  int index = 0;            ///< index in the file's "nodes" array (diagnostics name it)
  std::string name;
  Mat4d world{};            ///< node → world transform
  bool hasMesh = false;
  std::string extrasJson;   ///< the node's "extras" as JSON text; empty when it has none
  std::vector<std::array<Vec3d, 3>> triangles;  ///< world coordinates [m]
  std::string meshProblem;  ///< why the mesh's triangles could not be read; empty when fine
};

struct GltfScene {
  std::vector<GltfNode> nodes;   ///< nodes of the default scene, depth first
  std::string sceneExtrasJson;   ///< the default scene's "extras" as JSON text; empty when none
  int sceneIndex = -1;           ///< -1 when the file has no scene (then every root node is used)
};

/// Most triangles a world may hold (all meshes together); more is one diagnostic.
inline constexpr std::size_t kMaxWorldTriangles = 200000;

/// Parses glTF bytes (".glb" when they start with the "glTF" magic, else JSON). `source` names
/// the file in diagnostics; `baseDir` resolves external buffers. Returns false with diagnostics
/// when the file is no valid glTF. Triangles are read only for the mesh nodes `wantTriangles`
/// accepts (given the node's name and extras JSON): decoration meshes cost nothing.
bool readGltfScene(const std::string& bytes, const std::string& source, const std::string& baseDir, GltfScene& out,
                   core::Diagnostics& diagnostics,
                   const std::function<bool(const std::string&, const std::string&)>& wantTriangles);

/// Transforms a point by a column-major matrix.
[[nodiscard]] Vec3d transformPoint(const Mat4d& m, const Vec3d& p);
/// Transforms a direction (no translation).
[[nodiscard]] Vec3d transformDirection(const Mat4d& m, const Vec3d& d);

}  // namespace throng::io
