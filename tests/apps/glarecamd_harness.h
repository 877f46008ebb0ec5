// glarecamd as systemd runs it, for the tests that start it as a process
// (glarecamd_process_test.cpp, glarecamd_status_page_test.cpp): a fake NOTIFY_SOCKET, the process
// with its log, polling with a timeout, a directory's entries, and the lab rig of those tests.
#pragma once

#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <filesystem>
#include <optional>
#include <string>
#include <thread>
#include <vector>

extern char** environ;

namespace glarecam::testing {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;

inline constexpr auto kStartTimeout = 60s;  // a loaded CI machine, under a sanitizer

// A datagram socket at `path`, as systemd's NOTIFY_SOCKET.
class NotifySocket {
 public:
  explicit NotifySocket(const fs::path& path) : path_(path) {
    fd_ = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
    sockaddr_un address{};
    address.sun_family = AF_UNIX;
    // A longer path would be cut short here but not in glarecamd: name the cause (TMPDIR).
    EXPECT_LT(path.native().size(), sizeof(address.sun_path)) << path << ": too long for a socket";
    std::strncpy(address.sun_path, path.c_str(), sizeof(address.sun_path) - 1);
    EXPECT_EQ(bind(fd_, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0)
        << std::strerror(errno);
  }
  ~NotifySocket() { close(fd_); }
  const fs::path& path() const { return path_; }

  // The next message within `timeout`, or nullopt.
  std::optional<std::string> receive(std::chrono::milliseconds timeout) {
    pollfd poll_fd{fd_, POLLIN, 0};
    if (poll(&poll_fd, 1, static_cast<int>(timeout.count())) != 1) return std::nullopt;
    char buffer[4096];
    const ssize_t n = recv(fd_, buffer, sizeof(buffer), 0);
    if (n < 0) return std::nullopt;
    std::string message(buffer, static_cast<std::size_t>(n));
    received_.push_back({Clock::now(), message});
    return message;
  }
  // Reads until a message starting with `prefix` (true) or the timeout (false).
  bool waitFor(const std::string& prefix, std::chrono::seconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (Clock::now() < deadline) {
      const auto message =
          receive(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()));
      if (message && message->starts_with(prefix)) return true;
    }
    return false;
  }
  struct Received {
    Clock::time_point at;
    std::string message;
  };
  const std::vector<Received>& received() const { return received_; }

 private:
  fs::path path_;
  int fd_ = -1;
  std::vector<Received> received_;
};

class Process {
 public:
  Process(const std::vector<std::string>& args, const std::vector<std::string>& env,
          const fs::path& log) {
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    std::vector<std::string> environment;
    for (char** e = environ; *e; ++e)
      if (!std::string_view(*e).starts_with("NOTIFY_SOCKET=") &&
          !std::string_view(*e).starts_with("WATCHDOG_"))
        environment.emplace_back(*e);
    for (const std::string& e : env) environment.push_back(e);
    std::vector<char*> envp;
    for (const std::string& e : environment) envp.push_back(const_cast<char*>(e.c_str()));
    envp.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(),
                                     O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
    EXPECT_EQ(posix_spawn(&pid_, argv[0], &actions, nullptr, argv.data(), envp.data()), 0);
    posix_spawn_file_actions_destroy(&actions);
  }
  ~Process() {
    if (pid_ > 0 && !status_) {
      kill(pid_, SIGKILL);
      waitpid(pid_, nullptr, 0);
    }
  }
  pid_t pid() const { return pid_; }
  void signal(int number) { kill(pid_, number); }
  // The exit status (or 128 + the signal), within `timeout`; nullopt if it is still running.
  std::optional<int> wait(std::chrono::seconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (!status_ && Clock::now() < deadline) {
      int status = 0;
      if (waitpid(pid_, &status, WNOHANG) == pid_)
        status_ = WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
      else
        std::this_thread::sleep_for(20ms);
    }
    return status_;
  }

 private:
  pid_t pid_ = -1;
  std::optional<int> status_;
};

inline std::vector<fs::path> entries(const fs::path& directory, bool temporaries) {
  std::vector<fs::path> found;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(directory, error))
    if (entry.path().filename().string().starts_with(".tmp-") == temporaries)
      found.push_back(entry.path());
  return found;
}

// Polls `condition` every 50 ms until it holds or `timeout` passes.
template <typename Condition>
bool eventually(Condition condition, std::chrono::seconds timeout) {
  const auto deadline = Clock::now() + timeout;
  while (Clock::now() < deadline) {
    if (condition()) return true;
    std::this_thread::sleep_for(50ms);
  }
  return condition();
}

// The lab rig of these tests: a lamp on the horizon due south, the module on a table tilted 50°
// facing it (α 40°), the simulated inclinometer; `camera` and the sections that follow vary.
inline std::string labRig(const std::string& camera) {
  return "camera = \"" + camera + R"("
[source]
elevation_deg = 0
azimuth_deg = 180
[module]
azimuth_deg = 180
[inclinometer]
uri = "sim:50"
samples = 4
)";
}

}  // namespace glarecam::testing
