// The rig around the camera while stacks are taken, on the lab rig of the tests (the simulated
// inclinometer under a module tilted 50° facing a lamp on the horizon: α 40°): the tilt's
// plausibility rule, α measured and recorded (or why it is unknown), and the session as a
// capture series' rig.
#include "daemon/hardware/rig_session.h"

#include <gtest/gtest.h>

#include <string>

#include "daemon/daemon_config.h"
#include "daemon/daemon_fixture.h"
#include "sun/clear_sky.h"
#include "support/test_support.h"

namespace glarecam::daemon {
namespace {

using testing::TempDir;

RigSession labSession(const Config& config) {
  return RigSession(config.rig, {.faults = config.daemon.faults, .log_name = "test"});
}

rig::RigGeometry tiltedBy(double module_tilt_deg) {
  rig::RigGeometry geometry;
  geometry.tilt.emplace();
  geometry.tilt->module_tilt_deg = module_tilt_deg;
  geometry.inclinometer_uri = "sim:70";
  return geometry;
}

TEST(RigSession, ATiltOutsideTheFaultsRangeIsImplausible) {
  const FaultConfig faults{.min_tilt_deg = 5, .max_tilt_deg = 60};
  EXPECT_TRUE(checkPlausibleTilt(tiltedBy(50), faults));
  EXPECT_TRUE(checkPlausibleTilt(tiltedBy(5), faults));  // the range's ends are plausible
  EXPECT_TRUE(checkPlausibleTilt(tiltedBy(60), faults));
  const Status high = checkPlausibleTilt(tiltedBy(70), faults);
  ASSERT_FALSE(high);
  EXPECT_EQ(high.error().code, ErrorCode::kHardware);
  EXPECT_EQ(high.error().message,
            "sim:70: implausible tilt 70.00° (outside [5, 60]°: a loose sensor, a moved rig?)");
  EXPECT_FALSE(checkPlausibleTilt(tiltedBy(4.99), faults));
  // A tilt fixed in the config is the operator's word, not a sensor's reading.
  EXPECT_TRUE(checkPlausibleTilt(rig::RigGeometry{}, {.min_tilt_deg = 80, .max_tilt_deg = 85}));
}

TEST(RigSession, MeasuresAlphaFromTheConfigsRig) {
  TempDir dir;
  RigSession session = labSession(labConfig(dir.path()));
  EXPECT_TRUE(session.measuresAlpha());
  EXPECT_FALSE(session.sceneAlphaDeg());
  ASSERT_TRUE(session.openSensors());
  EXPECT_TRUE(session.sensorsOpen());
  const auto geometry = session.measure(utcNow(), std::nullopt);
  ASSERT_TRUE(geometry) << geometry.error().message;
  // The simulated inclinometer's noise over 4 samples: 0.05° is many σ.
  EXPECT_NEAR(geometry->alpha_deg, 40.0, 0.05);
  ASSERT_TRUE(session.lastGeometry());
  EXPECT_EQ(session.lastGeometry()->alpha_deg, geometry->alpha_deg);
  EXPECT_EQ(session.sceneAlphaDeg(), geometry->alpha_deg);
}

// A simulated camera's scene under the sun is lit by the clear-sky sun of the site at the hour
// the geometry was measured; a lab lamp gives no such value (its E is the operator's).
TEST(RigSession, TheScenesSunIsTheClearSkySunOfTheSiteThen) {
  TempDir dir;
  RigSession lab = labSession(labConfig(dir.path()));
  ASSERT_TRUE(lab.measure(utcNow(), std::nullopt));
  EXPECT_TRUE(lab.sceneState().alpha_deg);
  EXPECT_FALSE(lab.sceneState().source_illuminance_lx);
  TempDir outdoors;
  const Config config = labConfig(outdoors.path(), {.site = true});
  RigSession session = labSession(config);
  EXPECT_FALSE(session.sceneState().source_illuminance_lx);  // nothing measured yet
  // 2026-06-21 11:30 UTC at 48° N 7.85° E: the sun near its highest.
  const UtcTime noon = std::chrono::sys_days{std::chrono::year{2026} / 6 / 21} +
                       std::chrono::hours{11} + std::chrono::minutes{30};
  const auto geometry = session.measure(noon, std::nullopt);
  ASSERT_TRUE(geometry) << geometry.error().message;
  const capture::SceneState state = session.sceneState();
  EXPECT_EQ(state.alpha_deg, geometry->alpha_deg);
  const auto sky = sun::clearSkySource(noon, *config.rig.site);
  ASSERT_TRUE(sky) << sky.error().message;
  ASSERT_TRUE(state.source_illuminance_lx);
  EXPECT_EQ(*state.source_illuminance_lx, sky->illuminance_lx);
  // A midsummer noon sun at 65° elevation: near the 100 klx reference (IES RP-21 gives ~100 klx).
  EXPECT_NEAR(*state.source_illuminance_lx, 100'000, 8'000);
}

TEST(RigSession, AnImplausibleTiltIsAFaultNeverAnAlpha) {
  TempDir dir;
  RigSession session = labSession(labConfig(dir.path(), {.faults = "max_tilt_deg = 45"}));
  const auto geometry = session.measure(utcNow(), std::nullopt);  // opens the sensors itself
  ASSERT_FALSE(geometry);
  EXPECT_EQ(geometry.error().code, ErrorCode::kHardware);
  EXPECT_NE(geometry.error().message.find("sim:50: implausible tilt 50.0"), std::string::npos)
      << geometry.error().message;
  EXPECT_FALSE(session.lastGeometry());
  EXPECT_FALSE(session.sceneAlphaDeg());
}

TEST(RigSession, RecordsAlphaOrWhyItIsUnknown) {
  TempDir dir;
  RigSession session = labSession(labConfig(dir.path()));
  const auto measured = session.measure(utcNow(), std::nullopt);
  ASSERT_TRUE(measured) << measured.error().message;
  capture::CaptureSettings settings;
  RigSession::record(measured, settings);
  EXPECT_EQ(settings.alpha_deg, measured->alpha_deg);
  ASSERT_TRUE(settings.geometry);
  EXPECT_EQ((*settings.geometry)["inclinometer"]["uri"], "sim:50");

  capture::CaptureSettings unknown;
  RigSession::record(hardwareError("sim:50: saturated"), unknown);
  EXPECT_FALSE(unknown.alpha_deg);
  ASSERT_TRUE(unknown.geometry);
  EXPECT_EQ(*unknown.geometry, (nlohmann::json{{"alpha_unknown", "sim:50: saturated"}}));
}

TEST(RigSession, AConfigThatGivesNoAlphaMeasuresNothing) {
  TempDir dir;
  testing::writeText(dir / "glarecam.toml", "camera = \"sim:\"\n");
  const auto config = readConfig(dir / "glarecam.toml");
  ASSERT_TRUE(config) << config.error().message;
  RigSession session(config->rig, {});
  EXPECT_FALSE(session.measuresAlpha());
  ASSERT_TRUE(session.openSensors());
  EXPECT_FALSE(session.sensorsOpen());
  const auto geometry = session.measure(utcNow(), std::nullopt);
  ASSERT_FALSE(geometry);
  EXPECT_EQ(geometry.error().code, ErrorCode::kBadInput);
  EXPECT_NE(geometry.error().message.find("the config gives no α"), std::string::npos);
  ASSERT_TRUE(session.openGpio());  // no [gpio]: nothing to open
  EXPECT_EQ(session.io(), nullptr);
}

TEST(RigSession, OpensTheConfigsGpio) {
  TempDir dir;
  RigSession session = labSession(labConfig(dir.path()));
  ASSERT_TRUE(session.openGpio());
  ASSERT_NE(session.io(), nullptr);
  EXPECT_TRUE(session.io()->hasLed());
  EXPECT_FALSE(session.io()->hasButton());
  session.closeGpio();
  EXPECT_EQ(session.io(), nullptr);
}

TEST(RigSession, AsASeriesRigItMeasuresBeforeEachStack) {
  TempDir dir;
  RigSession session = labSession(labConfig(dir.path()));
  capture::CaptureSettings settings;
  const auto first = session.prepareStack(settings, 0);
  ASSERT_TRUE(first) << first.error().message;
  EXPECT_TRUE(*first);
  ASSERT_TRUE(settings.alpha_deg);
  EXPECT_NEAR(*settings.alpha_deg, 40.0, 0.05);
  EXPECT_TRUE(settings.geometry);

  RigSession implausible = labSession(labConfig(dir.path(), {.faults = "max_tilt_deg = 45"}));
  capture::CaptureSettings refused;
  const auto prepared = implausible.prepareStack(refused, 0);
  ASSERT_FALSE(prepared);
  EXPECT_EQ(prepared.error().code, ErrorCode::kHardware);
  EXPECT_FALSE(refused.alpha_deg);
}

}  // namespace
}  // namespace glarecam::daemon
