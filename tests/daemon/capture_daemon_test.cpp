// glarecamd's core (daemon/) in one process on a manual clock: the schedules, the
// stack's way to disk, results and the day's data sheet, systemd's notifications and watchdog,
// and every fault of issue 9 (camera lost, inclinometer, disk, clock, bad config, reload).
#include "daemon/capture_daemon.h"

#include <gtest/gtest.h>
#include <poll.h>
#include <signal.h>
#include <sys/inotify.h>
#include <sys/mount.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <condition_variable>
#include <cstring>
#include <mutex>
#include <thread>

#include "core/stack_io.h"
#include "daemon/daemon_fixture.h"
#include "daemon/daemon_run.h"
#include "pipeline/contour_table.h"
#include "pipeline/sweep_table.h"
#include "support/sim_support.h"

namespace glarecam::daemon {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using testing::utc;

// --max-use-gib is retention by space alone (the config's ages not applied); --reserve-mb the
// reserve; out of range they are usage errors.
TEST(DaemonOptions, TheRetentionOverridesReplaceTheConfigs) {
  Config config;
  config.daemon.output.retention = {.keep_stacks_days = 7, .keep_results_days = 21};
  config.daemon.output.reserve_bytes = 1ull << 30;
  const Config same = effectiveConfig(config, {});
  EXPECT_EQ(same.daemon.output.retention.keep_stacks_days, 7);
  const Config budget =
      effectiveConfig(config, {.max_use_bytes = 200ull << 20, .reserve_bytes = 64ull << 20});
  EXPECT_EQ(budget.daemon.output.retention.max_use_bytes, 200ull << 20);
  EXPECT_FALSE(budget.daemon.output.retention.keep_stacks_days);
  EXPECT_FALSE(budget.daemon.output.retention.keep_results_days);
  EXPECT_EQ(budget.daemon.output.reserve_bytes, 64ull << 20);
  DaemonRunOptions run;
  run.max_use_gib = 0.0;
  EXPECT_FALSE(run.validate());
  run.max_use_gib = 0.2;
  run.reserve_mb = -1;
  EXPECT_FALSE(run.validate());
  run.reserve_mb = 64;
  EXPECT_TRUE(run.validate());
}

TEST_F(DaemonTest, InvalidConfigIsBadInputBeforeAnythingOpens) {
  testing::writeText(config_path(), "camera = \"sim:\"\n[schedule]\nmode = 3\n");
  auto daemon = CaptureDaemon::create({.config_path = config_path()},
                                      {.clock = &clock_, .notifier = &notifier_, .disk = &disk_});
  ASSERT_FALSE(daemon);
  EXPECT_EQ(daemon.error().code, ErrorCode::kBadInput);
  EXPECT_NE(daemon.error().message.find(config_path().string() + ":3:"), std::string::npos);
  EXPECT_EQ(cameras_.opens(), 0);
  EXPECT_TRUE(notifier_.messages().empty());  // never READY: systemd sees the exit status
}

TEST_F(DaemonTest, CameraTheConfigCannotNameIsAConfigError) {
  writeConfig({.camera = "sim:size=banana"});
  auto daemon = makeDaemon();
  terminateAt(1h, *daemon);
  const Status ran = daemon->run();
  ASSERT_FALSE(ran);
  EXPECT_EQ(ran.error().code, ErrorCode::kBadInput);
  EXPECT_NE(ran.error().message.find("camera"), std::string::npos) << ran.error().message;
  EXPECT_EQ(notifier_.count("READY=1"), 0u);
}

TEST_F(DaemonTest, IntervalStacksAreWrittenProcessedAndTabulatedPerDay) {
  writeConfig();
  auto daemon = makeDaemon();
  terminateAt(3600s + 1s, *daemon);  // stacks at 0, 600, ... 3600 s
  ASSERT_TRUE(daemon->run());
  const auto written = stacks();
  ASSERT_EQ(written.size(), 7u);
  for (const fs::path& stack : written) {
    const auto read = readStack(stack);
    ASSERT_TRUE(read) << read.error().message;
    const nlohmann::json m = manifest(stack);
    EXPECT_NEAR(m["alpha_deg"].get<double>(), 40.0, 0.05);  // the table's 50° tilt
    EXPECT_EQ(m["daemon"]["trigger"], "schedule");
    EXPECT_TRUE(m["daemon"]["flags"].empty());
    EXPECT_TRUE(m.contains("geometry"));
    EXPECT_TRUE(fs::exists(out() / kResultsDirectory / stack.filename() / "result.json"));
    EXPECT_TRUE(fs::exists(out() / kResultsDirectory / stack.filename() / "luminance.png"));
  }
  // Simulated time: 08:00 to 09:00 UTC on 2026-06-21, one day. Its table has every stack; one α
  // is too few for the fits, so there is no sheet yet, and the table says why not.
  const fs::path day = out() / kDaysDirectory / "2026-06-21";
  const auto table = pipeline::readSweepTable(day / "sweep.csv");
  ASSERT_TRUE(table) << table.error().message;
  EXPECT_EQ(table->rows.size(), 7u);
  EXPECT_FALSE(fs::exists(day / "datasheet.pdf"));
  EXPECT_EQ(daemon->state().stacks_processed, 7u);
  EXPECT_NE(daemon->state().day.find("no data sheet yet"), std::string::npos);
  // Started again the same day on a disk now full, so that no stack comes: the day's count is
  // read back from the disk, not "none processed yet today".
  daemon.reset();
  disk_.set({.free_bytes = 10ull << 20, .total_bytes = 100ull << 30});
  auto again = makeDaemon();
  terminateAt(clock_.elapsed() + 60s, *again);
  ASSERT_TRUE(again->run());
  ASSERT_TRUE(again->state().last_day);
  EXPECT_EQ(again->state().last_day->day, "2026-06-21");
  EXPECT_EQ(again->state().last_day->stacks, 7u);
  EXPECT_FALSE(again->state().last_day->datasheet);
  EXPECT_EQ(again->state().stacks_written, 0u);  // this run's counters start at nought
  EXPECT_EQ(again->state().day, "2026-06-21: 7 stacks; no data sheet yet");
  ASSERT_TRUE(again->state().last_result);  // and the last result is the earlier run's last
  EXPECT_EQ(again->state().last_result->stack_id, written.back().filename().string());
  EXPECT_GT(again->state().last_result->brief.lmax_cd_m2, 0);
}

TEST_F(DaemonTest, NotifiesReadyOnceStatusOnChangeAndStoppingLast) {
  writeConfig();
  auto daemon = makeDaemon();
  terminateAt(1201s, *daemon);
  ASSERT_TRUE(daemon->run());
  const auto messages = notifier_.messages();
  ASSERT_FALSE(messages.empty());
  EXPECT_EQ(notifier_.count("READY=1"), 1u);
  EXPECT_EQ(notifier_.count("STOPPING=1"), 1u);
  EXPECT_TRUE(notifier_.matching("STATUS=").front().message.starts_with("STATUS=starting"));
  EXPECT_TRUE(statusMentioned("last 20260621T0800"));
  EXPECT_TRUE(statusMentioned("next at 2026-06-21T08:20:00Z"));
  EXPECT_TRUE(statusMentioned("stopping"));
  // STATUS only when it changes.
  const auto statuses = notifier_.matching("STATUS=");
  for (std::size_t i = 1; i < statuses.size(); ++i)
    EXPECT_NE(statuses[i].message, statuses[i - 1].message);
  // No heartbeat after STOPPING=1.
  bool stopping = false;
  for (const auto& m : messages) {
    if (m.message == "STOPPING=1") stopping = true;
    if (stopping) {
      EXPECT_NE(m.message, "WATCHDOG=1");
    }
  }
}

TEST_F(DaemonTest, WatchdogIsFedAtHalfItsIntervalWhileTheLoopRuns) {
  writeConfig();
  auto daemon = makeDaemon();
  terminateAt(2h, *daemon);
  ASSERT_TRUE(daemon->run());
  const auto pings = notifier_.matching("WATCHDOG=1");
  // WATCHDOG_USEC 10 s: a ping every 5 s (systemd's advice: half the interval), however idle the
  // schedule; the manual clock makes the cadence exact.
  ASSERT_GE(pings.size(), 2u * 3600 / 5);
  for (std::size_t i = 1; i < pings.size(); ++i) {
    EXPECT_LE(pings[i].at - pings[i - 1].at, 5s) << "gap before ping " << i;
    EXPECT_GE(pings[i].at - pings[i - 1].at, 5s) << "a ping on every wake-up, before ping " << i;
  }
}

// Brackets that take seconds, one after the other (interval 1 s; the camera takes its 4 s of
// exposures on the manual clock): the loop cannot ping during a bracket, so it pings before one
// in which a ping would fall due. Without that, a ping came only between brackets, 8 s apart.
TEST_F(DaemonTest, WatchdogKeepsItsCadenceAcrossBracketsThatTakeSeconds) {
  writeConfig({.schedule = "mode = \"interval\"\ninterval_s = 1",
               .extra = "[capture]\nexposures = [400000, 500000, 600000, 700000, 800000, "
                        "1000000]\n"});
  cameras_.takeExposureTime(clock_);
  auto daemon = makeDaemon({.max_stacks = 8});
  terminateAt(1h, *daemon);
  ASSERT_TRUE(daemon->run());
  EXPECT_EQ(daemon->state().stacks_written, 8u);
  const auto pings = notifier_.matching("WATCHDOG=1");
  ASSERT_GE(pings.size(), 8u);  // 8 brackets of 4 s, a ping at least every 5 s
  for (std::size_t i = 1; i < pings.size(); ++i)
    EXPECT_LE(pings[i].at - pings[i - 1].at, 5s) << "gap before ping " << i;
}

TEST_F(DaemonTest, AWedgedCameraStopsTheHeartbeat) {
  writeConfig();
  cameras_.wedgeAtCall(3);  // in the middle of the first auto bracket
  auto daemon = makeDaemon();
  terminateAt(1h, *daemon);
  std::thread loop([&] { EXPECT_TRUE(daemon->run()); });
  cameras_.waitUntilWedged();
  const std::size_t before = notifier_.count("WATCHDOG=1");
  clock_.advance(10min);  // far past WATCHDOG_USEC: systemd would kill and restart us now
  // Any other thread that pinged on its own (a timer thread's "heartbeat") has had its chance.
  std::this_thread::sleep_for(300ms);
  EXPECT_EQ(notifier_.count("WATCHDOG=1"), before) << "nothing may ping for a wedged loop";
  cameras_.release();
  loop.join();
  EXPECT_GT(notifier_.count("WATCHDOG=1"), before);
}

TEST_F(DaemonTest, Sigusr1AndTheButtonTakeAStackNow) {
  writeConfig({.schedule = "mode = \"button\""});
  auto daemon = makeDaemon();
  signalAt(100s, *daemon, SIGUSR1);
  clock_.at(200s, [&] { daemon->events().post(ButtonEvent{}); });
  terminateAt(300s, *daemon);
  ASSERT_TRUE(daemon->run());
  const auto written = stacks();
  ASSERT_EQ(written.size(), 2u);  // nothing on schedule
  EXPECT_EQ(manifest(written[0])["daemon"]["trigger"], "signal");
  EXPECT_EQ(manifest(written[1])["daemon"]["trigger"], "button");
  EXPECT_EQ(manifest(written[0])["captured_at"], "2026-06-21T08:01:40Z");  // the daemon's clock
}

TEST_F(DaemonTest, ButtonIgnoredWhenTheScheduleSaysSo) {
  writeConfig({.schedule = "mode = \"button\"\nbutton = false"});
  auto daemon = makeDaemon();
  clock_.at(200s, [&] { daemon->events().post(ButtonEvent{}); });
  terminateAt(300s, *daemon);
  ASSERT_TRUE(daemon->run());
  EXPECT_TRUE(stacks().empty());
}

TEST_F(DaemonTest, SighupReloadsTheConfigAndKeepsItWhenTheNewOneIsBad) {
  writeConfig();
  auto daemon = makeDaemon();
  clock_.at(1000s, [&] { writeConfig({.schedule = "mode = \"interval\"\ninterval_s = 60"}); });
  signalAt(1000s, *daemon, SIGHUP);
  clock_.at(1500s, [&] { testing::writeText(config_path(), "[schedule]\nmode = 7\n"); });
  signalAt(1500s, *daemon, SIGHUP);
  terminateAt(1801s, *daemon);
  ASSERT_TRUE(daemon->run());
  // 0 and 600 s on the old interval; the reload at 1000 s starts the new one: 1060, 1120, ...
  // 1780 s (13 stacks); the bad config at 1500 s changes nothing.
  EXPECT_EQ(stacks().size(), 2u + 13u);
  EXPECT_EQ(daemon->state().reloads, 1u);
  EXPECT_TRUE(statusMentioned(
      "config: reload failed, the previous config stays: " + config_path().string() + ":2:"));
}

TEST_F(DaemonTest, AlphaTargetsAreCaughtAsTheSunMoves) {
  // 48° N on the solstice, the module tilted 24.5° south: α falls through every target from 80°
  // to 5° in the morning. The manual clock stands still during a capture, so each stack's α is
  // its target's to the crossing's tolerance (0.5 s of sun, < 0.01°) plus the simulated
  // inclinometer's noise (60 µg, 0.004° per sample, 4 samples).
  clock_.setUtcStart(utc("2026-06-21T05:00:00Z"));
  // Five targets (the default sixteen take long under the sanitizer: a sheet each from the 4th).
  writeConfig({.inclinometer = "sim:24.5",
               .schedule = "mode = \"alpha-targets\"\nalpha_targets_deg = [80, 60, 40, 20, 5]",
               .site = true});
  auto daemon = makeDaemon({.max_stacks = 5});
  terminateAt(24h, *daemon);
  ASSERT_TRUE(daemon->run());
  const auto written = stacks();
  ASSERT_EQ(written.size(), 5u);
  const std::vector<double> targets{80, 60, 40, 20, 5};  // α falls through them in the morning
  for (std::size_t i = 0; i < written.size(); ++i) {     // in time order (ids start with the time)
    const nlohmann::json m = manifest(written[i]);
    EXPECT_NEAR(m["alpha_deg"].get<double>(), targets[i], 0.02) << written[i];
    EXPECT_EQ(m["daemon"]["target_alpha_deg"].get<double>(), targets[i]);
  }
  // Five α: the fits succeed and the day's sheet is published.
  const fs::path day = out() / kDaysDirectory / "2026-06-21";
  EXPECT_TRUE(fs::exists(day / "datasheet.pdf"));
  EXPECT_TRUE(fs::exists(day / "datasheet.png"));
  EXPECT_TRUE(fs::exists(day / "glare-profile.json"));
  EXPECT_TRUE(fs::exists(day / "fits.json"));
  EXPECT_EQ(pipeline::readSweepTable(day / "sweep.csv")->rows.size(), 5u);
  // Its contour ladders beside the table, and in the profile (/2) for the hazard.
  const auto contours = pipeline::readContourTable(day / pipeline::kContourTableFileName);
  ASSERT_TRUE(contours) << contours.error().message;
  EXPECT_GE(contours->rows.size(), 5u * 3);  // the limit, the half maximum and a rung, at least
  const auto profile = nlohmann::json::parse(testing::readText(day / "glare-profile.json"));
  ASSERT_TRUE(profile.contains("ladder")) << profile.dump().substr(0, 300);
  EXPECT_FALSE(profile["ladder"].empty());
}

// Under load the status once named the 45° target as the next stack while the 50° stack was
// still being taken: the schedule moved on when a stack began. It moves on once the stack is done.
TEST_F(DaemonTest, WhileAStackIsTakenTheStatusNamesItsTarget) {
  clock_.setUtcStart(utc("2026-06-21T05:00:00Z"));
  writeConfig({.inclinometer = "sim:24.5",
               .schedule = "mode = \"alpha-targets\"\nalpha_targets_deg = [50, 45]",
               .site = true});
  StatusBoard board;
  std::vector<std::optional<double>> named;  // the next stack's target, at each capture call
  cameras_.onCapture([&] { named.push_back(board.latest()->state.next_target_deg); });
  auto daemon = makeDaemon({.max_stacks = 1},
                           [&board](DaemonServices& services) { services.status_board = &board; });
  ASSERT_TRUE(daemon);
  ASSERT_TRUE(daemon->run());
  ASSERT_EQ(stacks().size(), 1u);
  EXPECT_EQ(manifest(stacks().front())["daemon"]["target_alpha_deg"].get<double>(), 50.0);
  ASSERT_FALSE(named.empty());
  for (const std::optional<double>& target : named) EXPECT_EQ(target, 50.0);
  EXPECT_EQ(board.latest()->state.next_target_deg, 45.0);  // once the 50° stack is done
}

TEST_F(DaemonTest, CameraLostMidBracketIsReopenedWithBackoff) {
  writeConfig();
  std::vector<std::chrono::nanoseconds> opens;
  auto script = cameras_.opener();
  cameras_.loseAtCall(3);  // mid-way through the first bracket; opens fail until healed
  auto daemon = makeDaemon({}, [&](DaemonServices& services) {
    services.open_camera = [&](std::string_view uri, const capture::CameraOptions& options,
                               const capture::SceneSource& scene_source) {
      opens.push_back(clock_.elapsed());
      return script(uri, options, scene_source);
    };
  });
  ASSERT_TRUE(daemon);
  rig::RigState led_while_lost;
  std::string status_while_lost;
  clock_.at(10s, [&] {
    led_while_lost = daemon->state().led;
    status_while_lost = daemon->state().status;
  });
  clock_.at(20s, [&] { cameras_.heal(); });
  terminateAt(601s, *daemon);
  ASSERT_TRUE(daemon->run());
  // Opened at 0 s (once: the simulated camera follows the stack's α without a reopen), lost
  // mid-bracket; reopened after 2 s, then 4 s (both fail: failures 2 and 3), then 8 s later at
  // 14 s (fails: 4 of 5)... healed at 20 s; the next try, 16 s after 14 s (the cap), at 30 s,
  // succeeds. The bracket lost at 0 s is not retried: the next stack is the schedule's at 600 s.
  ASSERT_GE(opens.size(), 5u);
  EXPECT_EQ(opens[0], 0s);
  EXPECT_EQ(opens[1], 2s);
  EXPECT_EQ(opens[2], 2s + 4s);
  EXPECT_EQ(opens[3], 2s + 4s + 8s);
  EXPECT_EQ(opens[4], 2s + 4s + 8s + 16s);
  EXPECT_EQ(led_while_lost, rig::RigState::faulted(rig::FaultCode::kCamera));
  // The camera's errors name its URI (the base class's contract).
  EXPECT_TRUE(statusMentioned("camera: " + std::string(testing::kSmallSimCamera) +
                              ": camera lost: control-lost (scripted); the stack was "
                              "discarded; reopening in 2 s (failure 1 of 5)"));
  EXPECT_NE(status_while_lost.find("failure 3 of 5"), std::string::npos) << status_while_lost;
  EXPECT_EQ(stacks().size(), 1u);  // only the 600 s stack: the lost bracket left nothing
  EXPECT_TRUE(daemon->state().camera_fault.empty());
  EXPECT_EQ(daemon->state().led, rig::RigState::ready());
}

TEST_F(DaemonTest, CameraLostForGoodEndsTheDaemonForSystemdToRestart) {
  writeConfig();
  cameras_.loseAtCall(1);
  auto daemon = makeDaemon();
  terminateAt(24h, *daemon);
  const Status ran = daemon->run();
  ASSERT_FALSE(ran);
  EXPECT_EQ(ran.error().code, ErrorCode::kHardware);  // glarecamd exits 1: Restart=on-failure
  EXPECT_NE(ran.error().message.find("failed 5 times in a row"), std::string::npos)
      << ran.error().message;
  // Capped: 2 + 4 + 8 + 16 s of backoff between the five failures, not a tight loop.
  EXPECT_EQ(clock_.elapsed(), 30s);
  EXPECT_TRUE(stacks().empty());
  EXPECT_EQ(notifier_.count("STOPPING=1"), 1u);
}

TEST_F(DaemonTest, CameraAbsentAtStartDelaysReady) {
  writeConfig();
  cameras_.failOpens();
  clock_.at(5s, [&] { cameras_.heal(); });
  auto daemon = makeDaemon();
  terminateAt(100s, *daemon);
  ASSERT_TRUE(daemon->run());
  const auto ready = notifier_.matching("READY=1");
  ASSERT_EQ(ready.size(), 1u);
  EXPECT_EQ(ready[0].at, 6s);  // opens at 0 and 2 s fail, the one at 6 s succeeds
  EXPECT_TRUE(statusMentioned("starting"));
  EXPECT_EQ(stacks().size(), 1u);
}

TEST_F(DaemonTest, InclinometerFaultTakesStacksWithAlphaUnknownByDefault) {
  writeConfig({.inclinometer = "sim:50,fault=saturated"});
  auto daemon = makeDaemon();
  terminateAt(601s, *daemon);
  ASSERT_TRUE(daemon->run());
  const auto written = stacks();
  ASSERT_EQ(written.size(), 2u);
  for (const fs::path& stack : written) {
    const nlohmann::json m = manifest(stack);
    EXPECT_FALSE(m.contains("alpha_deg"));
    EXPECT_TRUE(m["geometry"].contains("alpha_unknown"));
    EXPECT_EQ(m["daemon"]["flags"], nlohmann::json::array({"alpha_unknown"}));
  }
  EXPECT_EQ(daemon->state().led, rig::RigState::faulted(rig::FaultCode::kInclinometer));
  EXPECT_TRUE(statusMentioned("inclinometer: "));
  // The day's table notes the stacks it cannot place, and has no row.
  const std::string table = testing::readText(out() / kDaysDirectory / "2026-06-21" / "sweep.csv");
  EXPECT_EQ(std::count(table.begin(), table.end(), '\n'), 3) << table;  // 2 notes, the header
  EXPECT_NE(table.find("# skipped " + written[0].filename().string()), std::string::npos) << table;
}

TEST_F(DaemonTest, InclinometerFaultPausesCaptureWhenConfigured) {
  writeConfig({.inclinometer = "sim:50,fault=zeros", .faults = "inclinometer = \"pause\""});
  auto daemon = makeDaemon();
  terminateAt(1201s, *daemon);
  ASSERT_TRUE(daemon->run());
  EXPECT_TRUE(stacks().empty());
  EXPECT_EQ(daemon->state().captures_skipped, 3u);
  EXPECT_TRUE(statusMentioned("STATUS=paused"));
  EXPECT_EQ(daemon->state().led, rig::RigState::faulted(rig::FaultCode::kInclinometer));
}

TEST_F(DaemonTest, ImplausibleTiltIsAnInclinometerFault) {
  writeConfig({.inclinometer = "sim:70", .faults = "max_tilt_deg = 60\ninclinometer = \"pause\""});
  auto daemon = makeDaemon();
  terminateAt(1s, *daemon);
  ASSERT_TRUE(daemon->run());
  EXPECT_TRUE(stacks().empty());
  EXPECT_NE(daemon->state().inclinometer_fault.find("implausible tilt 70.0"), std::string::npos)
      << daemon->state().inclinometer_fault;
}

TEST_F(DaemonTest, DiskBelowTheReservePausesAndResumes) {
  writeConfig({.schedule = "mode = \"interval\"\ninterval_s = 60"});
  auto daemon = makeDaemon();
  std::string status_while_full;
  clock_.at(1000s, [&] { disk_.set({.free_bytes = 10ull << 20, .total_bytes = 100ull << 30}); });
  clock_.at(1500s, [&] { status_while_full = daemon->state().status; });
  clock_.at(2000s, [&] { disk_.set({.free_bytes = 50ull << 30, .total_bytes = 100ull << 30}); });
  terminateAt(3001s, *daemon);
  ASSERT_TRUE(daemon->run());
  // Every 60 s from 0 to 3000 s is 51 slots; the disk is full from 1000 s (seen by 1010 s at the
  // latest: the check runs every 10 s) to 2000 s (seen by 2010 s): 17 slots (1020 ... 1980 s)
  // are skipped for certain, the ones at 1000 and 2000 s maybe.
  const std::size_t taken = stacks().size();
  EXPECT_GE(taken, 51u - 17u - 2u);
  EXPECT_LE(taken, 51u - 17u);
  EXPECT_NE(status_while_full.find("paused"), std::string::npos) << status_while_full;
  EXPECT_NE(status_while_full.find("10.0 MiB free on"), std::string::npos) << status_while_full;
  EXPECT_NE(status_while_full.find("below the 100.0 MiB reserve"), std::string::npos);
  EXPECT_TRUE(daemon->state().disk_fault.empty());
}

TEST_F(DaemonTest, ReadOnlyFilesystemIsReported) {
  writeConfig();
  disk_.set({.free_bytes = 50ull << 30, .total_bytes = 100ull << 30, .read_only = true});
  auto daemon = makeDaemon();
  rig::RigState led;
  clock_.at(100s, [&] { led = daemon->state().led; });
  terminateAt(601s, *daemon);
  ASSERT_TRUE(daemon->run());
  EXPECT_TRUE(stacks().empty());
  EXPECT_TRUE(statusMentioned("read-only filesystem"));
  EXPECT_EQ(led, rig::RigState::faulted(rig::FaultCode::kDisk));
}

TEST_F(DaemonTest, AStackThatCannotBeWrittenIsKeptUntilTheDiskTakesIt) {
  writeConfig({.schedule = "mode = \"interval\"\ninterval_s = 60"});
  auto daemon = makeDaemon();
  // The stacks directory turns into a file between two stacks: the 120 s stack's write fails; it
  // is kept in memory and capture pauses. At 500 s the file goes; the next disk check writes a
  // probe, then the kept stack.
  refuseStacksAt(100s);
  clock_.at(500s, [&] { fs::remove(out() / kStacksDirectory); });
  terminateAt(541s, *daemon);
  ASSERT_TRUE(daemon->run());
  EXPECT_TRUE(statusMentioned("disk: writing a stack failed"));
  EXPECT_TRUE(statusMentioned("it is kept until the disk takes it"));
  EXPECT_EQ(daemon->state().stacks_failed, 0u);
  const auto written = stacks();
  ASSERT_EQ(written.size(), 2u);  // the one at 120 s, late, and the one at 540 s: none lost
  EXPECT_EQ(manifest(written[0])["captured_at"], "2026-06-21T08:02:00Z");
  EXPECT_TRUE(readStack(written[0]));
  EXPECT_TRUE(daemon->state().disk_fault.empty());
}

// A result the disk refuses (here: results/ turns into a file) is no reason to drop the stack: it
// stays, capture pauses saying why, and once the disk takes writes it is processed again.
TEST_F(DaemonTest, AStackWhoseResultCannotBeWrittenIsKeptAndProcessedAgain) {
  writeConfig({.schedule = "mode = \"interval\"\ninterval_s = 60"});
  auto daemon = makeDaemon();
  refuseResultsBetween(100s, 170s);
  std::string status_while_refused;
  clock_.at(150s, [&] { status_while_refused = daemon->state().status; });
  terminateAt(301s, *daemon);
  ASSERT_TRUE(daemon->run());
  const DaemonState& state = daemon->state();
  EXPECT_TRUE(statusMentioned("disk: processing a stack failed: "));
  EXPECT_TRUE(statusMentioned("it is processed again once the disk takes it"));
  EXPECT_NE(status_while_refused.find("paused"), std::string::npos) << status_while_refused;
  EXPECT_EQ(state.stacks_failed, 0u);
  EXPECT_TRUE(state.disk_fault.empty()) << state.disk_fault;
  // 0, 60 and 120 s (refused, then processed again at 170–180 s), 180 … 300 s after the pause.
  EXPECT_EQ(stacks().size(), 6u);
  EXPECT_EQ(state.stacks_processed, stacks().size());
  for (const fs::path& stack : stacks())
    EXPECT_TRUE(fs::exists(out() / kResultsDirectory / stack.filename() / "result.json")) << stack;
}

// On a worker thread the write runs in real time while the manual clock races on, so these two
// check only the outcomes (the kept-and-retried sequence itself is checked inline above).
TEST_F(DaemonTest, OnAWorkerThreadAStackTheDiskRefusedIsWrittenOnceItTakesIt) {
  writeConfig({.schedule = "mode = \"button\""});
  auto daemon = makeThreadedDaemon();
  refuseStacksAt(5s);
  signalAt(10s, *daemon, SIGUSR1);
  clock_.at(100s, [&] { fs::remove(out() / kStacksDirectory); });
  // From 200 s on, every 10 s of the manual clock, 1 ms of real time for the worker, until the
  // stack has landed (kept, retried at a disk check, written) or 20 s of real time have passed:
  // a budget of time, not of rounds (a loaded machine sleeps longer than asked: 20 000 rounds of
  // "1 ms" took minutes). The loop runs on meanwhile: a wait inside one alarm would stop the disk
  // checks that retry a stack whose refusal came late.
  const auto give_up = std::chrono::steady_clock::now() + 20s;
  std::function<void()> untilLanded = [&] {
    if (fs::exists(out() / kStacksDirectory / "20260621T080010Z-a40.00" / "stack.json") ||
        std::chrono::steady_clock::now() > give_up) {
      daemon->events().post(SignalEvent{SIGTERM});
      return;
    }
    std::this_thread::sleep_for(1ms);
    clock_.at(clock_.elapsed() + 10s, untilLanded);
  };
  clock_.at(200s, untilLanded);
  ASSERT_TRUE(daemon->run());
  EXPECT_EQ(daemon->state().stacks_written, 1u);
  EXPECT_EQ(daemon->state().stacks_failed, 0u);
}

TEST_F(DaemonTest, OnAWorkerThreadAStackTheDiskStillRefusesAtStopIsReportedLost) {
  writeConfig({.schedule = "mode = \"button\""});
  auto daemon = makeThreadedDaemon();
  refuseStacksAt(5s);
  signalAt(10s, *daemon, SIGUSR1);
  terminateAt(300s, *daemon);
  ASSERT_TRUE(daemon->run());
  EXPECT_EQ(daemon->state().stacks_written, 0u);
  EXPECT_EQ(daemon->state().stacks_failed, 1u);  // said, not silently dropped
  EXPECT_NE(daemon->state().worker_fault.find("the stack is lost (glarecamd is stopping)"),
            std::string::npos)
      << daemon->state().worker_fault;
}

TEST_F(DaemonTest, AWallClockJumpReplansTheAlphaTargets) {
  // A rig without a real-time clock: it boots believing it is 05:00, then NTP steps the clock
  // an hour ahead. The plan made before the step would take "80°" at 06:34, where α is 68°.
  clock_.setUtcStart(utc("2026-06-21T05:00:00Z"));
  writeConfig({.inclinometer = "sim:24.5", .schedule = "mode = \"alpha-targets\"", .site = true});
  auto daemon = makeDaemon({.max_stacks = 2});
  clock_.at(60s, [&] { clock_.setUtcStart(utc("2026-06-21T06:00:00Z")); });
  terminateAt(24h, *daemon);
  ASSERT_TRUE(daemon->run());
  ASSERT_EQ(stacks().size(), 2u);
  for (const fs::path& stack : stacks()) {
    const nlohmann::json m = manifest(stack);
    EXPECT_NEAR(m["alpha_deg"].get<double>(), m["daemon"]["target_alpha_deg"].get<double>(), 0.02)
        << stack;
  }
}

TEST_F(DaemonTest, UnsynchronisedClockIsInStatusAndFlagsEveryStack) {
  clock_.setClockStatus({.synchronised = false, .detail = "kernel: STA_UNSYNC"});
  writeConfig({.inclinometer = "sim:24.5", .site = true});
  auto daemon = makeDaemon();
  terminateAt(601s, *daemon);
  ASSERT_TRUE(daemon->run());
  ASSERT_EQ(stacks().size(), 2u);
  for (const fs::path& stack : stacks()) {
    const nlohmann::json m = manifest(stack);
    EXPECT_EQ(m["daemon"]["flags"], nlohmann::json::array({"clock_unsynchronised"}));
    EXPECT_EQ(m["geometry"]["clock_synchronised"], false);
  }
  EXPECT_TRUE(statusMentioned("clock: not synchronised (kernel: STA_UNSYNC); stacks are flagged"));
  EXPECT_EQ(daemon->state().led, rig::RigState::faulted(rig::FaultCode::kClock));
}

TEST_F(DaemonTest, StartCleansUpAndProcessesWhatAKilledRunLeft) {
  writeConfig({.schedule = "mode = \"button\""});
  const fs::path leftover = out() / kStacksDirectory / "20260621T070000Z-a40.00";
  testing::writeSmallStack(leftover);
  fs::create_directories(out() / kStacksDirectory / ".tmp-20260621T071000Z-a40.00-xyz");
  fs::create_directories(out() / kResultsDirectory / ".tmp-20260621T070000Z-a40.00-abc");
  // A stack no processing can read, noted as such by an earlier run: not tried again.
  const fs::path broken = out() / kStacksDirectory / "20260621T060000Z-a40.00";
  fs::create_directories(broken);
  testing::writeText(broken / "stack.json", "{}");
  testing::writeText(out() / kResultsDirectory / "20260621T060000Z-a40.00.failed", "bad\n");
  auto daemon = makeDaemon();
  terminateAt(1s, *daemon);
  ASSERT_TRUE(daemon->run());
  EXPECT_EQ(stacks(), (std::vector<fs::path>{broken, leftover}));
  EXPECT_EQ(results(),
            (std::vector<fs::path>{out() / kResultsDirectory / "20260621T060000Z-a40.00.failed",
                                   out() / kResultsDirectory / leftover.filename()}));
  EXPECT_EQ(daemon->state().stacks_failed, 0u);
  EXPECT_TRUE(fs::exists(out() / kResultsDirectory / leftover.filename() / "result.json"));
}

// A worker on its own thread, held at the start of its first job until the test opens the gate.
struct WorkerGate {
  std::mutex mutex;
  std::condition_variable opened_cv;
  bool opened = false;
  std::atomic<int> jobs{0};
  void hold() {
    if (jobs++ > 0) return;
    std::unique_lock lock(mutex);
    opened_cv.wait(lock, [this] { return opened; });
  }
  void open() {
    const std::lock_guard lock(mutex);
    opened = true;
    opened_cv.notify_all();
  }
  void waitUntilHeld() const {
    while (jobs == 0) std::this_thread::sleep_for(1ms);
  }
};

TEST_F(DaemonTest, StopWritesTheStacksStillQueued) {
  writeConfig({.schedule = "mode = \"button\""});
  WorkerGate gate;
  auto daemon = makeGatedDaemon(gate);
  ASSERT_TRUE(daemon);
  // Two stacks: the worker is held on the first, so the second is still queued, in memory, when
  // SIGTERM arrives; the gate opens once the daemon is stopping.
  signalAt(10s, *daemon, SIGUSR1);
  signalAt(20s, *daemon, SIGUSR1);
  signalAt(30s, *daemon, SIGTERM);
  std::thread opener([&] {
    while (notifier_.count("STOPPING=1") == 0) std::this_thread::sleep_for(1ms);
    gate.open();
  });
  ASSERT_TRUE(daemon->run());
  opener.join();
  ASSERT_EQ(stacks().size(), 2u);
  for (const fs::path& stack : stacks()) EXPECT_TRUE(readStack(stack)) << stack;
}

TEST_F(DaemonTest, WithItsCountCapturedTheLoopWaitsForTheWorkerWithoutSpinning) {
  // --count 1: the stack is captured at once and held in the worker for 20 minutes. Meanwhile a
  // SIGUSR1 asks for a capture and the interval's next slot (600 s) comes due; neither can be
  // taken, and neither may turn the loop into a busy one (the manual clock aborts on that).
  writeConfig();
  WorkerGate gate;
  auto daemon = makeGatedDaemon(gate, {.max_stacks = 1});
  ASSERT_TRUE(daemon);
  signalAt(20s, *daemon, SIGUSR1);
  clock_.at(20min, [&] {
    gate.open();
    while (results().empty()) std::this_thread::sleep_for(1ms);
  });
  // The count stops the daemon once the worker reports; the manual clock may run ahead to this
  // while the worker's thread posts that report.
  terminateAt(2h, *daemon);
  ASSERT_TRUE(daemon->run());
  EXPECT_EQ(daemon->state().stacks_captured, 1u);
  EXPECT_EQ(daemon->state().stacks_processed, 1u);
  EXPECT_EQ(stacks().size(), 1u);
  EXPECT_GE(clock_.elapsed(), 20min);
}

TEST_F(DaemonTest, AStuckWorkerStopsTheHeartbeat) {
  writeConfig({.schedule = "mode = \"button\""});
  WorkerGate gate;
  auto daemon = makeGatedDaemon(gate);
  ASSERT_TRUE(daemon);
  signalAt(10s, *daemon, SIGUSR1);  // the worker's first job hangs (a dead disk) ...
  clock_.at(11s, [&gate] { gate.waitUntilHeld(); });
  clock_.at(1h, [&] {  // ... until an hour later; the loop waits for it to finish
    gate.open();
    while (results().empty()) std::this_thread::sleep_for(1ms);
  });
  terminateAt(2h, *daemon);
  ASSERT_TRUE(daemon->run());
  // The loop went on (the manual clock ran through the hour), but from kWorkerStallLimit into the
  // stuck job (held from 10 s) it no longer fed the watchdog: systemd would have restarted it.
  const auto pings = notifier_.matching("WATCHDOG=1");
  std::chrono::nanoseconds longest_gap{0}, gap_end{0};
  for (std::size_t i = 1; i < pings.size(); ++i)
    if (pings[i].at - pings[i - 1].at > longest_gap) {
      longest_gap = pings[i].at - pings[i - 1].at;
      gap_end = pings[i].at;
    }
  EXPECT_GE(longest_gap, 1h - 10s - kWorkerStallLimit - 5s);
  EXPECT_GE(gap_end, 1h);  // the heartbeat came back with the worker
  EXPECT_LE(gap_end, 1h + 5s);
}

// [output] retention over three days of 6-hourly stacks: stacks older than a day go, results and
// day sheets older than two after their stacks, every deletion counted, and capture goes on.
TEST_F(DaemonTest, RetentionDeletesWhatIsOlderThanItsDaysAndCaptureGoesOn) {
  writeConfig({.schedule = "mode = \"interval\"\ninterval_s = 21600",
               .output = "keep_stacks_days = 1\nkeep_results_days = 2"});
  auto daemon = makeDaemon();
  terminateAt(72h + 1s, *daemon);  // from 2026-06-21 08:00 to 2026-06-24 08:00 UTC
  ASSERT_TRUE(daemon->run());
  const DaemonState& state = daemon->state();
  EXPECT_EQ(state.stacks_written, 13u);
  // Left: the 24th's stacks (02:00, 08:00); the 23rd's and 24th's results and days.
  std::vector<std::string> left;
  for (const fs::path& stack : stacks()) left.push_back(stack.filename().string().substr(0, 16));
  EXPECT_EQ(left, (std::vector<std::string>{"20260624T020000Z", "20260624T080000Z"}));
  EXPECT_EQ(results().size(), 4u + 2u);
  EXPECT_EQ(entries(out() / kDaysDirectory).size(), 2u);
  EXPECT_EQ(state.stacks_deleted, 11u);
  EXPECT_EQ(state.results_deleted, 7u);
  EXPECT_EQ(state.days_deleted, 2u);
  EXPECT_TRUE(statusMentioned("retention deleted 11 stacks, 0 result images, 7 results, 2 days"));
}

// The settings check: a budget that cannot hold one day's stacks is warned of after the first
// stack (nothing to measure before it), in the log's and the status page's words; a budget that
// can is not.
TEST_F(DaemonTest, ABudgetSmallerThanOneDaysStacksIsWarnedOf) {
  // A stack every hour while the sun is on the module (10.4 h here), about 0.4 MiB each.
  writeConfig({.schedule = "mode = \"interval\"\ninterval_s = 3600",
               .site = true,
               .output = "max_use_gib = 0.001"});  // 1 MiB
  auto daemon = makeDaemon();
  terminateAt(2h, *daemon);
  ASSERT_TRUE(daemon->run());
  const std::string& warning = daemon->state().retention_budget_warning;
  EXPECT_NE(warning.find("max_use_gib (1.0 MiB) holds about"), std::string::npos) << warning;
  EXPECT_NE(warning.find("a day the schedule takes (every 3600 s over 1"), std::string::npos)
      << warning;

  writeConfig({.schedule = "mode = \"interval\"\ninterval_s = 3600",
               .site = true,
               .output = "max_use_gib = 1"});
  auto roomy = makeDaemon();
  terminateAt(4h, *roomy);
  ASSERT_TRUE(roomy->run());
  EXPECT_EQ(roomy->state().retention_budget_warning, "");
}

// Ages are told by the clock: while it is not synchronised (it may have run ahead) nothing goes.
TEST_F(DaemonTest, RetentionDeletesNothingWhileTheClockIsUnsynchronised) {
  clock_.setClockStatus({.synchronised = false, .detail = "no NTP"});
  writeConfig({.schedule = "mode = \"interval\"\ninterval_s = 21600",
               .output = "keep_stacks_days = 1\nkeep_results_days = 2"});
  auto daemon = makeDaemon();
  terminateAt(72h + 1s, *daemon);
  ASSERT_TRUE(daemon->run());
  EXPECT_EQ(daemon->state().stacks_written, 13u);
  EXPECT_EQ(stacks().size(), 13u);
  EXPECT_EQ(daemon->state().stacks_deleted, 0u);
}

// Retention's policy follows a reload: off for two days, then a day's stacks kept from the reload
// on; the next stack done deletes what is older.
TEST_F(DaemonTest, AReloadThatTurnsRetentionOnTakesEffect) {
  const std::string schedule = "mode = \"interval\"\ninterval_s = 21600";
  writeConfig({.schedule = schedule});
  auto daemon = makeDaemon();
  std::uint64_t deleted_before_reload = 1;
  std::size_t stacks_before_reload = 0;
  clock_.at(48h, [&] {
    deleted_before_reload = daemon->state().stacks_deleted;
    stacks_before_reload = stacks().size();
    writeConfig({.schedule = schedule, .output = "keep_stacks_days = 1"});
  });
  signalAt(48h, *daemon, SIGHUP);
  terminateAt(72h + 1s, *daemon);  // from 2026-06-21 08:00 to 2026-06-24 08:00 UTC
  ASSERT_TRUE(daemon->run());
  EXPECT_EQ(daemon->state().reloads, 1u);
  EXPECT_EQ(deleted_before_reload, 0u);
  EXPECT_GE(stacks_before_reload, 8u);  // every stack of the first two days was kept
  EXPECT_GT(daemon->state().stacks_deleted, 0u);
  for (const fs::path& stack : stacks())  // nothing of the 21st or 22nd is left
    EXPECT_GE(stack.filename().string().substr(0, 8), "20260623") << stack;
}

// A disk whose free space is what the output tree leaves of a fixed capacity: deleting frees it.
class TreeSizedDisk final : public DiskProbe {
 public:
  TreeSizedDisk(fs::path root, std::uint64_t capacity)
      : root_(std::move(root)), capacity_(capacity) {}
  Result<DiskState> probe(const fs::path&) override {
    const std::uint64_t used = bytesUnder(root_);
    return DiskState{.free_bytes = capacity_ > used ? capacity_ - used : 0,
                     .total_bytes = capacity_};
  }
  static std::uint64_t bytesUnder(const fs::path& root) {
    std::uint64_t bytes = 0;
    std::error_code error;
    for (fs::recursive_directory_iterator it(root, error), end; !error && it != end;
         it.increment(error))
      if (it->is_regular_file(error)) bytes += it->file_size(error);
    return bytes;
  }

 private:
  fs::path root_;
  std::uint64_t capacity_;
};

// Below the reserve with a space budget set, retention frees the oldest stacks that may go; when
// only today's are left the pause stays and says why, and lifts by itself once a new day makes
// yesterday's stacks deletable. Nothing captured is lost: every stack written is on disk or was
// deleted after its result was complete.
TEST_F(DaemonTest, BelowTheReserveRetentionFreesSpaceOrThePauseSaysWhy) {
  clock_.setUtcStart(utc("2026-06-21T20:00:00Z"));  // a new day after the first stack
  writeConfig({.schedule = "mode = \"interval\"\ninterval_s = 21600",
               .output = "max_use_gib = 100\nkeep_results_days = 1"});
  {  // one stack first, to size the disk by it
    auto first = makeDaemon({.max_stacks = 1});
    ASSERT_TRUE(first->run());
  }
  const std::uint64_t one_stack = TreeSizedDisk::bytesUnder(out());
  ASSERT_GT(one_stack, 0u);
  fs::remove_all(out());
  // The 100 MiB reserve and room for two and a half stacks with their results.
  TreeSizedDisk disk(out(), (100ull << 20) + one_stack * 5 / 2);
  auto daemon = makeDaemon({}, [&disk](DaemonServices& services) { services.disk = &disk; });
  // Stacks at 20:00 on the 21st; 02:00, 08:00 (below the reserve: the 21st's stack goes), 14:00
  // (below again, only today's left: paused) on the 22nd; 02:00 on the 23rd (the 22nd's went).
  terminateAt(31h, *daemon);
  ASSERT_TRUE(daemon->run());
  const DaemonState& state = daemon->state();
  EXPECT_GT(state.stacks_deleted, 0u);
  EXPECT_EQ(state.stacks_written, stacks().size() + state.stacks_deleted) << "a stack was lost";
  for (const fs::path& stack : stacks())
    EXPECT_TRUE(fs::exists(out() / kResultsDirectory / stack.filename() / "result.json")) << stack;
  EXPECT_TRUE(statusMentioned("paused"));
  EXPECT_TRUE(statusMentioned("nothing more may go (stacks kept: "));
  EXPECT_TRUE(statusMentioned("of today; day directories "));
  // Capture resumed on the last day.
  EXPECT_TRUE(std::ranges::any_of(stacks(), [](const fs::path& stack) {
    return stack.filename().string().starts_with("20260623T");
  }));
}

// A tmpfs mounted for one test (root only: skips with the reason elsewhere), resized at will.
class TmpfsMount {
 public:
  explicit TmpfsMount(fs::path at) : at_(std::move(at)) {
    fs::create_directories(at_);
    if (::mount("tmpfs", at_.c_str(), "tmpfs", 0, "size=64m") != 0)
      reason_ = std::string("cannot mount a tmpfs: ") + std::strerror(errno);
  }
  ~TmpfsMount() {
    if (reason_.empty()) ::umount2(at_.c_str(), MNT_DETACH);
  }
  TmpfsMount(const TmpfsMount&) = delete;
  TmpfsMount& operator=(const TmpfsMount&) = delete;
  const std::string& unavailable() const { return reason_; }
  bool resize(std::uint64_t bytes) {
    const std::string options = "size=" + std::to_string(bytes);
    return ::mount(nullptr, at_.c_str(), nullptr, MS_REMOUNT, options.c_str()) == 0;
  }
  // Remounts read-only (false with EBUSY while a file is open for writing) or read-write.
  bool setReadOnly(bool read_only) {
    return ::mount(nullptr, at_.c_str(), nullptr, MS_REMOUNT | (read_only ? MS_RDONLY : 0),
                   nullptr) == 0;
  }

 private:
  fs::path at_;
  std::string reason_;
};

// The daemon on a real filesystem: a tmpfs mounted over the output root for each test (root only:
// the test skips with mount(2)'s reason elsewhere), its free space from the real statvfs probe.
// Selected with `ctest -R RealFilesystem`.
class RealFilesystemTest : public DaemonTest {
 protected:
  void SetUp() override {
    DaemonTest::SetUp();
    tmpfs_.emplace(out());
    if (!tmpfs_->unavailable().empty()) GTEST_SKIP() << tmpfs_->unavailable();
  }
  TmpfsMount& tmpfs() { return *tmpfs_; }
  // The daemon with the statvfs probe instead of the scripted disk.
  std::unique_ptr<CaptureDaemon> makeRealDiskDaemon() {
    return makeDaemon({}, [this](DaemonServices& services) { services.disk = disk_.get(); });
  }
  std::uint64_t usedBytes() const {
    const DiskState state = disk_->probe(out()).value();
    return state.total_bytes - state.free_bytes;
  }
  // What the tmpfs holds empty, and what one stack of the written config takes on it with its
  // result and day products (and its result alone, by file sizes): a first daemon takes one
  // stack, then the output root is emptied again.
  struct OneStack {
    std::uint64_t empty_bytes = 0, stack_bytes = 0, result_bytes = 0;
  };
  OneStack sizeOneStack() {
    OneStack sizes{.empty_bytes = usedBytes()};
    auto first = makeDaemon({.max_stacks = 1});
    EXPECT_TRUE(first->run());
    sizes.stack_bytes = usedBytes() - sizes.empty_bytes;
    sizes.result_bytes = TreeSizedDisk::bytesUnder(out() / kResultsDirectory);
    for (const fs::path& entry : entries(out())) fs::remove_all(entry);
    return sizes;
  }

 private:
  std::optional<TmpfsMount> tmpfs_;
  std::unique_ptr<DiskProbe> disk_ = makeStatvfsDiskProbe();
};

// The real thing on a real filesystem (statvfs, ENOSPC): a tmpfs sized for the 1 MiB reserve and
// two and a half stacks with their results fills as stacks land; retention deletes yesterday's
// oldest (max_use_gib set), pauses saying why when only today's are left, and capture resumes the
// next day. Nothing is lost and nothing half-written is left.
TEST_F(RealFilesystemTest, TmpfsFillsRetentionFreesItAndCaptureResumes) {
  clock_.setUtcStart(utc("2026-06-21T20:00:00Z"));
  writeConfig({.schedule = "mode = \"interval\"\ninterval_s = 21600",
               .output = "max_use_gib = 100",
               .reserve_mb = 1});
  const OneStack one = sizeOneStack();
  ASSERT_GT(one.stack_bytes, 0u);
  ASSERT_TRUE(tmpfs().resize(one.empty_bytes + (1ull << 20) + one.stack_bytes * 5 / 2));
  auto daemon = makeRealDiskDaemon();
  terminateAt(31h, *daemon);
  ASSERT_TRUE(daemon->run());
  const DaemonState& state = daemon->state();
  EXPECT_GT(state.stacks_deleted, 0u);
  EXPECT_EQ(state.stacks_written, stacks().size() + state.stacks_deleted) << "a stack was lost";
  for (const fs::path& stack : stacks()) {
    EXPECT_FALSE(stack.filename().string().starts_with(".tmp-")) << stack;
    EXPECT_TRUE(readStack(stack)) << stack;
    EXPECT_TRUE(fs::exists(out() / kResultsDirectory / stack.filename() / "result.json")) << stack;
  }
  EXPECT_TRUE(statusMentioned("paused"));
  EXPECT_TRUE(statusMentioned("of today; day directories "));
  EXPECT_TRUE(std::ranges::any_of(stacks(), [](const fs::path& stack) {
    return stack.filename().string().starts_with("20260623T");
  }));
}

// ENOSPC in the middle of writing a result, on a real filesystem: a tmpfs with room for the
// first stack and half its result, and no reserve (the daemon's free-space check cannot see this
// coming: a reserve set too small, or another program filling the disk). The stack stays, its
// processing fails "disk full" and is parked, capture pauses saying why; once the tmpfs grows (an
// operator freed space) the stack is processed again and capture resumes. No stack is lost or
// marked failed, and no half-written result is left.
TEST_F(RealFilesystemTest, ResultWriteHitsEnospcStackKeptProcessingRetried) {
  writeConfig({.schedule = "mode = \"interval\"\ninterval_s = 60", .reserve_mb = 0});
  const OneStack one = sizeOneStack();
  // Half the result must be well beyond the page rounding of its ~10 files (4 KiB each).
  ASSERT_GT(one.result_bytes, 128u << 10);
  ASSERT_TRUE(tmpfs().resize(one.empty_bytes + one.stack_bytes - one.result_bytes / 2));
  auto daemon = makeRealDiskDaemon();
  std::string status_while_full;
  clock_.at(30s, [&] { status_while_full = daemon->state().status; });
  clock_.at(35s, [&] { ASSERT_TRUE(tmpfs().resize(256ull << 20)); });
  terminateAt(301s, *daemon);
  ASSERT_TRUE(daemon->run());
  const DaemonState& state = daemon->state();
  EXPECT_TRUE(statusMentioned("disk: processing a stack failed: "));
  EXPECT_TRUE(statusMentioned("(disk full)"));
  EXPECT_NE(status_while_full.find("paused"), std::string::npos) << status_while_full;
  EXPECT_EQ(state.stacks_failed, 0u);
  EXPECT_TRUE(state.disk_fault.empty()) << state.disk_fault;
  EXPECT_EQ(stacks().size(), 6u);  // 0 s (processed again at 40 s), 60 … 300 s
  EXPECT_EQ(state.stacks_processed, stacks().size());
  for (const fs::path& stack : stacks())
    EXPECT_TRUE(fs::exists(out() / kResultsDirectory / stack.filename() / "result.json")) << stack;
  for (const fs::path& entry : entries(out() / kResultsDirectory))
    EXPECT_FALSE(entry.filename().string().starts_with(".tmp-")) << entry;
}

// Remounts `tmpfs` read-only in the middle of the first stack's write: once the first frame file
// of a staging directory under `stacks` is closed, while the others are still being encoded.
// A remount is refused (EBUSY) while a file is open for writing, so it is tried until it takes.
class ReadOnlyMidWrite {
 public:
  ReadOnlyMidWrite(TmpfsMount& tmpfs, fs::path stacks)
      : tmpfs_(tmpfs), stacks_(std::move(stacks)), thread_([this] { watch(); }) {}
  ~ReadOnlyMidWrite() {
    stop_ = true;
    thread_.join();
  }
  // The frames the staging directory held when the remount took; nullopt if it never did.
  // Stops the watcher first: asked once the daemon has run, so that a remount that never took is
  // a failed assertion, not a test waiting forever.
  std::optional<std::size_t> framesAtRemount() {
    stop_ = true;
    thread_done_.wait(false);
    return frames_at_remount_;
  }

 private:
  void watch() {
    const int fd = inotify_init1(IN_NONBLOCK | IN_CLOEXEC);
    inotify_add_watch(fd, stacks_.c_str(), IN_CREATE);
    alignas(inotify_event) char buffer[4096];
    while (!stop_ && !frames_at_remount_) {
      pollfd p{.fd = fd, .events = POLLIN, .revents = 0};
      if (::poll(&p, 1, 10) <= 0) continue;
      const ssize_t n = ::read(fd, buffer, sizeof buffer);
      for (ssize_t at = 0; at < n;) {
        const auto* event = reinterpret_cast<const inotify_event*>(buffer + at);
        at += static_cast<ssize_t>(sizeof(inotify_event) + event->len);
        const std::string name = event->len ? event->name : "";
        if ((event->mask & IN_CREATE) && (event->mask & IN_ISDIR) && name.starts_with(".tmp-")) {
          staging_ = stacks_ / name;
          inotify_add_watch(fd, staging_.c_str(), IN_CLOSE_WRITE);
        } else if ((event->mask & IN_CLOSE_WRITE) && name.ends_with(".png")) {
          remount();
        }
      }
    }
    ::close(fd);
    thread_done_ = true;
    thread_done_.notify_all();
  }
  void remount() {
    const auto deadline = std::chrono::steady_clock::now() + 2s;
    while (std::chrono::steady_clock::now() < deadline) {
      if (tmpfs_.setReadOnly(true)) {
        std::size_t frames = 0;
        std::error_code error;
        for (const auto& entry : fs::directory_iterator(staging_, error))
          frames += entry.path().extension() == ".png";
        frames_at_remount_ = frames;
        return;
      }
      std::this_thread::sleep_for(50us);
    }
  }

  TmpfsMount& tmpfs_;
  fs::path stacks_;
  fs::path staging_;
  std::atomic<bool> stop_ = false;
  std::atomic<bool> thread_done_ = false;
  std::optional<std::size_t> frames_at_remount_;
  std::thread thread_;
};

// A read-only remount (an SD card after I/O errors) in the middle of a stack's write, on a real
// filesystem: the write fails, the stack is kept in memory, capture pauses saying "read-only";
// once the filesystem is read-write again the kept stack is written whole and capture resumes.
// Frames of 1024×768 so that writing a stack's six takes long enough to remount between them.
TEST_F(RealFilesystemTest, ReadOnlyRemountMidStackWriteKeepsTheStack) {
  ASSERT_TRUE(tmpfs().resize(512ull << 20));
  writeConfig({.camera = "sim:size=1024x768,fov=30",
               .schedule = "mode = \"interval\"\ninterval_s = 60",
               .reserve_mb = 1});
  fs::create_directories(out() / kStacksDirectory);
  std::optional<ReadOnlyMidWrite> remount(std::in_place, tmpfs(), out() / kStacksDirectory);
  auto daemon = makeRealDiskDaemon();
  std::string status_while_read_only;
  clock_.at(50s, [&] { status_while_read_only = daemon->state().status; });
  clock_.at(100s, [&] { ASSERT_TRUE(tmpfs().setReadOnly(false)); });
  terminateAt(181s, *daemon);
  ASSERT_TRUE(daemon->run());
  const auto frames = remount->framesAtRemount();
  ASSERT_TRUE(frames.has_value()) << "the remount never took";
  EXPECT_LT(*frames, 6u) << "remounted after the frames were all written";
  const DaemonState& state = daemon->state();
  EXPECT_NE(status_while_read_only.find("paused"), std::string::npos) << status_while_read_only;
  EXPECT_NE(status_while_read_only.find("read-only"), std::string::npos) << status_while_read_only;
  EXPECT_EQ(state.stacks_failed, 0u);
  EXPECT_TRUE(state.disk_fault.empty()) << state.disk_fault;
  const auto written = stacks();
  ASSERT_GE(written.size(), 2u);  // the one at 0 s, late, and those after the pause
  EXPECT_EQ(manifest(written[0])["captured_at"], "2026-06-21T08:00:00Z");
  EXPECT_EQ(state.stacks_written, written.size());
  for (const fs::path& stack : written) EXPECT_TRUE(readStack(stack)) << stack;
  for (const fs::path& entry : entries(out() / kStacksDirectory))
    EXPECT_FALSE(entry.filename().string().starts_with(".tmp-")) << entry;
}

}  // namespace
}  // namespace glarecam::daemon
