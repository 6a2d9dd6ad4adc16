// `throng serve --recordings DIR` — the directory of recordings a viewer may list, open and upload
// to (docs/viewer.md, *Recordings from the page*). Names, never paths: a name is one file directly
// in DIR ending in .sqlite, with no `/`, `\`, NUL or leading dot, and no symbolic link leading out
// of DIR, so nothing outside DIR is ever read. An upload is written to a hidden temporary file in
// DIR, checked as a throng recording (hub::Replay opens it, its stored scenario parses) and only
// then linked under a sanitised name no other file has; whatever fails, the temporary file goes,
// so nothing is left half-written. Reads DIR and its recordings; writes only uploads.
#pragma once
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "throng/core/result.hpp"

namespace throng::cli {

/// One recording of the directory, as GET /api/recordings lists it.
struct RecordingEntry {
  std::string name;           ///< file name in DIR
  std::uintmax_t size = 0;    ///< [bytes]
  double duration = 0.0;      ///< first to last frame [s]
  std::uint64_t agents = 0;   ///< distinct agent ids
  std::string scenario;       ///< the scenario's name from the recording's metadata
  std::string error;          ///< why it cannot be read (then the figures above are 0); empty when fine
};

class RecordingsDir {
 public:
  /// DIR must exist and be a directory; kept as its canonical path. Error: one diagnostic naming it.
  static core::Result<RecordingsDir> open(const std::filesystem::path& dir);

  [[nodiscard]] const std::filesystem::path& path() const { return dir_; }

  /// Every valid name in DIR (see resolve), sorted by name, with its summary or its error.
  [[nodiscard]] std::vector<RecordingEntry> list() const;

  /// The path of recording `name` in DIR. Errors: not a plain file name (empty, `.`, `..`, a `/`,
  /// `\` or NUL, a leading dot), not ending in .sqlite, no such file, a symbolic link whose target
  /// is not in DIR, not a regular file.
  [[nodiscard]] core::Result<std::filesystem::path> resolve(std::string_view name) const;

  /// Stores an uploaded recording under sanitiseName(suggested), "-2", "-3", … appended when taken.
  /// Errors (one diagnostic, `source` the suggested name): empty, over maxBytes, not SQLite, not a
  /// throng recording (hub::Replay's reason), its stored scenario does not parse, cannot write.
  [[nodiscard]] core::Result<RecordingEntry> store(std::string_view suggested, std::string_view bytes,
                                                   std::size_t maxBytes) const;

 private:
  explicit RecordingsDir(std::filesystem::path dir) : dir_(std::move(dir)) {}
  [[nodiscard]] core::Result<std::string> linkUnique(const std::filesystem::path& temp, const std::string& base) const;
  std::filesystem::path dir_;
};

/// A file name made safe for DIR: the last path component of `suggested`, every character but
/// ASCII letters, digits, `-`, `_` and `.` replaced by `_`, leading dots dropped, at most 80
/// characters before the suffix, ending in .sqlite ("recording.sqlite" when nothing is left).
[[nodiscard]] std::string sanitiseRecordingName(std::string_view suggested);

/// The summary of one recording file, for the listing (error filled when it cannot be read).
[[nodiscard]] RecordingEntry summariseRecording(const std::filesystem::path& file);

}  // namespace throng::cli
