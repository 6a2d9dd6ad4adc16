// End-to-end test support — runs the built `throng` binary (path from the THRONG_EXE compile
// definition) in a working directory, capturing exit code, stdout and stderr; and a scratch
// directory per test that is removed afterwards.
#pragma once
#include <chrono>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <sys/types.h>

namespace throng::e2e {

struct CliResult {
  int exitCode = -1;   ///< the process's exit status; 128 + signal when killed by a signal
  std::string out;     ///< stdout
  std::string err;     ///< stderr
};

/// A fresh directory under the system temp directory, removed on destruction.
class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag);
  ~ScratchDir();
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  /// Writes `text` to `name` inside the directory and returns its full path.
  std::filesystem::path write(const std::string& name, const std::string& text) const;
  [[nodiscard]] std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

/// Runs `throng args...` in `cwd` and waits for it.
CliResult runThrong(const std::vector<std::string>& args, const std::filesystem::path& cwd);

/// Runs `throng args...` in `cwd` with its stderr on a pseudo-terminal `columns` wide (stdout to a
/// file), so it draws its progress line; `err` holds every byte written to the terminal.
CliResult runThrongInTerminal(const std::vector<std::string>& args, const std::filesystem::path& cwd, int columns = 80);

/// A throng process started in the background (for signal tests); its output goes to files.
class CliProcess {
 public:
  CliProcess(const std::vector<std::string>& args, const std::filesystem::path& cwd);
  ~CliProcess();  ///< kills the process if still running
  CliProcess(const CliProcess&) = delete;
  CliProcess& operator=(const CliProcess&) = delete;

  void signal(int sig) const;
  /// What it printed on stdout so far.
  [[nodiscard]] std::string outSoFar() const;
  /// Waits for the process to end and returns what it printed.
  CliResult wait();
  /// The same, but kills it (exit code 128 + SIGKILL) when it has not ended within `limit`.
  CliResult wait(std::chrono::milliseconds limit);

 private:
  pid_t pid_ = -1;
  std::filesystem::path outPath_;
  std::filesystem::path errPath_;
};

/// Reads a whole file ("" when missing).
std::string readFile(const std::filesystem::path& path);

/// Whether `needle` occurs in `haystack` (for output checks).
inline bool contains(const std::string& haystack, const std::string& needle) {
  return haystack.find(needle) != std::string::npos;
}

/// The non-empty lines of `text`.
inline std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) out.push_back(line);
  }
  return out;
}

}  // namespace throng::e2e
