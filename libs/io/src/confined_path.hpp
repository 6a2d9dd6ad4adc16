// throng::io confined paths — every path a file names (a glTF buffer URI, an action point's clip,
// a timeline crowd, the social databases, the micro-behaviours' clips) is read only from the
// directory of the file that names it and below: no absolute path, no ".." out of it, no symbolic
// link leading out of it (checked on the resolved path, std::filesystem::weakly_canonical). A
// scenario or world from the network or a shared folder must not make throng read /etc/shadow or
// ~/.ssh. Reads only directory entries (to resolve links); never a file's content. Private to
// throng_io.
#pragma once
#include <filesystem>
#include <string>

namespace throng::io::detail {

/// True when `path` (absolute or relative to the working directory) resolves to `root` or to a
/// file or directory below it. `root` must be canonical (canonicalDirectory). Symbolic links are
/// followed for every part that exists; a missing tail is judged lexically.
[[nodiscard]] bool insideDirectory(const std::filesystem::path& root, const std::filesystem::path& path);

/// weakly_canonical(dir), "." when `dir` is empty; empty when it cannot be resolved.
[[nodiscard]] std::filesystem::path canonicalDirectory(const std::filesystem::path& dir);

/// A path a file names, resolved against that file's directory.
struct ConfinedPath {
  std::filesystem::path path;  ///< dir / named, lexically normal (empty when refused)
  std::string problem;         ///< why it was refused ("" when accepted), without the file's content
  [[nodiscard]] bool ok() const { return problem.empty(); }
};

/// Resolves `named` (as the file wrote it) against `dir` (the directory of the naming file; the
/// working directory when empty) and refuses it when it is absolute or leads outside `dir`.
/// `namer` is how the message calls the naming file ("the scenario", "the world file").
[[nodiscard]] ConfinedPath confinePath(const std::filesystem::path& dir, const std::string& named,
                                       const std::string& namer);

/// What a refused path's diagnostic expects (one wording for every kind of path).
[[nodiscard]] std::string confinedExpectation(const std::string& what, const std::string& namer);

}  // namespace throng::io::detail
