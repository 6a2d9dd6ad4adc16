// Running a bundled Python script (`throng verify` runs scripts/verify.py, `throng plot` runs
// scripts/plot.py): where the script is (<prefix>/share/throng/scripts next to an installed binary,
// else the source tree the binary was built from), which python3 runs it (/usr/bin/python3, where
// Debian's numpy, pandas and matplotlib are, else the first on PATH), and running it with the
// terminal's SIGINT/SIGTERM passed on.
#pragma once
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace throng::cli {

/// The first existing `name` in <exe dir>/../share/throng/scripts, else in `sourceScripts`; empty if neither.
[[nodiscard]] std::filesystem::path findBundledScript(const std::filesystem::path& exe, std::string_view name,
                                                      const std::filesystem::path& sourceScripts);

/// /usr/bin/python3 if it exists, else the first python3 on PATH; empty if none.
[[nodiscard]] std::string findPython();

/// Runs argv[0] with argv and waits; its exit status (128 + signal when a signal ended it, 1 when it
/// could not start: `command` names the subcommand in that message). SIGINT/SIGTERM sent to this
/// process while it runs go on to it.
int runScriptAndWait(const std::vector<std::string>& argv, std::string_view command);

}  // namespace throng::cli
