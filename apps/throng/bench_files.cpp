// What `throng bench` needs beyond the in-memory scenarios — see bench_files.hpp.
#include "bench_files.hpp"

#include <atomic>
#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <unistd.h>

#include "throng/bench/scenarios.hpp"

namespace throng::cli {

std::string checkBenchScenarioValue(const std::string& value) {
  if (bench::layoutFromName(value)) return {};
  for (const char* name : kBundledBenchScenarios) {
    if (value == name) return {};
  }
  const bool looksLikeFile = value.size() > 5 && value.compare(value.size() - 5, 5, ".json") == 0;
  std::error_code ec;
  if (looksLikeFile || value.find('/') != std::string::npos || std::filesystem::is_regular_file(value, ec)) return {};
  return fmt::format("'{}' is not a bench scenario: expected {}", value, kBenchScenarioValues);
}

std::vector<std::filesystem::path> bundledScenarioCandidates(const std::string& name,
                                                             const std::filesystem::path& exe) {
  const std::string file = name + ".json";
  std::vector<std::filesystem::path> candidates{std::filesystem::path("scenarios") / file};
  if (!exe.empty()) {
    const auto dir = exe.parent_path();
    candidates.push_back((dir / "../share/throng/scenarios" / file).lexically_normal());
    candidates.push_back((dir / "../../../scenarios" / file).lexically_normal());
  }
  return candidates;
}

std::filesystem::path currentExecutable() {
  std::error_code ec;
  auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  return ec ? std::filesystem::path{} : exe;
}

std::uint64_t benchFrameStride(double fps, double dt, double& actualFps) {
  const double ratio = 1.0 / (fps * dt);
  const auto stride = static_cast<std::uint64_t>(std::max(1.0, std::round(ratio)));
  const bool exact = std::fabs(ratio - static_cast<double>(stride)) <= 1e-6 * ratio;
  actualFps = exact ? fps : 1.0 / (static_cast<double>(stride) * dt);
  return stride;
}

TempRecording::TempRecording() {
  static std::atomic<unsigned> counter{0};
  std::error_code ec;
  std::filesystem::path dir = std::filesystem::temp_directory_path(ec);
  if (ec) dir = "/tmp";
  path_ = (dir / fmt::format("throng-bench-{}-{}.sqlite", ::getpid(), counter++)).string();
}

TempRecording::~TempRecording() {
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) {
    std::error_code ec;
    std::filesystem::remove(path_ + suffix, ec);
  }
}

}  // namespace throng::cli
