// What `throng bench` needs beyond the in-memory scenarios of throng::bench (libs/bench): the
// --scenario values (layout names, bundled names such as "mall", any PATH.json) and where a bundled
// file is looked up (next to the working directory and the executable); --record's frame stride
// and the temporary recording file it writes. Private to the throng program.
#pragma once
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace throng::cli {

/// Bundled scenario files known by name (scenarios/<name>.json).
inline constexpr const char* kBundledBenchScenarios[] = {"mall"};
/// The accepted --scenario values, for messages.
inline constexpr const char* kBenchScenarioValues = "random, navmesh, musse, mall or a scenario file PATH.json";

/// An empty string when `value` is a usable --scenario value: an in-memory layout name, a bundled
/// name, a name ending in ".json", containing a '/', or naming an existing file; else the message.
[[nodiscard]] std::string checkBenchScenarioValue(const std::string& value);

/// Where a bundled scenario (`name`.json) is looked for, in order: ./scenarios/, an installed share
/// dir (<exe dir>/../share/throng/scenarios/), the source tree seen from a build tree's executable
/// (<exe dir>/../../../scenarios/). `exe` is this executable's path (empty: skipped).
[[nodiscard]] std::vector<std::filesystem::path> bundledScenarioCandidates(const std::string& name,
                                                                           const std::filesystem::path& exe);

/// This executable's path (/proc/self/exe), empty when unknown.
[[nodiscard]] std::filesystem::path currentExecutable();

/// Ticks between recorded frames for `fps` at time step `dt` — the rule of `throng run`:
/// round(1 / (fps * dt)), at least 1; `actualFps` is the rate that gives.
[[nodiscard]] std::uint64_t benchFrameStride(double fps, double dt, double& actualFps);

/// A recording path in the temporary directory ($TMPDIR, else /tmp), unique in this process; the
/// file and its SQLite companions (-wal, -shm, -journal) are deleted on destruction.
class TempRecording {
 public:
  TempRecording();
  ~TempRecording();
  TempRecording(const TempRecording&) = delete;
  TempRecording& operator=(const TempRecording&) = delete;

  [[nodiscard]] const std::string& path() const { return path_; }

 private:
  std::string path_;
};

}  // namespace throng::cli
