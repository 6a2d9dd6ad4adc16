// `throng link` and the example host in C (examples/link_host.c) run together as users would:
// the host launches throng; throng runs first and the host attaches by name; the UNIX-socket
// handshake. In each the guided group must follow the avatar (the host checks and exits 0). Also:
// a version mismatch is refused by both sides, and a crashed host is detected and the segment
// removed. Names carry the test's pid, so `ctest -j` runs stay apart.
#include <gtest/gtest.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>
#include <thread>

#include <fcntl.h>
#include <spawn.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include "throng/link/segment.hpp"
#include "throng/throng_link.h"

extern char** environ;

namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

const std::string kScenario = std::string(THRONG_SOURCE_DIR) + "/tests/link/link_square.json";

std::string readFile(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A child process whose stdout and stderr go to files in a scratch directory.
class Process {
 public:
  Process(const std::string& exe, const std::vector<std::string>& args, const fs::path& dir, const std::string& tag)
      : out_(dir / (tag + ".out")), err_(dir / (tag + ".err")) {
    std::vector<std::string> all{exe};
    all.insert(all.end(), args.begin(), args.end());
    std::vector<char*> argv;
    for (auto& a : all) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, 1, out_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    posix_spawn_file_actions_addopen(&actions, 2, err_.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (posix_spawn(&pid_, exe.c_str(), &actions, nullptr, argv.data(), environ) != 0) pid_ = -1;
    posix_spawn_file_actions_destroy(&actions);
  }
  ~Process() {
    if (pid_ > 0) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  [[nodiscard]] std::string out() const { return readFile(out_); }
  [[nodiscard]] std::string err() const { return readFile(err_); }
  void signal(int sig) const { kill(pid_, sig); }
  /// Waits until stdout (stderr with `onStderr`) contains `text` (true) or `limit` passed.
  bool waitFor(const std::string& text, std::chrono::milliseconds limit = 10s, bool onStderr = false) const {
    const auto end = std::chrono::steady_clock::now() + limit;
    while (std::chrono::steady_clock::now() < end) {
      if ((onStderr ? err() : out()).find(text) != std::string::npos) return true;
      std::this_thread::sleep_for(20ms);
    }
    return false;
  }
  /// Exit status (128 + signal when killed); -1 when it did not end within `limit` (then killed).
  int wait(std::chrono::milliseconds limit = 20s) {
    const auto end = std::chrono::steady_clock::now() + limit;
    int status = 0;
    while (std::chrono::steady_clock::now() < end) {
      if (waitpid(pid_, &status, WNOHANG) == pid_) {
        pid_ = -1;
        return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      }
      std::this_thread::sleep_for(10ms);
    }
    return -1;
  }

 private:
  pid_t pid_ = -1;
  fs::path out_, err_;
};

class LinkE2E : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string test = ::testing::UnitTest::GetInstance()->current_test_info()->name();
    tag_ = std::to_string(getpid()) + "-" + test;
    dir_ = fs::temp_directory_path() / ("throng-link-" + tag_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    shm_unlink(name().c_str());
    fs::remove_all(dir_);
  }
  [[nodiscard]] std::string name() const { return "/throng-e2e-" + tag_; }
  [[nodiscard]] bool segmentExists() const {
    const int fd = shm_open(name().c_str(), O_RDONLY, 0);
    if (fd >= 0) close(fd);
    return fd >= 0;
  }
  std::unique_ptr<Process> throng(std::vector<std::string> args, const std::string& tag = "throng") {
    args.insert(args.begin(), "link");
    return std::make_unique<Process>(THRONG_EXE, args, dir_, tag);
  }
  /// Attaches to `segment` as a host would (throng_link_attach, a heartbeat and one input).
  static bool attachAsHost(throng_link& link, const std::string& segment, Process& crowd) {
    char error[512];
    if (throng_link_open(&link, segment.c_str(), 5000, error, sizeof error) != 0) {
      ADD_FAILURE() << error;
      return false;
    }
    throng_link_attach(&link);
    const throng_link_avatar avatar{7, 5.0f, 5.0f, 0.0f, 0.0f};
    throng_link_write_input(&link, &avatar, 1, nullptr, 0, nullptr, 0);
    return crowd.waitFor("host attached");
  }
  /// Keeps the host's heartbeat going for `time`.
  static void beatFor(throng_link& link, std::chrono::milliseconds time) {
    const auto end = std::chrono::steady_clock::now() + time;
    while (std::chrono::steady_clock::now() < end) {
      throng_link_host_beat(&link);
      std::this_thread::sleep_for(20ms);
    }
  }
  std::unique_ptr<Process> host(const std::vector<std::string>& args) {
    return std::make_unique<Process>(THRONG_LINK_HOST_EXE, args, dir_, "host");
  }
  /// The host's report must say the group followed, and a crowd came and went (a bad one refused).
  static void expectFollowed(Process& h, int code) {
    EXPECT_EQ(code, 0) << h.out() << h.err();
    EXPECT_NE(h.out().find("the group follows the avatar"), std::string::npos) << h.out();
    EXPECT_NE(h.out().find("host: crowd inserted: "), std::string::npos) << h.out();
    EXPECT_NE(h.out().find("host: crowd removed: "), std::string::npos) << h.out();
    EXPECT_NE(h.out().find("a bad crowd is refused with status 2:"), std::string::npos) << h.out();
    EXPECT_NE(h.out().find("status 2: host request 9:1:"), std::string::npos) << h.out();  // where it is wrong
  }
  std::string tag_;
  fs::path dir_;
};

TEST_F(LinkE2E, HostLaunchesThrong) {
  auto h = host({"--launch", THRONG_EXE, kScenario, "--shm", name(), "--seconds", "3", "--", "--tick", "100"});
  const int code = h->wait(30s);
  expectFollowed(*h, code);
  EXPECT_NE(h->out().find("throng link exited with status 0"), std::string::npos) << h->out();
  EXPECT_FALSE(segmentExists()) << "throng removes the segment when its host detaches";
}

// The control: the same walk without an active guide record. The followed group stands still in
// tests/link/link_square.json, so only guiding can bring it to the avatar; without it the host must
// report that the group did not follow (and exit 1). Guards the check above against passing by drift.
TEST_F(LinkE2E, WithoutGuidingTheGroupDoesNotCome) {
  auto h = host({"--launch", THRONG_EXE, kScenario, "--shm", name(), "--seconds", "3", "--no-guide", "--", "--tick",
                 "100"});
  const int code = h->wait(30s);
  EXPECT_EQ(code, 1) << h->out() << h->err();
  EXPECT_NE(h->out().find("does not ask the group to follow"), std::string::npos) << h->out();
  EXPECT_NE(h->out().find("the group did NOT follow the avatar"), std::string::npos) << h->out();
  EXPECT_EQ(h->out().find("the group follows the avatar"), std::string::npos) << h->out();
}

TEST_F(LinkE2E, ThrongFirstThenHostAttachesByName) {
  auto t = throng({"--shm", name(), kScenario, "--tick", "100"});
  ASSERT_TRUE(t->waitFor("waiting for a host")) << t->out() << t->err();
  EXPECT_TRUE(segmentExists());
  auto h = host({"--shm", name(), "--seconds", "3"});
  expectFollowed(*h, h->wait(30s));
  EXPECT_EQ(t->wait(10s), 0) << t->out() << t->err();
  EXPECT_NE(t->out().find("host attached"), std::string::npos) << t->out();
  EXPECT_NE(t->out().find("host detached"), std::string::npos) << t->out();
  EXPECT_FALSE(segmentExists());
}

TEST_F(LinkE2E, SocketHandshakePassesTheName) {
  const std::string socketPath = (dir_ / "link.sock").string();
  auto t = throng({"--socket", socketPath, "--shm", name(), kScenario, "--tick", "100"});
  ASSERT_TRUE(t->waitFor("waiting for a host")) << t->out() << t->err();
  auto h = host({"--socket", socketPath, "--seconds", "3"});
  expectFollowed(*h, h->wait(30s));
  EXPECT_NE(h->out().find("says the segment is " + name()), std::string::npos) << h->out();
  EXPECT_EQ(t->wait(10s), 0) << t->out() << t->err();
  EXPECT_FALSE(fs::exists(socketPath)) << "the socket file is removed";
}

TEST_F(LinkE2E, HostRefusesASegmentOfAnotherVersion) {
  // A segment that claims layout version 99, made by hand.
  throng::link::SegmentOptions o;
  const throng::link::Layout layout = throng::link::computeLayout(o);
  const int fd = shm_open(name().c_str(), O_RDWR | O_CREAT | O_EXCL, 0600);
  ASSERT_GE(fd, 0);
  ASSERT_EQ(ftruncate(fd, static_cast<off_t>(layout.totalSize)), 0);
  void* memory = mmap(nullptr, layout.totalSize, PROT_READ | PROT_WRITE, MAP_SHARED, fd, 0);
  close(fd);
  ASSERT_NE(memory, MAP_FAILED);
  auto* header = static_cast<throng_link_header*>(memory);
  throng::link::initHeader(*header, o, layout);
  header->version = 99;
  header->crowd_state = THRONG_LINK_CROWD_RUNNING;
  auto h = host({"--shm", name(), "--seconds", "1"});
  EXPECT_EQ(h->wait(10s), 1);
  EXPECT_NE(h->err().find("layout version 99 but this host was built for version 2: refused"), std::string::npos)
      << h->err();
  munmap(memory, layout.totalSize);
}

TEST_F(LinkE2E, CrowdRefusesAHostOfAnotherVersion) {
  const std::string socketPath = (dir_ / "link.sock").string();
  auto t = throng({"--socket", socketPath, "--shm", name(), kScenario, "--tick", "100"});
  ASSERT_TRUE(t->waitFor("waiting for a host")) << t->out() << t->err();
  // Over the socket: a host line with version 99 gets "REFUSED".
  {
    const int fd = socket(AF_UNIX, SOCK_STREAM, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    std::snprintf(address.sun_path, sizeof address.sun_path, "%s", socketPath.c_str());
    ASSERT_EQ(connect(fd, reinterpret_cast<sockaddr*>(&address), sizeof address), 0);
    const std::string hello = "THRONG-LINK-HOST 99\n";
    ASSERT_EQ(write(fd, hello.data(), hello.size()), static_cast<ssize_t>(hello.size()));
    std::string got;
    char buffer[512];
    for (ssize_t n; got.find("REFUSED") == std::string::npos && (n = read(fd, buffer, sizeof buffer)) > 0;) {
      got.append(buffer, static_cast<std::size_t>(n));
    }
    close(fd);
    EXPECT_NE(got.find("THRONG-LINK " + std::to_string(THRONG_LINK_VERSION) + " " + name() + "\n"), std::string::npos) << got;
    EXPECT_NE(got.find("REFUSED host speaks link version 99, this crowd speaks version 2"), std::string::npos) << got;
  }
  // In the segment: a host announcing version 99 is marked REFUSED with the reason.
  throng_link link{};
  char error[512];
  ASSERT_EQ(throng_link_open(&link, name().c_str(), 5000, error, sizeof error), 0) << error;
  link.header->host_version = 99;
  link.header->host_pid = static_cast<std::int32_t>(getpid());
  __atomic_store_n(&link.header->host_state, THRONG_LINK_HOST_ATTACHED, __ATOMIC_RELEASE);
  const auto end = std::chrono::steady_clock::now() + 5s;
  while (__atomic_load_n(&link.header->host_state, __ATOMIC_ACQUIRE) != THRONG_LINK_HOST_REFUSED &&
         std::chrono::steady_clock::now() < end) {
    std::this_thread::sleep_for(10ms);
  }
  EXPECT_EQ(link.header->host_state, THRONG_LINK_HOST_REFUSED);
  EXPECT_NE(std::string(link.header->message).find("speaks link version 99"), std::string::npos)
      << link.header->message;
  EXPECT_EQ(throng_link_crowd_alive(&link), 0) << "a refused host sees the link as closed";
  munmap(link.header, link.size);
  t->signal(SIGINT);
  EXPECT_EQ(t->wait(10s), 130);
  EXPECT_NE(t->err().find("refused"), std::string::npos) << t->err();
  EXPECT_FALSE(segmentExists());
}

TEST_F(LinkE2E, CrashedHostIsDetectedAndTheSegmentRemoved) {
  auto t = throng({"--shm", name(), kScenario, "--tick", "40", "--host-timeout", "0.5"});
  ASSERT_TRUE(t->waitFor("waiting for a host")) << t->out() << t->err();
  auto h = host({"--shm", name(), "--seconds", "60"});
  ASSERT_TRUE(t->waitFor("host attached")) << t->out() << t->err();
  ASSERT_TRUE(h->waitFor("asks the group to follow")) << h->out() << h->err();
  h->signal(SIGKILL);
  EXPECT_EQ(h->wait(5s), 128 + SIGKILL);
  EXPECT_EQ(t->wait(10s), 1) << t->out() << t->err();
  EXPECT_NE(t->err().find("host stopped: no heartbeat for"), std::string::npos) << t->err();
  EXPECT_FALSE(segmentExists()) << "the crowd removes the segment";
}

TEST_F(LinkE2E, AnExistingSegmentIsRefusedUnlessForced) {
  auto first = throng({"--shm", name(), kScenario, "--duration", "5"});
  ASSERT_TRUE(first->waitFor("waiting for a host")) << first->out() << first->err();
  auto second = std::make_unique<Process>(THRONG_EXE, std::vector<std::string>{"link", "--shm", name(), kScenario},
                                          dir_, "second");
  EXPECT_EQ(second->wait(10s), 1);
  EXPECT_NE(second->err().find("exists already"), std::string::npos) << second->err();
  first->signal(SIGINT);
  EXPECT_EQ(first->wait(10s), 130);
}

TEST_F(LinkE2E, ADamagedHeaderStopsTheCrowdCleanly) {
  // A host (buggy or hostile) overwrites a field of the header while the crowd runs. The crowd
  // addresses the segment from its own copy of the layout, so nothing it reads or writes moves;
  // it notices, says which field, stops with exit 1 and removes the segment. (These used to be
  // SIGSEGV, leaving the segment in /dev/shm.)
  const std::vector<std::pair<std::string, std::function<void(throng_link_header&)>>> damages = {
      {"frame_offset[1]", [](throng_link_header& h) { h.frame_offset[1] = std::uint64_t{1} << 40; }},
      {"max_avatars",
       [](throng_link_header& h) {
         throng_link_input_of(&h)->avatar_count = 0xffffffffu;  // the count a too-large capacity lets through
         h.max_avatars = 0xffffffffu;
       }},
      {"host_offset", [](throng_link_header& h) { h.host_offset = std::uint64_t{1} << 40; }},
      {"max_detailed", [](throng_link_header& h) { h.max_detailed = 0xffffffffu; }},
      {"the magic", [](throng_link_header& h) { h.magic = 0; }},
      {"the layout version", [](throng_link_header& h) { h.version = 99; }},
  };
  for (std::size_t i = 0; i < damages.size(); ++i) {
    const auto& [field, damage] = damages[i];
    SCOPED_TRACE(field);
    const std::string segment = name() + "-" + std::to_string(i);
    auto t = throng({"--shm", segment, kScenario, "--tick", "40", "--host-timeout", "30"}, "throng" + std::to_string(i));
    ASSERT_TRUE(t->waitFor("waiting for a host")) << t->out() << t->err();
    throng_link link{};
    ASSERT_TRUE(attachAsHost(link, segment, *t)) << t->out() << t->err();
    beatFor(link, 200ms);  // a few ticks with the host's input applied
    damage(*link.header);
    EXPECT_EQ(t->wait(10s), 1) << t->out() << t->err();
    EXPECT_NE(t->err().find("the segment's header was overwritten (" + field + " is "), std::string::npos) << t->err();
    EXPECT_NE(t->err().find("segment " + segment + " removed"), std::string::npos) << t->err();
    EXPECT_EQ(__atomic_load_n(&link.header->crowd_state, __ATOMIC_ACQUIRE), THRONG_LINK_CROWD_STOPPED);
    EXPECT_NE(std::string(link.header->message).find("overwritten"), std::string::npos) << link.header->message;
    munmap(link.header, link.size);
    const int fd = shm_open(segment.c_str(), O_RDONLY, 0);
    EXPECT_LT(fd, 0) << "the segment is removed";
    if (fd >= 0) {
      close(fd);
      shm_unlink(segment.c_str());
    }
  }
}

TEST_F(LinkE2E, TheHostsInputIsCheckedBeforeUse) {
  // Counts past the capacities and avatars that are not finite numbers are refused with a
  // warning (once each); the crowd runs on and ends normally when the host detaches.
  auto t = throng({"--shm", name(), kScenario, "--tick", "40", "--host-timeout", "30"});
  ASSERT_TRUE(t->waitFor("waiting for a host")) << t->out() << t->err();
  throng_link link{};
  ASSERT_TRUE(attachAsHost(link, name(), *t)) << t->out() << t->err();
  throng_link_header& h = *link.header;
  throng_link_input* in = throng_link_input_of(&h);
  const std::uint64_t seq = __atomic_load_n(&in->seq, __ATOMIC_RELAXED);
  __atomic_store_n(&in->seq, seq + 1, __ATOMIC_RELEASE);
  throng_link_input_avatars(&h)[0] = {7, std::numeric_limits<float>::quiet_NaN(), 5.0f, 0.0f, 0.0f};
  throng_link_input_avatars(&h)[1] = {8, 5.0f, std::numeric_limits<float>::infinity(), 0.0f, 0.0f};
  throng_link_input_guides(&h)[0] = {0, 0, 1, 0};
  in->avatar_count = 1000;  // more than --max-avatars (16)
  in->guide_count = 1;
  in->detail_count = 0;
  __atomic_store_n(&in->seq, seq + 2, __ATOMIC_RELEASE);
  for (const std::string expected :
       {"warning: avatar_count 1000 is more than max_avatars 16: only the first 16 are read",
        "warning: avatar 0 (id 7) has a position or heading that is not a finite number within 1000000 m: ignored",
        "warning: avatar 1 (id 8) has a position or heading",
        "warning: guide record for group 0 ignored: its avatar's position is not usable"}) {
    EXPECT_TRUE(t->waitFor(expected, 5s, true)) << expected << "\n" << t->err();
  }
  beatFor(link, 300ms);
  __atomic_store_n(&h.host_state, THRONG_LINK_HOST_DETACHED, __ATOMIC_RELEASE);
  EXPECT_EQ(t->wait(10s), 0) << t->out() << t->err();
  const std::string err = t->err();
  EXPECT_EQ(err.find("avatar_count 1000"), err.rfind("avatar_count 1000")) << "said once:\n" << err;
  munmap(link.header, link.size);
  EXPECT_FALSE(segmentExists());
}

}  // namespace
