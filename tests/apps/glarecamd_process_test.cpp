// glarecamd as systemd runs it: a real process, its notify messages read from a fake
// NOTIFY_SOCKET (a datagram socket this test binds), its signals, its exit statuses, SIGKILL at
// random moments while it writes (no partial stack ever visible, the next start cleans up), and
// Aravis's fake GigE Vision camera killed under it. Timing only bounds waits (every wait is for
// an event, with a generous timeout); nothing asserts how fast anything is.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <spawn.h>
#include <sys/inotify.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "apps/glarecamd_harness.h"
#include "core/build_config.h"
#include "core/json.h"
#include "core/stack_io.h"
#include "support/test_support.h"

namespace glarecam {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using Clock = std::chrono::steady_clock;
// The harness (apps/glarecamd_harness.h): NotifySocket, Process, eventually, entries, labRig.
using namespace testing;

// The rig of the fake GigE Vision camera's tests: its Mono16 calibration (in cal/), the lab rig on
// aravis:127.0.0.1, `sections`, a stack every `interval_s`, reopening after 1, 2, 2 … s and giving
// up after `max_failures`.
std::string fakeCameraRig(const std::string& sections, int interval_s, int max_failures) {
  return "calibration = \"cal/fake-camera-mono16.json\"\n" + labRig("aravis:127.0.0.1") + sections +
         "[schedule]\ninterval_s = " + std::to_string(interval_s) +
         "\n[output]\nroot = \"out\"\nreserve_mb = 1\n[faults]\ncamera_backoff_s = 1\n"
         "camera_backoff_max_s = 2\ncamera_max_failures = " +
         std::to_string(max_failures) + "\n";
}

class GlarecamdProcess : public ::testing::Test {
 protected:
  std::vector<std::string> daemon(std::vector<std::string> args) {
    args.insert(args.begin(), GLARECAMD_PATH);
    return args;
  }
  std::string log() const { return testing::readText(dir_ / "glarecamd.log"); }
  testing::TempDir dir_;
};

TEST_F(GlarecamdProcess, UsageErrorsExit2) {
  const auto run = [&](std::vector<std::string> args) {
    Process process(daemon(std::move(args)), {}, dir_ / "glarecamd.log");
    return process.wait(30s);
  };
  EXPECT_EQ(run({"--no-such-option"}), 2);
  EXPECT_EQ(run({"--simulate"}), 2);  // needs --output
  EXPECT_EQ(run({"--interval", "0", "--simulate", "--output", (dir_ / "o").string()}), 2);
  EXPECT_EQ(run({"--simulate", "--output", (dir_ / "o").string(), "--start", "noon"}), 2);
  EXPECT_EQ(run({"--config", "x.toml", "--simulate", "--output", (dir_ / "o").string()}), 2);
  EXPECT_EQ(run({"--max-use-gib", "0", "--simulate", "--output", (dir_ / "o").string()}), 2);
  EXPECT_NE(log().find("--max-use-gib must be between"), std::string::npos) << log();
  EXPECT_EQ(run({"--reserve-mb", "-1", "--simulate", "--output", (dir_ / "o").string()}), 2);
  EXPECT_NE(log().find("--reserve-mb must be between 0 and"), std::string::npos) << log();
  // The simulated rig's --output is the command line's, not a config's: 2, not 78.
  testing::writeText(dir_ / "a-file", "");
  EXPECT_EQ(run({"--simulate", "--output", (dir_ / "a-file").string(), "--count", "1"}), 2);
  EXPECT_NE(log().find((dir_ / "a-file").string()), std::string::npos) << log();
  EXPECT_EQ(run({"--help"}), 0);
  EXPECT_NE(log().find("SIGHUP reloads the config"), std::string::npos);
}

TEST_F(GlarecamdProcess, InvalidConfigExits78NamingTheLine) {
  testing::writeText(dir_ / "rig.toml", "camera = \"sim:\"\n[schedule]\ninterval_s = \"soon\"\n");
  Process process(daemon({"--config", (dir_ / "rig.toml").string()}), {}, dir_ / "glarecamd.log");
  EXPECT_EQ(process.wait(30s), 78);  // EX_CONFIG: RestartPreventExitStatus=78
  EXPECT_NE(log().find((dir_ / "rig.toml").string() + ":3: schedule.interval_s must be a whole"),
            std::string::npos)
      << log();
  Process missing(daemon({"--config", (dir_ / "none.toml").string()}), {}, dir_ / "glarecamd.log");
  EXPECT_EQ(missing.wait(30s), 78);
}

TEST_F(GlarecamdProcess, SpeaksSystemdsNotifyProtocol) {
  NotifySocket notify(dir_ / "notify.sock");
  const fs::path out = dir_ / "out";
  Process process(daemon({"--simulate", "--output", out.string(), "--interval", "3600", "--camera",
                          "sim:size=320x256"}),
                  {"NOTIFY_SOCKET=" + notify.path().string(), "WATCHDOG_USEC=2000000"},
                  dir_ / "glarecamd.log");
  ASSERT_TRUE(notify.waitFor("READY=1", kStartTimeout)) << log();
  // The first stack at once; then nothing for an hour, but the heartbeat: WATCHDOG_USEC is 2 s,
  // glarecamd pings every second.
  ASSERT_TRUE(eventually([&] { return entries(out / "stacks", false).size() == 1; }, 60s)) << log();
  const auto watch_start = Clock::now();
  while (Clock::now() - watch_start < 4s) notify.receive(100ms);
  std::vector<Clock::time_point> pings;
  for (const auto& m : notify.received())
    if (m.message == "WATCHDOG=1" && m.at >= watch_start) pings.push_back(m.at);
  ASSERT_GE(pings.size(), 2u);
  for (std::size_t i = 1; i < pings.size(); ++i) EXPECT_LT(pings[i] - pings[i - 1], 2s);
  // SIGUSR1: a stack now.
  process.signal(SIGUSR1);
  ASSERT_TRUE(eventually([&] { return entries(out / "stacks", false).size() == 2; }, 60s)) << log();
  bool signalled = false;
  for (const fs::path& stack : entries(out / "stacks", false))
    signalled |= (*readJsonFile((stack / "stack.json").string()))["daemon"]["trigger"] == "signal";
  EXPECT_TRUE(signalled);
  // SIGHUP: the config is read again.
  process.signal(SIGHUP);
  ASSERT_TRUE(eventually([&] { return log().find("reloaded") != std::string::npos; }, 30s))
      << log();
  // SIGTERM: STOPPING=1, a clean exit.
  process.signal(SIGTERM);
  EXPECT_TRUE(notify.waitFor("STOPPING=1", 30s));
  EXPECT_EQ(process.wait(60s), 0) << log();
  bool status_seen = false;
  for (const auto& m : notify.received())
    status_seen |= m.message.starts_with("STATUS=ready, every 3600 s; last ");
  EXPECT_TRUE(status_seen);
}

// The operator's button, polled and debounced on its own thread: the simulated chip's operator
// presses it for 100 ms every 3 s (time enough to process a stack before the next press, even
// on a loaded machine: --count counts stacks done).
TEST_F(GlarecamdProcess, TheButtonTakesAStack) {
  testing::writeText(dir_ / "rig.toml", labRig("sim:size=160x128") + R"([gpio]
chip = "sim:button_period_s=3"
led = 27
button = 22
[schedule]
mode = "button"
[output]
root = "out"
reserve_mb = 1
)");
  Process process(daemon({"--config", (dir_ / "rig.toml").string(), "--count", "2"}), {},
                  dir_ / "glarecamd.log");
  EXPECT_EQ(process.wait(120s), 0) << log();  // --count 2: two presses, two stacks, done
  const auto stacks = entries(dir_ / "out" / "stacks", false);
  ASSERT_EQ(stacks.size(), 2u) << log();
  for (const fs::path& stack : stacks)
    EXPECT_EQ((*readJsonFile((stack / "stack.json").string()))["daemon"]["trigger"], "button");
}

// Staging directories (".tmp-*") appearing in and renamed out of a directory, as inotify
// reports them, each stamped when this test read it.
class StagingWatch {
 public:
  struct Event {
    std::string name;
    bool created = false;  // else renamed away: the commit
    Clock::time_point at;
  };

  explicit StagingWatch(const fs::path& directory) : fd_(inotify_init1(IN_CLOEXEC | IN_NONBLOCK)) {
    EXPECT_GE(inotify_add_watch(fd_, directory.c_str(), IN_CREATE | IN_MOVED_FROM), 0);
  }
  ~StagingWatch() { close(fd_); }

  // The next staging event within `timeout`.
  std::optional<Event> next(std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (pending_.empty() && Clock::now() < deadline) {
      pollfd poll_fd{fd_, POLLIN, 0};
      if (poll(&poll_fd, 1, 20) != 1) continue;
      alignas(inotify_event) char buffer[4096];
      const ssize_t n = read(fd_, buffer, sizeof(buffer));
      for (ssize_t at = 0; at < n;) {
        const auto* event = reinterpret_cast<const inotify_event*>(buffer + at);
        if (event->len && std::string_view(event->name).starts_with(".tmp-"))
          pending_.push_back({event->name, (event->mask & IN_CREATE) != 0, Clock::now()});
        at += static_cast<ssize_t>(sizeof(inotify_event) + event->len);
      }
    }
    if (pending_.empty()) return std::nullopt;
    Event event = pending_.front();
    pending_.erase(pending_.begin());
    return event;
  }
  bool waitForCreation(std::chrono::milliseconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (Clock::now() < deadline) {
      const auto event =
          next(std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()));
      if (event && event->created) return true;
    }
    return false;
  }

 private:
  int fd_;
  std::vector<Event> pending_;
};

// Issue 9: "SIGKILL at random moments while writing (≥ 50 trials): zero partial stacks visible,
// and the next start cleans up temporary directories." How long a stack or result stays staged
// depends on the disk (fsyncs): it is measured first on an undisturbed run; then each trial waits
// until glarecamd starts staging a stack (even trials) or a result (odd ones), kills it a random
// moment into that time and looks at what is visible.
class GlarecamdKills : public ::testing::Test {
 protected:
  std::vector<std::string> simulated(const std::string& interval) const {
    return {GLARECAMD_PATH, "--simulate", "--output",         out_.string(), "--interval",
            interval,       "--camera",   "sim:size=320x256", "-q"};
  }
  // The longest staging time of a directory, over a few undisturbed stacks.
  std::chrono::microseconds stagingTime(const fs::path& watched) {
    StagingWatch watch(watched);
    Process process(simulated("1"), {}, dir_ / "glarecamd.log");
    std::map<std::string, Clock::time_point> created;
    std::chrono::microseconds longest{0};
    int commits = 0;
    const auto deadline = Clock::now() + 60s;
    while (commits < 3 && Clock::now() < deadline) {
      const auto event = watch.next(1000ms);
      if (!event) continue;
      if (event->created) {
        created[event->name] = event->at;
      } else if (created.count(event->name)) {
        longest = std::max(longest, std::chrono::duration_cast<std::chrono::microseconds>(
                                        event->at - created[event->name]));
        ++commits;
      }
    }
    process.signal(SIGTERM);
    process.wait(60s);
    return longest;
  }
  testing::TempDir dir_;
  fs::path out_ = dir_ / "out";
};

// GLARECAM_LONG_CHECKS=1 (`make kill-check`): the checks of half a minute and more that a camera
// lost under the daemon needs (the fake GigE camera killed, a long bracket cut). `make test` keeps
// their small versions: the camera supervisor's and the watchdog's unit tests, the kills below.
bool longChecks() {
  const char* text = std::getenv("GLARECAM_LONG_CHECKS");
  return text && std::string_view(text) == "1";
}

// GLARECAM_KILLS_PER_KIND: kills wanted while a stack, and while a result, is being written.
int killsPerKind() {
  constexpr int kDefaultKillsPerKind = 8;
  const char* text = std::getenv("GLARECAM_KILLS_PER_KIND");
  const int kills = text ? std::atoi(text) : kDefaultKillsPerKind;
  return std::clamp(kills, 1, 25);
}

TEST_F(GlarecamdKills, SigkillWhileWritingLeavesNoPartialStack) {
  const auto test_start = Clock::now();
  // Wanted of each kind, stacks and results: issue 9's 50 kills in all under `make kill-check`
  // (GLARECAM_KILLS_PER_KIND=25), 8 of each in `make test`, where the full run cost 170 s of a
  // loaded 2-core CI machine's time for the same verdict.
  const int kKillsWhileWriting = killsPerKind();
  const int kMaxTrials = 12 * kKillsWhileWriting;
  // On a loaded machine fewer kills land mid-write (start-up jitter outgrows the writes), and the
  // trials once ran into ctest's 300 s timeout. So they stop at a budget from the test's start
  // that leaves the staging measurement before and the restart after room inside that timeout
  // (150 s), and at least 40 % of each kind must have landed (a busy 2-core machine reaches it; an
  // idle one lands all 50 in about 30 s, and 8 of each in a few seconds; with three builds beside
  // it, 8 kills took 57 s).
  constexpr auto kTrialBudget = 150s;
  const int kMinKillsWhileWriting = (2 * kKillsWhileWriting + 4) / 5;
  // A staging time measured too short (both inotify events in one read) still leaves room.
  constexpr std::chrono::microseconds kMinKillWindow{2000};
  fs::create_directories(out_ / "stacks");
  fs::create_directories(out_ / "results");
  const std::array<std::chrono::microseconds, 2> staging{stagingTime(out_ / "stacks"),
                                                         stagingTime(out_ / "results")};
  std::printf("staging a 320x256 stack takes up to %lld µs, its result %lld µs\n",
              static_cast<long long>(staging[0].count()),
              static_cast<long long>(staging[1].count()));
  std::mt19937 random(20261201);
  int trials = 0;
  std::array<int, 2> landed{0, 0};
  while (std::min(landed[0], landed[1]) < kKillsWhileWriting && trials < kMaxTrials &&
         Clock::now() - test_start < kTrialBudget) {
    const int kind =
        landed[0] < kKillsWhileWriting && (landed[1] >= kKillsWhileWriting || trials % 2 == 0) ? 0
                                                                                               : 1;
    ++trials;
    const fs::path watched = out_ / (kind ? "results" : "stacks");
    {
      StagingWatch watch(watched);  // before the process starts: no staging can be missed
      Process process(simulated("1"), {}, dir_ / "glarecamd.log");
      if (!watch.waitForCreation(30s)) continue;
      std::uniform_int_distribution<long long> delay_us(
          0, std::max(staging[kind], kMinKillWindow).count());
      std::this_thread::sleep_for(std::chrono::microseconds(delay_us(random)));
      process.signal(SIGKILL);
      process.wait(30s);
    }
    landed[kind] += !entries(watched, true).empty();  // the kill left its staging directory
    for (const fs::path& stack : entries(out_ / "stacks", false)) {
      const auto read = readStack(stack);
      ASSERT_TRUE(read) << "trial " << trials << ": " << read.error().message;
    }
    for (const fs::path& result : entries(out_ / "results", false))
      ASSERT_TRUE(fs::exists(result / "result.json")) << "trial " << trials << ": " << result;
  }
  std::printf(
      "SIGKILL: %d trials in %.0f s, %d while a stack and %d while a result was being written "
      "(%d of each wanted, %d required); %zu stacks\n",
      trials, std::chrono::duration<double>(Clock::now() - test_start).count(), landed[0],
      landed[1], kKillsWhileWriting, kMinKillsWhileWriting, entries(out_ / "stacks", false).size());
  EXPECT_GE(landed[0], kMinKillsWhileWriting);
  EXPECT_GE(landed[1], kMinKillsWhileWriting);
  // The next start removes what the kills left half-written, and processes what was not.
  std::vector<fs::path> left;
  for (const char* directory : {"stacks", "results"})
    for (const fs::path& temporary : entries(out_ / directory, true)) left.push_back(temporary);
  NotifySocket notify(dir_ / "notify.sock");
  auto args = simulated("3600");
  args.pop_back();  // not -q
  Process process(args, {"NOTIFY_SOCKET=" + notify.path().string()}, dir_ / "glarecamd.log");
  ASSERT_TRUE(notify.waitFor("READY=1", kStartTimeout));
  for (const fs::path& temporary : left) EXPECT_FALSE(fs::exists(temporary)) << temporary;
  ASSERT_TRUE(eventually(
      [&] {
        return entries(out_ / "results", false).size() == entries(out_ / "stacks", false).size();
      },
      120s));
  process.signal(SIGTERM);
  EXPECT_EQ(process.wait(60s), 0);
  EXPECT_TRUE(entries(out_ / "results", true).empty());
  EXPECT_TRUE(entries(out_ / "stacks", true).empty());
}

#if GLARECAM_WITH_ARAVIS
// The camera lost under a running daemon: Aravis's fake GigE Vision camera, killed.
TEST_F(GlarecamdProcess, FakeGigECameraKilledAndRestarted) {
  if (!longChecks()) GTEST_SKIP() << "a long check (44 s): make kill-check runs it";
  const fs::path cal = dir_ / "cal";
  const auto startFake = [&] {
    return std::make_unique<Process>(
        std::vector<std::string>{GLARECAM_PATH, "fake-camera", "--size", "320x256",
                                 "--calibration-out", cal.string()},
        std::vector<std::string>{}, dir_ / "fake.log");
  };
  auto fake = startFake();
  ASSERT_TRUE(eventually([&] { return fs::exists(cal / "fake-camera-mono16.json"); }, 30s));
  testing::writeText(dir_ / "rig.toml", fakeCameraRig("", 2, 6));
  NotifySocket notify(dir_ / "notify.sock");
  Process process(daemon({"--config", (dir_ / "rig.toml").string()}),
                  {"NOTIFY_SOCKET=" + notify.path().string()}, dir_ / "glarecamd.log");
  ASSERT_TRUE(notify.waitFor("READY=1", kStartTimeout)) << log();
  const fs::path stacks = dir_ / "out" / "stacks";
  ASSERT_TRUE(eventually([&] { return !entries(stacks, false).empty(); }, 60s)) << log();
  fake.reset();  // SIGKILL
  ASSERT_TRUE(notify.waitFor("STATUS=waiting for the camera", 60s)) << log();
  for (const fs::path& stack : entries(stacks, false)) EXPECT_TRUE(readStack(stack)) << stack;
  // Back: the daemon reopens it and captures again.
  fake = startFake();
  const std::size_t before = entries(stacks, false).size();
  ASSERT_TRUE(eventually([&] { return entries(stacks, false).size() > before; }, 90s)) << log();
  // Gone for good: after camera_max_failures in a row, exit status 1 for systemd to restart.
  fake.reset();
  EXPECT_EQ(process.wait(180s), 1) << log();
  EXPECT_NE(log().find("failed 6 times in a row"), std::string::npos) << log();
  EXPECT_TRUE(entries(stacks, true).empty());
}

// Brackets that take seconds (issue 21): the fake GigE Vision camera takes each exposure, and the
// rig asks for six of 0.6 … 1.5 s, a bracket of about 6 s.
constexpr const char* kLongBracket =
    "[capture]\nexposures = [600000, 700000, 800000, 1000000, 1200000, 1500000]\n";
constexpr auto kLongBracketS = 5.8s;

class GlarecamdLongBracket : public GlarecamdProcess {
 protected:
  void SetUp() override {
    if (!longChecks()) GTEST_SKIP() << "a long check (30 s): make kill-check runs it";
    fake_ = startFake();
    ASSERT_TRUE(
        eventually([&] { return fs::exists(dir_ / "cal" / "fake-camera-mono16.json"); }, 30s));
    testing::writeText(dir_ / "rig.toml", fakeCameraRig(kLongBracket, 1, 20));
  }
  std::unique_ptr<Process> startFake() {
    return std::make_unique<Process>(
        std::vector<std::string>{GLARECAM_PATH, "fake-camera", "--size", "320x256",
                                 "--calibration-out", (dir_ / "cal").string()},
        std::vector<std::string>{}, dir_ / "fake.log");
  }
  // Reads notify messages until `condition` holds (true) or `timeout` passes.
  static bool pumpUntil(NotifySocket& notify, const std::function<bool()>& condition,
                        std::chrono::seconds timeout) {
    const auto deadline = Clock::now() + timeout;
    while (Clock::now() < deadline) {
      if (condition()) return true;
      notify.receive(100ms);
    }
    return condition();
  }
  // The longest stretch from `from` to `to` without a WATCHDOG=1 (what systemd's watchdog
  // times): between two pings, and from `from` to the first and from the last to `to`.
  static Clock::duration longestWatchdogGap(const NotifySocket& notify, Clock::time_point from,
                                            Clock::time_point to) {
    Clock::time_point last = from;
    Clock::duration longest{};
    for (const auto& m : notify.received()) {
      if (m.message != "WATCHDOG=1" || m.at < from || m.at > to) continue;
      longest = std::max(longest, m.at - last);
      last = m.at;
    }
    return std::max(longest, to - last);
  }
  static bool lastStatusIs(const NotifySocket& notify, std::string_view prefix) {
    for (auto m = notify.received().rbegin(); m != notify.received().rend(); ++m)
      if (m->message.starts_with("STATUS=")) return m->message.starts_with(prefix);
    return false;
  }
  fs::path stacks() const { return dir_ / "out" / "stacks"; }
  std::unique_ptr<Process> fake_;
};

// WatchdogSec 16 s (WATCHDOG_USEC), so glarecamd pings every 8 s: across 6 s brackets one after
// the other, a ping comes at least every WatchdogSec/2 (checked over three brackets, from READY
// on; 1 s of slack for a loaded machine's scheduling). The loop cannot ping during a bracket, so
// it pings before one in which a ping would fall due; without that a ping came only between
// brackets, 12 s apart here. SIGTERM 2 s into a bracket: glarecamd exits 0 well
// within the unit's TimeoutStopSec (300 s, systemd/glarecamd.service), the bracket finished and
// written whole or not at all, nothing half-written left.
TEST_F(GlarecamdLongBracket, WatchdogKeepsItsCadenceAndSigtermStopsCleanly) {
  NotifySocket notify(dir_ / "notify.sock");
  Process process(daemon({"--config", (dir_ / "rig.toml").string()}),
                  {"NOTIFY_SOCKET=" + notify.path().string(), "WATCHDOG_USEC=16000000"},
                  dir_ / "glarecamd.log");
  ASSERT_TRUE(notify.waitFor("READY=1", kStartTimeout)) << log();
  const auto watch_start = Clock::now();
  ASSERT_TRUE(pumpUntil(
      notify, [&] { return entries(stacks(), false).size() >= 3; }, 120s))
      << log();
  EXPECT_GE(Clock::now() - watch_start, 2 * kLongBracketS) << "the brackets took no time";
  EXPECT_LE(longestWatchdogGap(notify, watch_start, Clock::now()), 8s + 1s) << log();
  // SIGTERM mid-bracket.
  ASSERT_TRUE(pumpUntil(
      notify, [&] { return lastStatusIs(notify, "STATUS=capturing"); }, 60s));
  std::this_thread::sleep_for(2s);
  const auto before = entries(stacks(), false).size();
  const auto signalled = Clock::now();
  process.signal(SIGTERM);
  EXPECT_EQ(process.wait(300s), 0) << log();
  EXPECT_LT(Clock::now() - signalled, 60s) << "far from TimeoutStopSec=300, but no quick stop";
  EXPECT_TRUE(entries(stacks(), true).empty()) << "a half-written stack was left";
  const auto after = entries(stacks(), false);
  EXPECT_LE(after.size(), before + 1);
  for (const fs::path& stack : after) EXPECT_TRUE(readStack(stack)) << stack;
}

// The camera killed 2 s into a 6 s bracket: that bracket leaves no stack, the status says the
// camera is being waited for, the reopening backs off 1, 2, 2 s (capped at camera_backoff_max_s),
// and once the camera is back the next stack lands.
TEST_F(GlarecamdLongBracket, CameraKilledMidBracketLeavesNoStackAndIsReopened) {
  NotifySocket notify(dir_ / "notify.sock");
  Process process(daemon({"--config", (dir_ / "rig.toml").string()}),
                  {"NOTIFY_SOCKET=" + notify.path().string(), "WATCHDOG_USEC=16000000"},
                  dir_ / "glarecamd.log");
  ASSERT_TRUE(notify.waitFor("READY=1", kStartTimeout)) << log();
  ASSERT_TRUE(pumpUntil(
      notify, [&] { return !entries(stacks(), false).empty(); }, 120s))
      << log();
  ASSERT_TRUE(pumpUntil(
      notify, [&] { return lastStatusIs(notify, "STATUS=capturing"); }, 60s));
  std::this_thread::sleep_for(2s);
  const auto before = entries(stacks(), false).size();
  fake_.reset();  // SIGKILL, mid-bracket
  ASSERT_TRUE(pumpUntil(
      notify, [&] { return lastStatusIs(notify, "STATUS=waiting for the camera"); }, 90s))
      << log();
  EXPECT_EQ(entries(stacks(), false).size(), before) << "the interrupted bracket left a stack";
  EXPECT_TRUE(entries(stacks(), true).empty());
  // Let it back off a few times, then bring the camera back.
  ASSERT_TRUE(pumpUntil(
      notify, [&] { return log().find("(failure 3 of 20)") != std::string::npos; }, 60s))
      << log();
  EXPECT_NE(log().find("reopening in 1 s (failure 1 of 20)"), std::string::npos) << log();
  EXPECT_NE(log().find("reopening in 2 s (failure 2 of 20)"), std::string::npos) << log();
  EXPECT_NE(log().find("reopening in 2 s (failure 3 of 20)"), std::string::npos) << log();
  fake_ = startFake();
  ASSERT_TRUE(pumpUntil(
      notify, [&] { return entries(stacks(), false).size() > before; }, 120s))
      << log();
  for (const fs::path& stack : entries(stacks(), false)) EXPECT_TRUE(readStack(stack)) << stack;
  process.signal(SIGTERM);
  EXPECT_EQ(process.wait(120s), 0) << log();
}
#endif

}  // namespace
}  // namespace glarecam
