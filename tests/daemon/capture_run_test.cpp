// `glarecam capture` as one call: its options checked first, a series from the simulated camera,
// the rig's config giving the camera and α, and a rig whose tilt is implausible refused before any
// exposure.
#include "daemon/capture_run.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "capture/camera_registry.h"
#include "core/build_config.h"
#include "core/stack_io.h"
#include "daemon/daemon_fixture.h"
#include "support/test_support.h"

namespace glarecam::daemon {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

// Two quick fixed exposures into `out`, without a progress line.
CaptureRunOptions quietRun(const fs::path& out) {
  CaptureRunOptions options;
  options.capture.exposures_us = std::vector<double>{1000, 10000};
  options.series.out = out;
  options.show_progress = false;
  return options;
}

std::vector<fs::path> stacksIn(const fs::path& directory) {
  std::vector<fs::path> found;
  std::error_code error;
  for (const auto& entry : fs::directory_iterator(directory, error))
    if (isStackDirectory(entry.path())) found.push_back(entry.path());
  return found;
}

// Runs `options` into `out` and reads back the one stack's manifest (a failure fails the test and
// gives an empty manifest).
StackManifest captureOne(CaptureRunOptions options, const fs::path& out) {
  options.series.out = out;
  const Status run = runCapture(options);
  EXPECT_TRUE(run) << run.error().message;
  const auto stacks = stacksIn(out);
  EXPECT_EQ(stacks.size(), 1u);
  if (stacks.size() != 1) return {};
  const auto read = readStack(stacks.front());
  EXPECT_TRUE(read) << read.error().message;
  return read ? read->manifest : StackManifest{};
}

std::string problem(const CaptureRunOptions& options) {
  const Status status = options.validate();
  EXPECT_FALSE(status);
  if (status) return {};
  EXPECT_EQ(status.error().code, ErrorCode::kBadInput);
  return status.error().message;
}

TEST(CaptureRun, OptionsAreCheckedBeforeAnythingOpens) {
  TempDir dir;
  EXPECT_TRUE(quietRun(dir / "out").validate());
  CaptureRunOptions options = quietRun(dir / "out");
  options.alpha_deg = 90;
  EXPECT_EQ(problem(options), "capture: --alpha must be in [0, 90) degrees");
  options = quietRun(dir / "out");
  options.capture.f_number = 0;
  EXPECT_EQ(problem(options), "capture: --f-number must be positive");
  options = quietRun(dir / "out");
  options.capture.nd_transmission = 1.5;
  EXPECT_EQ(problem(options), "capture: --nd-transmission must be in (0, 1]");
  options = quietRun(dir / "out");
  options.on_button = true;
  EXPECT_EQ(problem(options), "capture: --on-button needs a --config with a [gpio] button line");
  options = quietRun(dir / "out");
  options.series.count = 0;
  EXPECT_EQ(problem(options), "capture: --count must be at least 1");
  options = quietRun(dir / "out");  // no camera given anywhere
  EXPECT_EQ(runCapture(options).error().message,
            "capture: give --camera URI (or a --config with camera = \"URI\")");
  EXPECT_FALSE(fs::exists(dir / "out"));
}

TEST(CaptureRun, TakesTheSeriesFromTheSimulatedCamera) {
  TempDir dir;
  CaptureRunOptions options = quietRun(dir / "out");
  options.camera_uri = "sim:size=64x48";
  options.alpha_deg = 35;
  options.series.count = 2;
  ASSERT_TRUE(runCapture(options));
  const auto stacks = stacksIn(dir / "out");
  ASSERT_EQ(stacks.size(), 2u);
  for (const fs::path& stack : stacks) {
    const auto read = readStack(stack);
    ASSERT_TRUE(read) << read.error().message;
    EXPECT_EQ(read->manifest.alpha_deg, 35.0);
    EXPECT_EQ(read->frames.size(), 2u);
  }
}

TEST(CaptureRun, TheRigsConfigGivesTheCameraAndAlpha) {
  TempDir dir;
  testing::writeText(dir / "glarecam.toml", rigToml({}));
  CaptureRunOptions options = quietRun(dir / "out");
  options.config_path = dir / "glarecam.toml";
  ASSERT_TRUE(runCapture(options));
  const auto stacks = stacksIn(dir / "out");
  ASSERT_EQ(stacks.size(), 1u);
  const auto read = readStack(stacks.front());
  ASSERT_TRUE(read) << read.error().message;
  ASSERT_TRUE(read->manifest.alpha_deg);
  EXPECT_NEAR(*read->manifest.alpha_deg, 40.0, 0.05);  // the lab rig's
  EXPECT_EQ(read->manifest.source["camera"]["backend"], "sim");
  EXPECT_EQ(read->manifest.source["geometry"]["inclinometer"]["uri"], "sim:50");
  EXPECT_FALSE(read->manifest.source_illuminance);  // a lamp the config states no E for

  options.alpha_deg = 40;  // the config's [source] gives α already
  const Status twice = runCapture(options);
  ASSERT_FALSE(twice);
  EXPECT_NE(twice.error().message.find("--alpha contradicts"), std::string::npos)
      << twice.error().message;
}

#if GLARECAM_WITH_MODBUS
// The rig's [illuminance] instrument (here the simulated one, over Modbus TCP on loopback) is
// sampled during each bracket: the stack records it as a sensor source; failing, the stack is
// written unreferred; a source given for the series is kept and the instrument not read.
TEST(CaptureRun, TheRigsInstrumentGivesEachStackItsSource) {
  TempDir dir;
  const std::string instrument =
      "[illuminance]\ntransport = \"sim\"\ndata_type = \"float32\"\nunits = \"W/m2\"\n"
      "uncertainty_pct = 2\nsample_interval_ms = 5\n";
  testing::writeText(dir / "glarecam.toml", rigToml({.extra = instrument}));
  CaptureRunOptions options = quietRun(dir / "out");
  options.config_path = dir / "glarecam.toml";
  const StackManifest sensed = captureOne(options, dir / "out");
  ASSERT_TRUE(sensed.source_illuminance);
  EXPECT_EQ(sensed.source_illuminance->origin, IlluminanceOrigin::kSensor);
  EXPECT_NEAR(sensed.source_illuminance->illuminance_lx, 90'000, 0.1);

  testing::writeText(dir / "glarecam.toml",
                     rigToml({.extra = instrument + "sim_fault = \"out-of-range\"\n"}));
  const StackManifest faulted = captureOne(options, dir / "faulted");
  ASSERT_TRUE(faulted.id);
  EXPECT_FALSE(faulted.source_illuminance);

  options.source_illuminance = SourceIlluminance{.illuminance_lx = 55'000};
  const StackManifest given = captureOne(options, dir / "given");
  ASSERT_TRUE(given.source_illuminance);
  EXPECT_EQ(given.source_illuminance->origin, IlluminanceOrigin::kGiven);
  EXPECT_DOUBLE_EQ(given.source_illuminance->illuminance_lx, 55'000);
}
#endif

TEST(CaptureRun, AnImplausibleTiltIsRefusedBeforeAnyExposure) {
  TempDir dir;
  testing::writeText(dir / "glarecam.toml", rigToml({.faults = "max_tilt_deg = 45"}));
  CaptureRunOptions options = quietRun(dir / "out");
  options.config_path = dir / "glarecam.toml";
  const Status refused = runCapture(options);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::kHardware);
  EXPECT_NE(refused.error().message.find("implausible tilt 50.0"), std::string::npos)
      << refused.error().message;
  EXPECT_TRUE(stacksIn(dir / "out").empty());
}

TEST(CaptureRun, ACameraThatKnowsItsLensIsNotToldAnother) {
  auto camera = capture::openCamera("sim:size=64x48", {});
  ASSERT_TRUE(camera) << camera.error().message;
  capture::CaptureSettings settings;
  EXPECT_TRUE(checkAgainstCamera(**camera, settings));
  settings.optics.f_number = 4;
  const Status refused = checkAgainstCamera(**camera, settings);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::kBadInput);
  EXPECT_EQ(refused.error().message,
            "capture: sim:size=64x48 knows its own lens and filter; --f-number and "
            "--nd-transmission are for real cameras");
}

// A lab lamp whose illuminance the config states ([source] illuminance) lights every stack of the
// series: recorded as the manifest's source (origin given), and the simulated scene lit by it;
// --source-illuminance replaces it.
TEST(CaptureRun, ALabLampsStatedIlluminanceIsEveryStacksSource) {
  TempDir dir;
  std::string toml = rigToml({});
  const std::string lamp = "[source]\nelevation_deg = 0\nazimuth_deg = 180\n";
  ASSERT_NE(toml.find(lamp), std::string::npos);
  toml.replace(toml.find(lamp), lamp.size(), lamp + "illuminance = \"61000±1500\"\n");
  testing::writeText(dir / "glarecam.toml", toml);
  CaptureRunOptions options = quietRun(dir / "out");
  options.config_path = dir / "glarecam.toml";
  const auto lit_by = [](const fs::path& out) {  // the scene as the simulated camera lit it
    const auto stacks = stacksIn(out);
    if (stacks.size() != 1) return -1.0;
    return nlohmann::json::parse(testing::readText(stacks.front() / "truth.json"))
        .value("source_illuminance_lx", -1.0);
  };
  const StackManifest lamp_lit = captureOne(options, dir / "out");
  ASSERT_TRUE(lamp_lit.source_illuminance);
  EXPECT_EQ(lamp_lit.source_illuminance->illuminance_lx, 61'000);
  EXPECT_EQ(lamp_lit.source_illuminance->illuminance_u_lx, 1'500);
  EXPECT_EQ(lamp_lit.source_illuminance->origin, IlluminanceOrigin::kGiven);
  EXPECT_EQ(lit_by(dir / "out"), 61'000.0);

  options.source_illuminance = SourceIlluminance{.illuminance_lx = 75'000};
  const StackManifest given = captureOne(options, dir / "given");
  ASSERT_TRUE(given.source_illuminance);
  EXPECT_EQ(given.source_illuminance->illuminance_lx, 75'000);
  EXPECT_EQ(lit_by(dir / "given"), 75'000.0);
}

}  // namespace
}  // namespace glarecam::daemon
