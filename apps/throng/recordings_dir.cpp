// `throng serve --recordings DIR`: listing, resolving names safely and storing uploads
// (recordings_dir.hpp). Steps of an upload: checkUpload (size, SQLite header), writeTemp (a
// hidden file created exclusively), checkRecording (hub::Replay, the stored scenario), linkUnique.
#include "recordings_dir.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <optional>

#include <fmt/format.h>

#include "throng/hub/replay.hpp"
#include "throng/io/scenario_loader.hpp"
#include "throng/recording/recorder.hpp"

namespace throng::cli {
namespace {

namespace fs = std::filesystem;

constexpr std::string_view kSuffix = ".sqlite";
constexpr std::size_t kMaxStem = 80;
constexpr const char* kExpectedRecording = "a recording written by `throng run` (SQLite, .sqlite)";

core::Diagnostic diag(std::string source, std::string what, std::string expected = kExpectedRecording) {
  core::Diagnostic d;
  d.source = std::move(source);
  d.what = std::move(what);
  d.expected = std::move(expected);
  return d;
}

/// Whether `name` could name a file directly in DIR (see RecordingsDir::resolve).
std::optional<std::string> badName(std::string_view name) {
  if (name.empty()) return "an empty name";
  if (name == "." || name == "..") return "not a file name";
  if (name.find_first_of(std::string_view("/\\\0", 3)) != std::string_view::npos) {
    return "a path, not a file name (it has a '/', '\\' or NUL)";
  }
  if (name.front() == '.') return "a hidden name (it starts with a dot)";
  if (name.size() <= kSuffix.size() || !name.ends_with(kSuffix)) return "not a .sqlite file name";
  return std::nullopt;
}

/// Whether `p` (canonical) lies directly in `dir` (canonical).
bool directlyIn(const fs::path& p, const fs::path& dir) { return p.parent_path() == dir; }

std::string mib(std::size_t bytes) { return fmt::format("{:.1f} MiB", static_cast<double>(bytes) / (1024.0 * 1024.0)); }

/// Size and SQLite header of an upload.
std::optional<core::Diagnostic> checkUpload(const std::string& name, std::string_view bytes, std::size_t maxBytes) {
  if (bytes.empty()) return diag(name, "the file is empty");
  if (bytes.size() > maxBytes) {
    return diag(name, fmt::format("too large: {}; the limit is {} (throng serve --max-upload)", mib(bytes.size()),
                                  mib(maxBytes)));
  }
  static constexpr char kHeader[16] = {'S', 'Q', 'L', 'i', 't', 'e', ' ', 'f', 'o', 'r', 'm', 'a', 't', ' ', '3', '\0'};
  if (bytes.size() < sizeof kHeader || std::memcmp(bytes.data(), kHeader, sizeof kHeader) != 0) {
    return diag(name, "not a SQLite file (its first bytes are not \"SQLite format 3\")");
  }
  return std::nullopt;
}

/// Writes `bytes` to a new hidden file in `dir`; its path, or a diagnostic.
core::Result<fs::path> writeTemp(const fs::path& dir, const std::string& name, std::string_view bytes) {
  static std::atomic<unsigned> counter{0};
  const auto stamp = std::chrono::steady_clock::now().time_since_epoch().count();
  const fs::path temp = dir / fmt::format(".upload-{}-{}-{}.part", ::getpid(), counter++, stamp);
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return diag(name, fmt::format("cannot write into {}: {}", dir.string(), std::strerror(errno)), {});
  std::size_t written = 0;
  while (written < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + written, bytes.size() - written);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const std::string why = std::strerror(errno);
      ::close(fd);
      ::unlink(temp.c_str());
      return diag(name, fmt::format("cannot write into {}: {}", dir.string(), why), {});
    }
    written += static_cast<std::size_t>(n);
  }
  if (::fsync(fd) != 0 || ::close(fd) != 0) {
    ::unlink(temp.c_str());
    return diag(name, fmt::format("cannot write into {}: {}", dir.string(), std::strerror(errno)), {});
  }
  return temp;
}

/// What `throng serve` needs to play it: hub::Replay opens it, and the scenario it stores parses.
std::optional<core::Diagnostic> checkRecording(const fs::path& temp, const std::string& name) {
  auto replay = hub::Replay::open(temp.string());
  if (!replay) {
    core::Diagnostic d = replay.errors().front();
    d.source = name;
    if (d.expected.empty()) d.expected = kExpectedRecording;
    return d;
  }
  auto parsed = io::parseScenario(replay.value().scenarioText(), name + " (stored scenario)");
  if (!parsed) {
    return diag(name, "the scenario it stores does not load: " + parsed.errors().front().format(),
                "a recording of a scenario this throng loads");
  }
  return std::nullopt;
}

}  // namespace

std::string sanitiseRecordingName(std::string_view suggested) {
  const std::size_t slash = suggested.find_last_of("/\\");
  if (slash != std::string_view::npos) suggested.remove_prefix(slash + 1);
  if (suggested.ends_with(kSuffix)) suggested.remove_suffix(kSuffix.size());
  std::string stem;
  for (const char ch : suggested) {
    const bool keep = (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') || (ch >= '0' && ch <= '9') || ch == '-' ||
                      ch == '_' || ch == '.';
    stem.push_back(keep ? ch : '_');
  }
  stem.erase(0, stem.find_first_not_of('.'));
  if (stem.size() > kMaxStem) stem.resize(kMaxStem);
  if (stem.empty()) stem = "recording";
  return stem + std::string(kSuffix);
}

RecordingEntry summariseRecording(const fs::path& file) {
  RecordingEntry e;
  e.name = file.filename().string();
  std::error_code ec;
  e.size = fs::file_size(file, ec);
  auto summary = recording::readRecordingSummary(file.string());
  if (!summary) {
    e.error = summary.errors().front().what;
    return e;
  }
  e.duration = summary->duration;
  e.agents = summary->agents;
  e.scenario = summary->scenarioName;
  return e;
}

core::Result<RecordingsDir> RecordingsDir::open(const fs::path& dir) {
  std::error_code ec;
  const fs::path canonical = fs::canonical(dir, ec);
  if (ec) return diag(dir.string(), "no such directory", "a directory of recordings (--recordings DIR)");
  if (!fs::is_directory(canonical, ec)) {
    return diag(dir.string(), "not a directory", "a directory of recordings (--recordings DIR)");
  }
  return RecordingsDir(canonical);
}

core::Result<fs::path> RecordingsDir::resolve(std::string_view name) const {
  const std::string shown(name.substr(0, 200));
  if (auto bad = badName(name)) return diag(shown, "not a recording name: " + *bad, "the name of a .sqlite file in the recordings directory");
  const fs::path p = dir_ / std::string(name);
  std::error_code ec;
  const fs::file_status link = fs::symlink_status(p, ec);
  if (ec || !fs::exists(link)) return diag(shown, "no such recording in the recordings directory", {});
  const fs::path target = fs::canonical(p, ec);
  if (ec) return diag(shown, "no such recording in the recordings directory (a broken link)", {});
  if (!directlyIn(target, dir_)) return diag(shown, "a link to a file outside the recordings directory", {});
  if (!fs::is_regular_file(target, ec)) return diag(shown, "not a regular file", {});
  return target;
}

std::vector<RecordingEntry> RecordingsDir::list() const {
  std::vector<RecordingEntry> entries;
  std::error_code ec;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir_, ec)) {
    const std::string name = entry.path().filename().string();
    auto path = resolve(name);
    if (!path) continue;
    RecordingEntry e = summariseRecording(path.value());
    e.name = name;
    entries.push_back(std::move(e));
  }
  std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) { return a.name < b.name; });
  return entries;
}

core::Result<std::string> RecordingsDir::linkUnique(const fs::path& temp, const std::string& base) const {
  const std::string stem = base.substr(0, base.size() - kSuffix.size());
  for (int n = 1; n < 10000; ++n) {
    const std::string name = n == 1 ? base : fmt::format("{}-{}{}", stem, n, kSuffix);
    // link() never replaces an existing file: a name taken meanwhile fails with EEXIST.
    if (::link(temp.c_str(), (dir_ / name).c_str()) == 0) return name;
    if (errno != EEXIST) {
      return diag(base, fmt::format("cannot store it in {}: {}", dir_.string(), std::strerror(errno)), {});
    }
  }
  return diag(base, "every variant of this name is taken", {});
}

core::Result<RecordingEntry> RecordingsDir::store(std::string_view suggested, std::string_view bytes,
                                                  std::size_t maxBytes) const {
  const std::string name = sanitiseRecordingName(suggested);
  if (auto bad = checkUpload(name, bytes, maxBytes)) return *bad;
  auto temp = writeTemp(dir_, name, bytes);
  if (!temp) return temp.errors();
  auto stored = [&]() -> core::Result<std::string> {
    if (auto bad = checkRecording(temp.value(), name)) return *bad;
    return linkUnique(temp.value(), name);
  }();
  ::unlink(temp.value().c_str());
  if (!stored) return stored.errors();
  RecordingEntry entry = summariseRecording(dir_ / stored.value());
  entry.name = stored.value();
  return entry;
}

}  // namespace throng::cli
