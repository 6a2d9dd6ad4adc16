// Fuzz target for throng::recording::readRecordingSummary (libs/recording/src/recording_reader.cpp), the
// Common Ground readers and metrics (recording_social.cpp, metrics_queries.cpp,
// metrics_analysis.cpp) and the replay frames (frame_reader.cpp): the input bytes become a file on
// disk (SQLite reads files, not buffers) and are summarised read-only.
// Any input must give a summary or a diagnostic: no crash, hang, leak or write.
// Corpus: fuzz/corpus/recording_reader/ (tiny valid recordings and junk).
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "throng/recording/frame_reader.hpp"
#include "throng/recording/recorder.hpp"
#include "throng/recording/recording_social.hpp"

namespace {

std::string& tempDir() {
  static std::string dir;
  return dir;
}

/// One private directory per fuzzing process, holding the current input as a file; removed at exit.
const std::string& inputPath() {
  static const std::string path = [] {
    std::string dir = "/tmp/throng-fuzz-recording-XXXXXX";
    if (::mkdtemp(dir.data()) == nullptr) std::abort();
    tempDir() = dir;
    std::atexit([] { ::rmdir(tempDir().c_str()); });
    return dir + "/input.sqlite";
  }();
  return path;
}

void removeFiles(const std::string& path) {
  for (const char* suffix : {"", "-wal", "-shm", "-journal"}) std::remove((path + suffix).c_str());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size > (1u << 20)) return 0;  // recordings in the corpus are a few KB; skip huge inputs
  const std::string& path = inputPath();
  removeFiles(path);
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (f == nullptr) std::abort();
  if (size > 0 && std::fwrite(data, 1, size, f) != size) std::abort();
  std::fclose(f);

  const auto summary = throng::recording::readRecordingSummary(path);
  if (!summary.ok() && summary.errors().empty()) std::abort();  // a failure must say why
  if (summary.ok() && summary->fps <= 0.0) std::abort();       // the reader validates fps

  // The Common Ground readers and metrics: a value or a diagnostic, never a crash.
  const auto coordinations = throng::recording::readCoordinations(path);
  if (!coordinations.ok() && coordinations.errors().empty()) std::abort();
  const auto script = throng::recording::readScript(path, 0);
  if (!script.ok() && script.errors().empty()) std::abort();
  if (coordinations.ok() && !coordinations->empty()) {
    const auto all = throng::recording::readCoordinationScript(path, coordinations.value().front().id);
    if (!all.ok() && all.errors().empty()) std::abort();
  }
  const auto track = throng::recording::readAgentTrack(path, 0);
  if (!track.ok() && track.errors().empty()) std::abort();
  const auto metrics = throng::recording::computeMetrics(path);
  if (!metrics.ok() && metrics.errors().empty()) std::abort();
  if (metrics.ok() && (metrics->cohesion.shareTogether < 0.0 || metrics->cohesion.shareTogether > 1.0)) std::abort();

  // The frames for replay (hub::Replay), within a small memory budget: one frame per frame
  // number, times from 0 and non-decreasing, every per-agent column as long as ids.
  const auto frames = throng::recording::readRecordedFrames(path, throng::recording::FrameReadOptions{std::size_t{64} << 20});
  if (!frames.ok() && frames.errors().empty()) std::abort();
  if (frames.ok()) {
    if (frames->frames.empty() || frames->frames.size() != frames->times.size() || frames->times[0] != 0.0) std::abort();
    for (std::size_t i = 0; i < frames->frames.size(); ++i) {
      const throng::sim::Frame& fr = *frames->frames[i];
      if (i > 0 && frames->times[i] < frames->times[i - 1]) std::abort();
      if (fr.posX.size() != fr.ids.size() || fr.clip.size() != fr.ids.size() || fr.phase.size() != fr.ids.size() ||
          fr.mode.size() != fr.ids.size()) {
        std::abort();
      }
    }
  }
  removeFiles(path);
  return 0;
}
