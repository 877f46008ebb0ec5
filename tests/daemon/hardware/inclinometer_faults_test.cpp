// What glarecamd makes of the inclinometer's faults, on the lab rig of the tests (the simulated
// inclinometer, α 40°, or one with a scripted fault) and the manual clock: a stack with α unknown
// by default, a pause when configured, the retry 30 s on that clears the fault when the sensor
// reads, a sensor that cannot open, and a rig whose α is not measured.
#include "daemon/hardware/inclinometer_faults.h"

#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "daemon/daemon_fixture.h"
#include "daemon/daemon_test_support.h"
#include "support/test_support.h"

namespace glarecam::daemon {
namespace {

using namespace std::chrono_literals;

struct InclinometerFaultsTest : ::testing::Test {
  testing::TempDir dir;
  testing::ManualClock clock{testing::utc("2026-06-21T10:00:00Z")};
  InclinometerFaults faults{clock};
  DaemonState state;

  // A session on the lab rig whose inclinometer is `uri` ("sim:50,fault=zeros" reads nothing).
  RigSession session(const std::string& uri) {
    const Config config = labConfig(dir.path(), {.inclinometer = uri});
    return RigSession(config.rig, {.faults = config.daemon.faults, .log_name = "test"});
  }
};

TEST_F(InclinometerFaultsTest, AHealthySensorGivesTheGeometryAndNoFault) {
  RigSession rig = session("sim:50");
  capture::CaptureSettings settings;
  const InclinometerFaults::Measured measured =
      faults.measure(rig, {}, state, settings, clock.utcNow());
  ASSERT_TRUE(measured.geometry);
  EXPECT_NEAR(measured.geometry->alpha_deg, 40.0, 0.05);  // the sim's noise over 4 samples
  EXPECT_FALSE(measured.pause);
  EXPECT_EQ(settings.alpha_deg, measured.geometry->alpha_deg);
  EXPECT_EQ(state.inclinometer_fault, "");
  EXPECT_FALSE(faults.retryAt());
}

TEST_F(InclinometerFaultsTest, AFaultTakesTheStackWithAlphaUnknownByDefault) {
  RigSession rig = session("sim:50,fault=zeros");
  capture::CaptureSettings settings;
  const InclinometerFaults::Measured measured =
      faults.measure(rig, {}, state, settings, clock.utcNow());
  EXPECT_FALSE(measured.geometry);
  EXPECT_FALSE(measured.pause);
  EXPECT_FALSE(state.inclinometer_pauses);
  EXPECT_NE(state.inclinometer_fault, "");
  ASSERT_TRUE(settings.geometry && settings.geometry->contains("alpha_unknown"));
  EXPECT_EQ((*settings.geometry)["alpha_unknown"], state.inclinometer_fault);
  EXPECT_EQ(faults.retryAt(), clock.now() + kInclinometerRetry);
}

TEST_F(InclinometerFaultsTest, AFaultPausesCaptureWhenConfigured) {
  RigSession rig = session("sim:50,fault=saturated");
  capture::CaptureSettings settings;
  const FaultConfig pause{.inclinometer = InclinometerFaultPolicy::kPause};
  const InclinometerFaults::Measured measured =
      faults.measure(rig, pause, state, settings, clock.utcNow());
  EXPECT_FALSE(measured.geometry);
  EXPECT_TRUE(measured.pause);
  EXPECT_TRUE(state.inclinometer_pauses);
  EXPECT_NE(state.inclinometer_fault, "");
}

TEST_F(InclinometerFaultsTest, TheRetryClearsTheFaultWhenTheSensorReadsAgain) {
  RigSession broken = session("sim:50,fault=zeros");
  capture::CaptureSettings settings;
  faults.measure(broken, {}, state, settings, clock.utcNow());
  ASSERT_TRUE(faults.retryAt());

  clock.advance(kInclinometerRetry);
  faults.retry(broken, {}, state);  // still broken: the next retry is another 30 s on
  EXPECT_NE(state.inclinometer_fault, "");
  EXPECT_EQ(faults.retryAt(), clock.now() + kInclinometerRetry);

  clock.advance(kInclinometerRetry);
  RigSession mended = session("sim:50");  // the sensor reads again (a reload, a reseated cable)
  faults.retry(mended, {}, state);
  EXPECT_EQ(state.inclinometer_fault, "");
  EXPECT_FALSE(faults.retryAt());
}

TEST_F(InclinometerFaultsTest, ASensorThatCannotOpenIsTheStatusFault) {
  RigSession absent = session("sim:50,fault=absent");
  faults.open(absent, state);
  EXPECT_NE(state.inclinometer_fault, "");
  RigSession present = session("sim:50");
  faults.open(present, state);
  EXPECT_EQ(state.inclinometer_fault, "");
}

TEST_F(InclinometerFaultsTest, ARigWhoseAlphaIsNotMeasuredHasNoInclinometerFaults) {
  RigSession rig(rig::RigConfig{},
                 {.faults = {}, .log_name = "test"});  // neither [site] nor [source]
  capture::CaptureSettings settings;
  const InclinometerFaults::Measured measured =
      faults.measure(rig, {}, state, settings, clock.utcNow());
  EXPECT_FALSE(measured.geometry);
  EXPECT_FALSE(measured.pause);
  EXPECT_EQ(state.inclinometer_fault, "");
  EXPECT_FALSE(faults.retryAt());
}

}  // namespace
}  // namespace glarecam::daemon
