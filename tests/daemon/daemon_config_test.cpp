// glarecamd's config: the defaults, every key of the daemon's sections, errors naming the file and
// line, the shipped example, and the GenICam presets it may name.
#include "daemon/daemon_config.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "daemon/daemon_fixture.h"
#include "support/test_support.h"

namespace glarecam::daemon {
namespace {

namespace fs = std::filesystem;
using namespace std::chrono_literals;

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
  EXPECT_FALSE(daemon.status.listen);  // the status page is off unless asked for
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
keep_stacks_days = 30
keep_results_days = 365
max_use_gib = 1.5
[faults]
inclinometer = "pause"
min_tilt_deg = 5
max_tilt_deg = 60
camera_max_failures = 3
camera_backoff_s = 5
camera_backoff_max_s = 60
[status]
listen = "127.0.0.1:8080"
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
  EXPECT_EQ(d.output.retention.keep_stacks_days, 30);
  EXPECT_EQ(d.output.retention.keep_results_days, 365);
  EXPECT_EQ(d.output.retention.max_use_bytes, 3ull << 29);
  EXPECT_EQ(d.faults.inclinometer, InclinometerFaultPolicy::kPause);
  EXPECT_EQ(d.faults.max_tilt_deg, 60);
  EXPECT_EQ(d.faults.camera_max_failures, 3);
  EXPECT_EQ(d.faults.camera_backoff, 5s);
  EXPECT_EQ(d.faults.camera_backoff_max, 60s);
  EXPECT_EQ(d.status.listen, (ListenAddress{.host = "127.0.0.1", .port = 8080}));
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
  expectError("[output]\nkeep_stacks_days = 0\n", ":2: output.keep_stacks_days = 0 is outside");
  expectError("[output]\nkeep_stacks_days = 1.5\n", "output.keep_stacks_days");
  expectError("[output]\nmax_use_gib = 0\n", ":2: output.max_use_gib = 0 is outside");
  expectError("[output]\nkeep_stacks_days = 30\nkeep_results_days = 7\n",
              file + ":1: [output] keep_results_days: must be at least keep_stacks_days");
  expectError("[faults]\nmin_tilt_deg = 50\nmax_tilt_deg = 40\n", "min_tilt_deg 50 must be below");
  expectError("[faults]\ninclinometer = \"ignore\"\n",
              "faults.inclinometer = \"ignore\" is not one of");
  expectError("[faults]\ncamera_backoff_s = 100\ncamera_backoff_max_s = 10\n",
              "is below camera_backoff_s");
  expectError("[daemon]\n", "unknown section [daemon]");
  expectError("[status]\nlisten = 8080\n", ":2: status.listen must be a string");
  expectError("[status]\n\nlisten = \"rig.local:8080\"\n",
              file + ":3: status.listen: expected ADDRESS:PORT");
  expectError("[status]\nport = 8080\n", ":2: unknown key status.port");
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
  EXPECT_EQ(a.status.listen, b.status.listen);
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

}  // namespace
}  // namespace glarecam::daemon
