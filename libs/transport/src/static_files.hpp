// throng::transport::detail static files — turns an HTTP request target into a file under the
// static root (percent-decoded, no way out of the root) and names its Content-Type. Reads the
// file system (existence, canonical paths) only in resolveStaticFile.
#pragma once
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "throng/transport/transport.hpp"

namespace throng::transport::detail {

/// The relative path a target names ("" for "/"), or nullopt when the target is malformed
/// (not starting with '/', bad escape, NUL, backslash) or has a ".." segment.
[[nodiscard]] std::optional<std::filesystem::path> safeRelativePath(std::string_view target);

enum class StaticLookup { Found, NotFound, BadTarget };

struct StaticFile {
  StaticLookup lookup = StaticLookup::NotFound;
  std::filesystem::path path;  ///< set when Found
};

/// The file under `root` a target names (a directory gives its index.html); a path that resolves
/// (through symbolic links) outside the root is NotFound.
[[nodiscard]] StaticFile resolveStaticFile(const std::filesystem::path& root, std::string_view target);

/// MIME type from the extension (html, js, mjs, css, json, png, jpg, svg, wasm, glb, gltf, bin,
/// txt, ico, map); application/octet-stream otherwise.
[[nodiscard]] std::string_view contentTypeFor(const std::filesystem::path& file);

}  // namespace throng::transport::detail
