// libFuzzer target for glTF world files (libs/io world_file, gltf_scene, world_footprint):
// arbitrary bytes (JSON glTF or binary .glb) → parseWorld. Reads the input only (buffers with
// external URIs resolve against a directory that does not exist). Checks that nothing crashes,
// throws or hangs and that results are coherent: an accepted world has a walkable area and its
// point indices are in range; a rejected one has diagnostics that name the source and say what
// is wrong.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string_view>

#include "throng/io/world_file.hpp"

namespace {

void check(bool condition) {
  if (!condition) std::abort();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  throng::io::LoadOptions options;
  options.checkReachability = size < 4096;  // the navmesh for small inputs only
  const auto r = throng::io::parseWorld(bytes, "/nonexistent-throng-fuzz/world.gltf", options);
  if (!r.ok()) {
    check(!r.errors().empty());
    for (const auto& d : r.errors()) {
      check(!d.what.empty());
      check(d.line >= 0 && d.column >= 0);
    }
    return 0;
  }
  const auto& desc = r.value().desc;
  check(!desc.walkable.empty());
  check(!r.value().text.empty());
  for (const auto& pop : desc.populations) {
    for (const auto goal : pop.goals) check(goal < desc.points.size());
    check(pop.sizeMin >= 1 && pop.sizeMin <= pop.sizeMax);
  }
  return 0;
}
