// Where the program finds its bundled data (docs/install.md): the scenarios with their motion
// clips, the browser viewer's built files, the verification scripts and suites. An installed
// program looks in <prefix>/share/throng, found from its own path (so a moved or extracted prefix
// works); a program in a build tree falls back to the source tree it was built from.
#pragma once
#include <filesystem>
#include <string_view>

namespace throng::cli {

/// <exe dir>/../share/throng when that is a directory, else empty. `exe` is this executable's
/// path (currentExecutable(), bench_files.hpp); empty gives empty.
[[nodiscard]] std::filesystem::path installedDataDir(const std::filesystem::path& exe);

/// The bundled directory `sub` of an installed tree (<prefix>/share/throng/`sub`) when it exists,
/// else `buildTreeFallback` (a source-tree path compiled in; may be empty).
[[nodiscard]] std::filesystem::path bundledDataDir(const std::filesystem::path& exe, std::string_view sub,
                                                   const std::filesystem::path& buildTreeFallback);

}  // namespace throng::cli
