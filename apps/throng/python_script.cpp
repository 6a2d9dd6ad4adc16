// Running a bundled Python script — see python_script.hpp.
#include "python_script.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <fmt/format.h>

#include "commands.hpp"
#include "output.hpp"

namespace throng::cli {
namespace {

namespace fs = std::filesystem;

volatile sig_atomic_t gChild = 0;

/// SIGINT/SIGTERM while the script runs: passed on to it (a terminal's Ctrl-C reaches it anyway).
void forwardSignal(int sig) {
  if (gChild > 0) ::kill(static_cast<pid_t>(gChild), sig);
}

/// Waits for `pid`, passing SIGINT/SIGTERM on to it; its wait status.
int waitForwardingSignals(pid_t pid) {
  gChild = pid;
  struct sigaction forward {};
  forward.sa_handler = forwardSignal;
  struct sigaction oldInt {}, oldTerm {};
  ::sigaction(SIGINT, &forward, &oldInt);
  ::sigaction(SIGTERM, &forward, &oldTerm);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  ::sigaction(SIGINT, &oldInt, nullptr);
  ::sigaction(SIGTERM, &oldTerm, nullptr);
  gChild = 0;
  return status;
}

}  // namespace

fs::path findBundledScript(const fs::path& exe, std::string_view name, const fs::path& sourceScripts) {
  std::vector<fs::path> candidates;
  if (!exe.empty()) candidates.push_back((exe.parent_path() / "../share/throng/scripts" / name).lexically_normal());
  candidates.push_back(sourceScripts / name);
  for (const auto& c : candidates) {
    std::error_code ec;
    if (fs::is_regular_file(c, ec)) return c;
  }
  return {};
}

std::string findPython() {
  if (::access("/usr/bin/python3", X_OK) == 0) return "/usr/bin/python3";
  const char* path = std::getenv("PATH");
  std::string dirs = path ? path : "";
  std::size_t start = 0;
  while (start <= dirs.size()) {
    const std::size_t end = std::min(dirs.find(':', start), dirs.size());
    const fs::path candidate = fs::path(dirs.substr(start, end - start)) / "python3";
    if (end > start && ::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    start = end + 1;
  }
  return {};
}

int runScriptAndWait(const std::vector<std::string>& argv, std::string_view command) {
  std::vector<char*> raw;
  for (const auto& a : argv) raw.push_back(const_cast<char*>(a.c_str()));
  raw.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) {
    printLine(stderr, fmt::format("throng {}: error: cannot start {}: {}", command, argv[0], std::strerror(errno)));
    return kExitFailure;
  }
  if (pid == 0) {
    ::execv(raw[0], raw.data());
    std::fprintf(stderr, "throng %.*s: error: cannot run %s: %s\n", static_cast<int>(command.size()), command.data(),
                 raw[0], std::strerror(errno));
    ::_exit(127);
  }
  const int status = waitForwardingSignals(pid);
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return WIFSIGNALED(status) ? 128 + WTERMSIG(status) : kExitFailure;
}

}  // namespace throng::cli
