// throng::io confined paths (see confined_path.hpp).
#include "confined_path.hpp"

#include <system_error>

#include "throng/core/text.hpp"

namespace throng::io::detail {

namespace fs = std::filesystem;

namespace {

/// The path as written, quoted and safe to echo (core::printable: escapes, at most 120 characters).
std::string quoted(const std::string& s) { return "\"" + core::printable(s, 120) + "\""; }

bool isAbsolute(const std::string& named) {
  return fs::path(named).is_absolute() || (!named.empty() && (named.front() == '/' || named.front() == '\\')) ||
         (named.size() > 1 && named[1] == ':');
}

/// "a/b/../c" stays below its start; "a/../../c" does not (no file system access).
bool lexicallyBelow(const fs::path& rel) {
  const fs::path n = rel.lexically_normal();
  return n.empty() || (!n.is_absolute() && *n.begin() != "..");
}

}  // namespace

fs::path canonicalDirectory(const fs::path& dir) {
  std::error_code ec;
  const fs::path absolute = fs::absolute(dir.empty() ? fs::path(".") : dir, ec);
  if (ec) return {};
  fs::path root = fs::weakly_canonical(absolute, ec);
  if (ec) return {};
  return root;
}

bool insideDirectory(const fs::path& root, const fs::path& path) {
  if (root.empty()) return false;
  std::error_code ec;
  // Absolute first: weakly_canonical leaves a relative path with no existing part relative.
  const fs::path absolute = fs::absolute(path, ec);
  if (ec) return false;
  const fs::path resolved = fs::weakly_canonical(absolute, ec);
  if (ec) return false;
  const fs::path rel = resolved.lexically_relative(root);
  return !rel.empty() && !rel.is_absolute() && *rel.begin() != "..";
}

ConfinedPath confinePath(const fs::path& dir, const std::string& named, const std::string& namer) {
  ConfinedPath out;
  if (named.empty()) {
    out.problem = "empty path";
    return out;
  }
  if (named.find('\0') != std::string::npos) {
    out.problem = "the path contains a NUL character";
    return out;
  }
  if (isAbsolute(named)) {
    out.problem = "absolute path " + quoted(named) + ": files are read only from the directory of " + namer;
    return out;
  }
  if (!lexicallyBelow(fs::path(named))) {
    out.problem = quoted(named) + " leads out of the directory of " + namer + " (\"..\")";
    return out;
  }
  const fs::path joined = ((dir.empty() ? fs::path(".") : dir) / fs::path(named)).lexically_normal();
  if (!insideDirectory(canonicalDirectory(dir), joined)) {
    out.problem = quoted(named) + " leads out of the directory of " + namer + " through a symbolic link";
    return out;
  }
  out.path = joined;
  return out;
}

std::string confinedExpectation(const std::string& what, const std::string& namer) {
  return what + " inside the directory of " + namer + " (a relative path without \"..\" out of it or links leading out)";
}

}  // namespace throng::io::detail
