// glarecamd's core (daemon/) in one process on a manual clock: the schedules, the
// stack's way to disk, results and the day's data sheet, systemd's notifications and watchdog,
// and every fault of issue 9 (camera lost, inclinometer, disk, clock, bad config, reload).
#include <gtest/gtest.h>
#include <signal.h>
#include <spdlog/spdlog.h>

#include <atomic>
#include <cmath>
#include <condition_variable>
#include <fstream>
#include <mutex>
#include <thread>

#include "core/stack_io.h"
#include "core/stack_manifest.h"
#include "daemon/alpha_schedule.h"
#include "daemon/capture_daemon.h"
#include "daemon/daemon_test_support.h"
#include "daemon/day_products.h"
#include "daemon/journal_sink.h"
#include "pipeline/sweep_table.h"
#include "support/sim_support.h"

namespace glarecam::daemon {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;
using testing::ManualClock;
using testing::RecordingNotifier;
using testing::ScriptedCameras;
using testing::ScriptedDisk;
using testing::TempDir;

UtcTime utc(const char* text) { return *sun::parseIsoTime(text); }

// The lab rig of the tests: a lamp on the horizon due south, the module on a table tilted 50°
// facing it, so α = 90° − 50° = 40° (docs/rig.md); the small simulated camera; the simulated
// GPIO chip with a LED.
struct RigSpec {
  std::string camera = testing::kSmallSimCamera;
  std::string inclinometer = "sim:50";
  std::string schedule = "mode = \"interval\"\ninterval_s = 600";
  std::string faults = "camera_backoff_s = 2\ncamera_backoff_max_s = 16\ncamera_max_failures = 5";
  bool site = false;    // [site] at 48° N instead of the lab lamp (α from the sun)
  std::string extra{};  // more sections
};

std::string rigToml(const RigSpec& spec) {
  std::string text = "camera = \"" + spec.camera + "\"\n";
  text += spec.site ? "[site]\nlatitude_deg = 48\nlongitude_deg = 7.85\naltitude_m = 278\n"
                    : "[source]\nelevation_deg = 0\nazimuth_deg = 180\n";
  text += "[module]\nazimuth_deg = 180\n";
  text += "[inclinometer]\nuri = \"" + spec.inclinometer + "\"\nsamples = 4\n";
  text += "[gpio]\nchip = \"sim\"\nled = 27\n";
  text += "[output]\nroot = \"out\"\nreserve_mb = 100\n";
  text += "[schedule]\n" + spec.schedule + "\n";
  text += "[faults]\n" + spec.faults + "\n";
  return text + spec.extra;
}

class DaemonTest : public ::testing::Test {
 protected:
  void SetUp() override { spdlog::set_level(spdlog::level::warn); }

  fs::path writeConfig(const RigSpec& spec = {}) {
    testing::writeText(config_path(), rigToml(spec));
    return config_path();
  }
  fs::path config_path() const { return dir_ / "glarecam.toml"; }
  fs::path out() const { return dir_ / "out"; }

  // The daemon on the test's clock, notifier, disk and cameras, its worker inline; `adjust`
  // changes the services (a worker thread, an opener of its own).
  std::unique_ptr<CaptureDaemon> makeDaemon(
      DaemonOptions options = {}, const std::function<void(DaemonServices&)>& adjust = {}) {
    if (options.config_path == rig::kDefaultRigConfigPath) options.config_path = config_path();
    DaemonServices services{.clock = &clock_,
                            .notifier = &notifier_,
                            .disk = &disk_,
                            .open_camera = cameras_.opener(),
                            .worker_mode = StackWorker::Mode::kInline,
                            .watch_button = false};
    if (adjust) adjust(services);
    auto daemon = CaptureDaemon::create(options, std::move(services));
    EXPECT_TRUE(daemon) << daemon.error().message;
    return daemon ? std::move(*daemon) : nullptr;
  }
  // With its worker on a thread, held at the start of its first job by `gate`.
  template <typename Gate>
  std::unique_ptr<CaptureDaemon> makeGatedDaemon(Gate& gate, DaemonOptions options = {}) {
    return makeDaemon(std::move(options), [&gate](DaemonServices& services) {
      services.worker_mode = StackWorker::Mode::kThread;
      services.worker_job_hook = [&gate] { gate.hold(); };
    });
  }

  // SIGTERM (through the event queue, as the signal forwarder posts it) at `offset`.
  void terminateAt(std::chrono::nanoseconds offset, CaptureDaemon& daemon) {
    signalAt(offset, daemon, SIGTERM);
  }
  void signalAt(std::chrono::nanoseconds offset, CaptureDaemon& daemon, int signal) {
    clock_.at(offset, [&daemon, signal] { daemon.events().post(SignalEvent{signal}); });
  }

  std::vector<fs::path> stacks() const { return entries(out() / kStacksDirectory); }
  std::vector<fs::path> results() const { return entries(out() / kResultsDirectory); }
  static std::vector<fs::path> entries(const fs::path& directory) {
    std::vector<fs::path> found;
    std::error_code error;
    for (const auto& entry : fs::directory_iterator(directory, error))
      found.push_back(entry.path());
    std::sort(found.begin(), found.end());
    return found;
  }
  static nlohmann::json manifest(const fs::path& stack) {
    return *readJsonFile((stack / "stack.json").string());
  }
  bool statusMentioned(const std::string& text) const {
    for (const auto& status : notifier_.matching("STATUS="))
      if (status.message.find(text) != std::string::npos) return true;
    return false;
  }

  TempDir dir_;
  ManualClock clock_{utc("2026-06-21T08:00:00Z")};
  RecordingNotifier notifier_{clock_, std::chrono::microseconds(10s)};
  ScriptedDisk disk_;
  ScriptedCameras cameras_;
};

// ---- the config -------------------------------------------------------------------------------

TEST_F(DaemonTest, ConfigWithoutDaemonSectionsRunsOnDefaults) {
  testing::writeText(config_path(), "camera = \"sim:\"\n");
  const auto config = readConfig(config_path());
  ASSERT_TRUE(config) << config.error().message;
  const DaemonConfig& daemon = config->daemon;
  EXPECT_EQ(daemon.schedule.mode, ScheduleMode::kInterval);
  EXPECT_EQ(daemon.schedule.interval, 600s);
  EXPECT_EQ(daemon.schedule.alpha_targets_deg.size(), 16u);  // 5, 10, ... 80
  EXPECT_EQ(daemon.schedule.alpha_targets_deg.front(), 5.0);
  EXPECT_EQ(daemon.schedule.alpha_targets_deg.back(), 80.0);
  EXPECT_EQ(daemon.output.root, "/var/lib/glarecam");
  EXPECT_EQ(daemon.output.reserve_bytes, 1024ull << 20);
  EXPECT_FALSE(daemon.capture.exposures_us);  // auto
  EXPECT_EQ(daemon.faults.inclinometer, InclinometerFaultPolicy::kContinue);
}

TEST_F(DaemonTest, ConfigReadsEveryDaemonKey) {
  testing::writeText(config_path(), R"(camera = "sim:"
[site]
latitude_deg = 48
longitude_deg = 7.85
[module]
azimuth_deg = 180
tilt_deg = 25
[capture]
exposures = [10, 100, 1000]
gain_db = 3
pixel_format = "Mono12"
f_number = 8
nd_transmission = 0.001
max_frame_retries = 7
[schedule]
mode = "alpha-targets"
interval_s = 300
alpha_targets_deg = [60, 20, 40, 20]
button = false
max_alpha_deg = 75
[output]
root = "data"
reserve_mb = 2048
module = "ACME 400"
processing_threads = 2
[faults]
inclinometer = "pause"
min_tilt_deg = 5
max_tilt_deg = 60
camera_max_failures = 3
camera_backoff_s = 5
camera_backoff_max_s = 60
)");
  const auto config = readConfig(config_path());
  ASSERT_TRUE(config) << config.error().message;
  const DaemonConfig& d = config->daemon;
  EXPECT_EQ(d.capture.exposures_us, (std::vector<double>{10, 100, 1000}));
  EXPECT_EQ(d.capture.gain_db, 3);
  EXPECT_EQ(d.capture.pixel_format, "Mono12");
  EXPECT_EQ(d.capture.nd_transmission, 0.001);
  EXPECT_EQ(d.capture.max_frame_retries, 7);
  EXPECT_EQ(d.schedule.mode, ScheduleMode::kAlphaTargets);
  EXPECT_EQ(d.schedule.alpha_targets_deg, (std::vector<double>{20, 40, 60}));  // sorted, once
  EXPECT_FALSE(d.schedule.button);
  EXPECT_EQ(d.schedule.max_alpha_deg, 75);
  EXPECT_EQ(d.output.root, dir_.path() / "data");  // relative to the config's directory
  EXPECT_EQ(d.output.reserve_bytes, 2048ull << 20);
  EXPECT_EQ(d.output.module, "ACME 400");
  EXPECT_EQ(d.output.processing_threads, 2u);
  EXPECT_EQ(d.faults.inclinometer, InclinometerFaultPolicy::kPause);
  EXPECT_EQ(d.faults.max_tilt_deg, 60);
  EXPECT_EQ(d.faults.camera_max_failures, 3);
  EXPECT_EQ(d.faults.camera_backoff, 5s);
  EXPECT_EQ(d.faults.camera_backoff_max, 60s);
}

TEST_F(DaemonTest, ConfigErrorsNameTheFileAndLine) {
  const auto expectError = [&](const std::string& text, const std::string& expected) {
    testing::writeText(config_path(), text);
    const auto config = readConfig(config_path());
    ASSERT_FALSE(config) << text;
    EXPECT_EQ(config.error().code, ErrorCode::kBadInput);
    EXPECT_NE(config.error().message.find(expected), std::string::npos)
        << config.error().message << " lacks " << expected;
  };
  const std::string file = config_path().string();
  expectError("[schedule]\nmode = \"hourly\"\n",
              file + ":2: schedule.mode = \"hourly\" is not one of");
  expectError("[schedule]\n\ninterval_s = 0\n", file + ":3: schedule.interval_s = 0 is outside");
  expectError("[schedule]\nmode = \"alpha-targets\"\n", "needs a [site]");
  expectError("[schedule]\nalpha_targets_deg = [10, \"x\"]\n",
              ":2: schedule.alpha_targets_deg must hold numbers");
  expectError("[schedule]\nalpha_targets_deg = [10, 95]\n", "holds 95, outside");
  expectError("[schedule]\nintervals = 5\n", ":2: unknown key schedule.intervals");
  expectError("[capture]\nexposures = \"fast\"\n",
              ":2: capture.exposures must be \"auto\" or an array");
  expectError("[capture]\nexposures = []\n", "must have 1 to 64 elements");
  expectError("[output]\nreserve_mb = -1\n", ":2: output.reserve_mb = -1 is outside");
  expectError("[faults]\nmin_tilt_deg = 50\nmax_tilt_deg = 40\n", "min_tilt_deg 50 must be below");
  expectError("[faults]\ninclinometer = \"ignore\"\n",
              "faults.inclinometer = \"ignore\" is not one of");
  expectError("[faults]\ncamera_backoff_s = 100\ncamera_backoff_max_s = 10\n",
              "is below camera_backoff_s");
  expectError("[daemon]\n", "unknown section [daemon]");
}

TEST(RigConfig, TheShippedExampleIsValid) {
  const auto example = testing::testDataDir() / ".." / ".." / "firmware-config" / "glarecam.toml";
  const auto whole = readConfig(example);
  ASSERT_TRUE(whole) << whole.error().message;
  const rig::RigConfig* config = &whole->rig;
  EXPECT_TRUE(config->site && config->inclinometer && config->gpio && config->module_azimuth_deg);
}

TEST_F(DaemonTest, TheShippedExampleStatesTheDefaults) {
  const fs::path firmware = testing::testDataDir() / ".." / ".." / "firmware-config";
  const auto example = readConfig(firmware / "glarecam.toml");
  ASSERT_TRUE(example) << example.error().message;
  testing::writeText(config_path(), "camera = \"sim:\"\n");
  const auto defaults = readConfig(config_path());
  ASSERT_TRUE(defaults);
  const DaemonConfig& a = example->daemon;
  const DaemonConfig& b = defaults->daemon;
  EXPECT_EQ(a.capture.exposures_us, b.capture.exposures_us);
  EXPECT_EQ(a.capture.max_frame_retries, b.capture.max_frame_retries);
  EXPECT_EQ(a.schedule.mode, b.schedule.mode);
  EXPECT_EQ(a.schedule.interval, b.schedule.interval);
  EXPECT_EQ(a.schedule.alpha_targets_deg, b.schedule.alpha_targets_deg);
  EXPECT_EQ(a.schedule.max_alpha_deg, b.schedule.max_alpha_deg);
  EXPECT_EQ(a.output.root, b.output.root);
  EXPECT_EQ(a.output.reserve_bytes, b.output.reserve_bytes);
  EXPECT_EQ(a.output.processing_threads, b.output.processing_threads);
  EXPECT_EQ(a.faults.camera_max_failures, b.faults.camera_max_failures);
  EXPECT_EQ(a.faults.camera_backoff, b.faults.camera_backoff);
  EXPECT_EQ(a.faults.camera_backoff_max, b.faults.camera_backoff_max);
  EXPECT_EQ(a.faults.max_tilt_deg, b.faults.max_tilt_deg);
}

TEST_F(DaemonTest, GenicamPresetsAreReadIntoOneFeatureString) {
  const fs::path presets = testing::testDataDir() / ".." / ".." / "firmware-config" / "genicam";
  int read = 0;
  for (const auto& entry : fs::directory_iterator(presets)) {
    const auto features = readGenicamPreset(entry.path());
    ASSERT_TRUE(features) << features.error().message;
    EXPECT_NE(features->find("ExposureAuto=Off"), std::string::npos) << entry.path();
    ++read;
  }
  EXPECT_GE(read, 4);
  testing::writeText(dir_ / "preset.conf", "# comment\n\n  Width=320\nGammaEnable=false\n");
  testing::writeText(config_path(),
                     "camera = \"aravis:\"\n[capture]\ngenicam_preset = \"preset.conf\"\n");
  const auto config = readConfig(config_path());
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->daemon.capture.genicam_features, "Width=320 GammaEnable=false");
  testing::writeText(dir_ / "preset.conf", "Width=320\nGamma Enable = false\n");
  const auto bad = readConfig(config_path());
  ASSERT_FALSE(bad);
  EXPECT_NE(
      bad.error().message.find((dir_ / "preset.conf").string() + ":2: expected Feature=Value"),
      std::string::npos)
      << bad.error().message;
  fs::remove(dir_ / "preset.conf");
  EXPECT_FALSE(readConfig(config_path()));
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

// ---- the interval schedule and what each stack becomes ----------------------------------------

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

// ---- other triggers ---------------------------------------------------------------------------

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

// ---- the α targets ----------------------------------------------------------------------------

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
}

TEST(AlphaSchedule, CrossingsAgreeWithAFineScan) {
  const sun::SiteLocation site{.latitude_deg = 48, .longitude_deg = 7.85, .altitude_m = 278};
  const sun::ModuleOrientation module{.tilt_deg = 24.5, .azimuth_deg = 180};
  const UtcTime from = utc("2026-06-21T00:00:00Z");
  const std::vector<double> targets{10, 45, 80};
  const auto crossings = alphaCrossings(site, module, from, 24h, targets);
  ASSERT_TRUE(crossings) << crossings.error().message;
  ASSERT_EQ(crossings->size(), 6u);  // each target morning and afternoon
  for (const AlphaCrossing& crossing : *crossings) {
    const auto at = sunIncidence(site, module, crossing.time);
    ASSERT_TRUE(at);
    EXPECT_TRUE(at->sun_up);
    // Bisected to 0.5 s, during which α moves < 0.005° (at most ~0.6°/min near sunrise).
    EXPECT_NEAR(at->alpha_deg, crossing.target_deg, 0.005);
  }
  EXPECT_FALSE((*crossings)[0].rising);
  EXPECT_TRUE((*crossings)[5].rising);
  for (std::size_t i = 1; i < crossings->size(); ++i)
    EXPECT_LT((*crossings)[i - 1].time, (*crossings)[i].time);
}

TEST(AlphaSchedule, NoCrossingWhenTheSunNeverReachesTheTarget) {
  // A north-facing vertical wall at 48° N: the sun never shines on it at α 5°.
  const sun::SiteLocation site{.latitude_deg = 48, .longitude_deg = 7.85};
  const auto crossings = alphaCrossings(site, {.tilt_deg = 90, .azimuth_deg = 0},
                                        utc("2026-12-21T00:00:00Z"), 24h, std::vector<double>{5});
  ASSERT_TRUE(crossings);
  EXPECT_TRUE(crossings->empty());
}

// ---- faults -----------------------------------------------------------------------------------

TEST_F(DaemonTest, CameraLostMidBracketIsReopenedWithBackoff) {
  writeConfig();
  std::vector<std::chrono::nanoseconds> opens;
  auto script = cameras_.opener();
  cameras_.loseAtCall(3);  // mid-way through the first bracket; opens fail until healed
  auto daemon = makeDaemon({}, [&](DaemonServices& services) {
    services.open_camera = [&](std::string_view uri, const capture::CameraOptions& options,
                               const capture::SceneAlphaSource& scene_alpha) {
      opens.push_back(clock_.elapsed());
      return script(uri, options, scene_alpha);
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
  // The stacks directory turns into a file (a refusal statvfs cannot see) between two stacks:
  // the 120 s stack's write fails; it is kept in memory and capture pauses. At 500 s the file
  // goes; the next disk check writes a probe, then the kept stack.
  clock_.at(100s, [&] {
    fs::remove_all(out() / kStacksDirectory);
    testing::writeText(out() / kStacksDirectory, "not a directory");
  });
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

// On a worker thread the write runs in real time while the manual clock races on, so these two
// check only the outcomes (the kept-and-retried sequence itself is checked inline above).
TEST_F(DaemonTest, OnAWorkerThreadAStackTheDiskRefusedIsWrittenOnceItTakesIt) {
  writeConfig({.schedule = "mode = \"button\""});
  auto daemon = makeDaemon(
      {}, [](DaemonServices& services) { services.worker_mode = StackWorker::Mode::kThread; });
  clock_.at(5s, [&] {
    fs::remove_all(out() / kStacksDirectory);
    testing::writeText(out() / kStacksDirectory, "not a directory");
  });
  signalAt(10s, *daemon, SIGUSR1);
  clock_.at(100s, [&] { fs::remove(out() / kStacksDirectory); });
  clock_.at(200s, [&] {  // the loop waits here until the stack has landed (kept or not)
    while (!fs::exists(out() / kStacksDirectory / "20260621T080010Z-a40.00" / "stack.json"))
      std::this_thread::sleep_for(1ms);
  });
  terminateAt(300s, *daemon);
  ASSERT_TRUE(daemon->run());
  EXPECT_EQ(daemon->state().stacks_written, 1u);
  EXPECT_EQ(daemon->state().stacks_failed, 0u);
}

TEST_F(DaemonTest, OnAWorkerThreadAStackTheDiskStillRefusesAtStopIsReportedLost) {
  writeConfig({.schedule = "mode = \"button\""});
  auto daemon = makeDaemon(
      {}, [](DaemonServices& services) { services.worker_mode = StackWorker::Mode::kThread; });
  clock_.at(5s, [&] {
    fs::remove_all(out() / kStacksDirectory);
    testing::writeText(out() / kStacksDirectory, "not a directory");
  });
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

// ---- restarts ---------------------------------------------------------------------------------

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

// ---- the pure parts ---------------------------------------------------------------------------

TEST(CameraSupervisor, BackoffDoublesToItsCapAndSuccessClearsTheCount) {
  int opens = 0;
  CameraSupervisor supervisor(
      {.camera_max_failures = 4, .camera_backoff = 2s, .camera_backoff_max = 10s},
      [&](std::string_view, const capture::CameraOptions&,
          const capture::SceneAlphaSource&) -> Result<std::unique_ptr<capture::Camera>> {
        ++opens;
        return hardwareError("absent");
      },
      {});
  supervisor.configure("sim:", {},
                       {.camera_max_failures = 4, .camera_backoff = 2s, .camera_backoff_max = 10s});
  EXPECT_EQ(supervisor.backoffAfter(1), 2s);
  EXPECT_EQ(supervisor.backoffAfter(2), 4s);
  EXPECT_EQ(supervisor.backoffAfter(3), 8s);
  EXPECT_EQ(supervisor.backoffAfter(4), 10s);
  EXPECT_EQ(supervisor.backoffAfter(40), 10s);
  const SteadyTime t0{};
  EXPECT_FALSE(supervisor.acquire(t0));
  EXPECT_EQ(supervisor.retryAt(), t0 + 2s);
  EXPECT_FALSE(supervisor.acquire(t0 + 1s));  // too soon: not even tried
  EXPECT_EQ(opens, 1);
  EXPECT_FALSE(supervisor.acquire(t0 + 2s));
  EXPECT_EQ(supervisor.failures(), 2);
  EXPECT_FALSE(supervisor.exhausted());
  supervisor.succeeded();
  EXPECT_EQ(supervisor.failures(), 0);
}

TEST(DaemonStatus, OneLineWithEveryFaultAndTheLedShowsTheWorst) {
  DaemonState state;
  state.ready = true;
  EXPECT_EQ(statusLine(state, "every 600 s"), "ready, every 600 s");
  EXPECT_EQ(ledState(state, false), rig::RigState::ready());
  EXPECT_EQ(ledState(state, true), rig::RigState::capturing());
  state.last_stack = "20260621T101503Z-a42.30";
  state.last_alpha_deg = 42.3;
  state.last_capture_time = utc("2026-06-21T10:15:03.25Z");
  state.next_capture_time = utc("2026-06-21T10:25:03Z");
  state.clock_warning = "not synchronised";
  EXPECT_EQ(statusLine(state, "every 600 s"),
            "ready, every 600 s; last 20260621T101503Z-a42.30 (α 42.30°) at "
            "2026-06-21T10:15:03Z; next at 2026-06-21T10:25:03Z; clock: not synchronised");
  EXPECT_EQ(ledState(state, false), rig::RigState::faulted(rig::FaultCode::kClock));
  state.disk_fault = "full";
  EXPECT_TRUE(statusLine(state, "x").starts_with("paused, x"));
  EXPECT_EQ(ledState(state, false), rig::RigState::faulted(rig::FaultCode::kDisk));
  state.camera_fault = "lost";
  EXPECT_EQ(ledState(state, false), rig::RigState::faulted(rig::FaultCode::kCamera));
  state.stopping = true;
  EXPECT_TRUE(statusLine(state, "x").starts_with("stopping, x"));
  EXPECT_EQ(statusLine(state, "x").find("next at"), std::string::npos);
}

TEST(DayProducts, TheDayIsTheSitesMeanSolarDay) {
  EXPECT_EQ(stackDay("20260621T101503Z-a42.30", std::nullopt), "2026-06-21");
  EXPECT_EQ(stackDay("20260621T231503Z", 7.85), "2026-06-21");    // 23:46 local mean time
  EXPECT_EQ(stackDay("20260621T234503Z", 7.85), "2026-06-22");    // 00:16
  EXPECT_EQ(stackDay("20260622T010000Z", -105.0), "2026-06-21");  // Colorado: 18:00 the day before
  EXPECT_FALSE(stackDay("alpha-40", std::nullopt));
  EXPECT_FALSE(stackDay("20261341T101503Z", std::nullopt));
}

TEST(DiskSpace, PauseReasonsInWords) {
  EXPECT_EQ(diskPauseReason({.free_bytes = 2ull << 30}, 1ull << 30, "/data"), "");
  EXPECT_EQ(diskPauseReason({.free_bytes = 512ull << 20}, 1ull << 30, "/data"),
            "512.0 MiB free on /data, below the 1.0 GiB reserve");
  EXPECT_NE(
      diskPauseReason({.free_bytes = 2ull << 30, .read_only = true}, 0, "/data").find("read-only"),
      std::string::npos);
  EXPECT_EQ(formatBytes(512), "512 B");
  const auto probed = makeStatvfsDiskProbe()->probe(fs::temp_directory_path() / "not" / "yet");
  ASSERT_TRUE(probed);  // the nearest existing parent's filesystem
  EXPECT_GT(probed->total_bytes, 0u);
}

TEST(DaemonClock, TimeLapseRunsTheWallClockFaster) {
  const UtcTime start = utc("2026-06-21T05:00:00Z");
  const TimeLapseClock clock(start, 600.0);
  const UtcTime later = start + 1h;
  // An hour of simulated sun is 6 s of real time.
  const auto real = clock.steadyAt(later) - clock.steadyAt(start);
  EXPECT_NEAR(std::chrono::duration<double>(real).count(), 6.0, 1e-6);
  EXPECT_TRUE(clock.clockStatus().synchronised);
  EXPECT_GE(clock.utcNow(), start);
}

TEST(JournalSink, EntriesCarryTheScopesFieldsAndDropInvalidNames) {
  {
    const ScopedLogFields outer(LogFields{{"GLARECAM_EVENT", "capture"}});
    const ScopedLogFields inner(
        LogFields{{"GLARECAM_STACK", "20260621T101503Z-a42.30"}, {"_PID", "1"}, {"lower", "x"}});
    EXPECT_EQ(journalEntry("glarecamd", 4, "disk: full", currentLogFields()),
              (std::vector<std::string>{"MESSAGE=disk: full", "PRIORITY=4",
                                        "SYSLOG_IDENTIFIER=glarecamd", "GLARECAM_EVENT=capture",
                                        "GLARECAM_STACK=20260621T101503Z-a42.30"}));
  }
  EXPECT_TRUE(currentLogFields().empty());  // the scopes are gone
  // Not connected to the journal here: stderr is a terminal or a file, not $JOURNAL_STREAM's.
  ::setenv("JOURNAL_STREAM", "1:1", 1);
  EXPECT_FALSE(stderrIsJournal());
  ::unsetenv("JOURNAL_STREAM");
  EXPECT_FALSE(stderrIsJournal());
  // Without a journal to send to, logging through the sink must not throw or stop anything.
  auto logger = std::make_shared<spdlog::logger>("journal-test", makeJournalSink("glarecamd"));
  EXPECT_NO_THROW(logger->error("no journald here"));
}

}  // namespace
}  // namespace glarecam::daemon
