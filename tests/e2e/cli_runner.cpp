// End-to-end test support — see cli_runner.hpp. fork/exec with stdout and stderr redirected to
// files in the working directory's parent scratch area; no shell, so arguments need no quoting.
#include "cli_runner.hpp"

#include <atomic>
#include <cerrno>
#include <csignal>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <thread>

#include <fcntl.h>
#include <pty.h>
#include <sys/ioctl.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef THRONG_EXE
#error "THRONG_EXE must name the throng binary"
#endif

namespace throng::e2e {
namespace fs = std::filesystem;

namespace {

std::atomic<int> gCounter{0};

fs::path uniqueOutputPath(const char* stream) {
  return fs::temp_directory_path() /
         ("throng-cli-" + std::to_string(::getpid()) + "-" + std::to_string(gCounter++) + "." + stream);
}

/// Starts throng with `args` in `cwd`, stdin from /dev/null and stdout into the file `out`;
/// stderr goes into the file `err`, or to the descriptor `errFd` when it is >= 0 (a terminal).
/// `closeFd` (>= 0) is closed in the child (the terminal's other end).
pid_t spawn(const std::vector<std::string>& args, const fs::path& cwd, const fs::path& out, const fs::path& err,
            int errFd = -1, int closeFd = -1) {
  std::vector<std::string> argvStrings{THRONG_EXE};
  argvStrings.insert(argvStrings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argvStrings) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    // Child: only async-signal-safe calls until exec.
    const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = errFd >= 0 ? errFd : ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int in = ::open("/dev/null", O_RDONLY);
    if (o < 0 || e < 0 || in < 0 || ::chdir(cwd.c_str()) != 0) ::_exit(126);
    if (closeFd >= 0) ::close(closeFd);
    ::dup2(in, 0);
    ::dup2(o, 1);
    ::dup2(e, 2);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return pid;
}

int waitFor(pid_t pid) {
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return 128 + WTERMSIG(status);
  return -1;
}

}  // namespace

ScratchDir::ScratchDir(const std::string& tag) {
  path_ = fs::temp_directory_path() /
          ("throng-e2e-" + tag + "-" + std::to_string(::getpid()) + "-" + std::to_string(gCounter++));
  fs::remove_all(path_);
  fs::create_directories(path_);
}

ScratchDir::~ScratchDir() {
  std::error_code ec;
  fs::remove_all(path_, ec);
}

fs::path ScratchDir::write(const std::string& name, const std::string& text) const {
  const fs::path p = path_ / name;
  std::ofstream(p, std::ios::binary) << text;
  return p;
}

std::string readFile(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

CliResult runThrong(const std::vector<std::string>& args, const fs::path& cwd) {
  CliProcess process(args, cwd);
  return process.wait();
}

CliResult runThrongInTerminal(const std::vector<std::string>& args, const fs::path& cwd, int columns) {
  winsize size{};
  size.ws_row = 24;
  size.ws_col = static_cast<unsigned short>(columns);
  int master = -1, slave = -1;
  if (::openpty(&master, &slave, nullptr, nullptr, &size) != 0) throw std::runtime_error("openpty failed");
  const fs::path outPath = uniqueOutputPath("out");
  const pid_t pid = spawn(args, cwd, outPath, {}, slave, master);
  ::close(slave);
  CliResult r;
  char buf[4096];
  while (true) {
    const ssize_t n = ::read(master, buf, sizeof buf);
    if (n > 0) {
      r.err.append(buf, static_cast<std::size_t>(n));
    } else if (n < 0 && errno == EINTR) {
      continue;
    } else {
      break;  // EIO once the child has closed the terminal
    }
  }
  ::close(master);
  r.exitCode = waitFor(pid);
  r.out = readFile(outPath);
  std::error_code ec;
  fs::remove(outPath, ec);
  return r;
}

CliProcess::CliProcess(const std::vector<std::string>& args, const fs::path& cwd)
    : outPath_(uniqueOutputPath("out")), errPath_(uniqueOutputPath("err")) {
  pid_ = spawn(args, cwd, outPath_, errPath_);
}

CliProcess::~CliProcess() {
  if (pid_ > 0) {
    ::kill(pid_, SIGKILL);
    waitFor(pid_);
  }
  std::error_code ec;
  fs::remove(outPath_, ec);
  fs::remove(errPath_, ec);
}

void CliProcess::signal(int sig) const {
  if (pid_ > 0) ::kill(pid_, sig);
}

CliResult CliProcess::wait() {
  CliResult r;
  r.exitCode = waitFor(pid_);
  pid_ = -1;
  r.out = readFile(outPath_);
  r.err = readFile(errPath_);
  return r;
}

CliResult CliProcess::wait(std::chrono::milliseconds limit) {
  const auto end = std::chrono::steady_clock::now() + limit;
  while (pid_ > 0 && std::chrono::steady_clock::now() < end) {
    int status = 0;
    const pid_t done = ::waitpid(pid_, &status, WNOHANG);
    if (done == pid_) {
      CliResult r;
      r.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      pid_ = -1;
      r.out = readFile(outPath_);
      r.err = readFile(errPath_);
      return r;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  signal(SIGKILL);
  return wait();
}

std::string CliProcess::outSoFar() const { return readFile(outPath_); }

}  // namespace throng::e2e
