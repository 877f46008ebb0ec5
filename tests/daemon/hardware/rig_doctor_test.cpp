// `glarecam doctor`'s checks on the lab rig of the tests (daemon_fixture.h): each part ok with
// the simulated hardware, the camera's test frame taken within the camera's own limits, a camera
// that fails named in its check, an invalid config failing alone with the rest skipped, and the
// camera left alone while glarecamd runs.
#include "daemon/hardware/rig_doctor.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

#include "capture/test_cameras.h"
#include "daemon/daemon_fixture.h"
#include "daemon/daemon_test_support.h"
#include "daemon/hardware/simulated_rig.h"
#include "support/test_support.h"

namespace glarecam::daemon {
namespace {

class RigDoctor : public ::testing::Test {
 protected:
  DoctorOptions options(const RigSpec& spec = {}) {
    testing::writeText(dir_ / "glarecam.toml", rigToml(spec));
    DoctorOptions options;
    options.config_path = dir_ / "glarecam.toml";
    options.disk = &disk_;
    options.unit_state = [](const std::string&) -> Result<std::string> { return "inactive"; };
    return options;
  }

  static const DoctorCheck& check(const std::vector<DoctorCheck>& checks, const std::string& name) {
    const auto found = std::find_if(checks.begin(), checks.end(),
                                    [&](const DoctorCheck& c) { return c.name == name; });
    EXPECT_NE(found, checks.end()) << name;
    return *found;
  }

  testing::TempDir dir_;
  testing::ScriptedDisk disk_;
};

TEST_F(RigDoctor, TheSimulatedLabRigIsReady) {
  DoctorOptions doctor = options();
  const std::vector<DoctorCheck> checks = runDoctor(doctor);
  EXPECT_EQ(check(checks, "config").level, CheckLevel::kOk);
  const DoctorCheck& camera = check(checks, "camera");
  EXPECT_EQ(camera.level, CheckLevel::kOk) << camera.detail;
  EXPECT_NE(camera.detail.find("frame at"), std::string::npos) << camera.detail;
  EXPECT_EQ(check(checks, "inclinometer").level, CheckLevel::kOk);
  EXPECT_EQ(check(checks, "systemd").level, CheckLevel::kWarn);  // inactive: look, not fail
  EXPECT_FALSE(doctor.config_bad_input);
}

// An unsynchronised clock fails a real rig that takes α from the sun; the simulated rig (the
// config glarecamd --simulate writes) is synchronised by construction, as glarecamd's status says
// (rigClockStatus): its sun, α and scene all follow its own clock.
TEST_F(RigDoctor, AnUnsynchronisedClockFailsARealRigButNotTheSimulatedOne) {
  const auto unsynchronised = [] {
    return sun::ClockStatus{.synchronised = false, .detail = "the kernel says so"};
  };
  DoctorOptions simulated = options({.site = true});
  std::filesystem::rename(simulated.config_path, dir_ / kSimulatedRigFileName);
  simulated.config_path = dir_ / kSimulatedRigFileName;
  simulated.clock_status = unsynchronised;
  const std::vector<DoctorCheck> sim_checks = runDoctor(simulated);
  const DoctorCheck& sim_clock = check(sim_checks, "clock");
  EXPECT_EQ(sim_clock.level, CheckLevel::kOk) << sim_clock.detail;
  EXPECT_EQ(sim_clock.detail, simulatedClockStatus().detail);

  RigSpec real{.site = true};
  real.inclinometer = "adxl355:/dev/i2c-1@0x1d";
  DoctorOptions doctor = options(real);
  doctor.clock_status = unsynchronised;
  const std::vector<DoctorCheck> checks = runDoctor(doctor);
  const DoctorCheck& real_clock = check(checks, "clock");
  EXPECT_EQ(real_clock.level, CheckLevel::kFail) << real_clock.detail;
  EXPECT_NE(real_clock.detail.find("a wrong clock is a wrong"), std::string::npos);

  DoctorOptions synchronised = options({.site = true});
  synchronised.clock_status = [] {
    return sun::ClockStatus{.synchronised = true, .estimated_error_s = 0.002, .detail = ""};
  };
  EXPECT_EQ(check(runDoctor(synchronised), "clock").level, CheckLevel::kOk);
}

// Camera::capture refuses a gain outside limits(): the test frame must ask for one inside, also
// on a sensor whose least gain is above 0 dB (1×).
TEST_F(RigDoctor, TheTestFrameIsTakenWithinTheCamerasGainRange) {
  DoctorOptions doctor = options();
  doctor.open_camera = [](std::string_view, const capture::CameraOptions&,
                          const capture::SceneSource&) -> Result<std::unique_ptr<capture::Camera>> {
    return std::make_unique<testing::CountingCamera>(capture::CameraLimits{
        .min_exposure_us = 10, .max_exposure_us = 1e6, .min_gain_db = 1.5, .max_gain_db = 24});
  };
  const DoctorCheck camera = check(runDoctor(doctor), "camera");
  EXPECT_EQ(camera.level, CheckLevel::kOk) << camera.detail;
}

TEST_F(RigDoctor, AFailingCameraIsNamedInItsCheck) {
  DoctorOptions doctor = options();
  doctor.open_camera = [](std::string_view, const capture::CameraOptions&,
                          const capture::SceneSource&) -> Result<std::unique_ptr<capture::Camera>> {
    return std::make_unique<testing::CountingCamera>(
        capture::CameraLimits{.min_exposure_us = 10, .max_exposure_us = 1e6},
        testing::CountingCamera::Answer::kError);
  };
  const DoctorCheck camera = check(runDoctor(doctor), "camera");
  EXPECT_EQ(camera.level, CheckLevel::kFail);
  EXPECT_NE(camera.detail.find("control-lost"), std::string::npos) << camera.detail;
}

TEST_F(RigDoctor, AnInvalidConfigFailsAloneAndSkipsTheParts) {
  DoctorOptions doctor = options({.schedule = "interval_s = \"soon\""});
  const std::vector<DoctorCheck> checks = runDoctor(doctor);
  EXPECT_EQ(check(checks, "config").level, CheckLevel::kFail);
  EXPECT_EQ(check(checks, "camera").level, CheckLevel::kSkip);
  EXPECT_EQ(check(checks, "disk").level, CheckLevel::kSkip);
  EXPECT_TRUE(doctor.config_bad_input);
  EXPECT_TRUE(anyFailed(checks));
}

TEST_F(RigDoctor, TheCameraIsLeftAloneWhileGlarecamdRuns) {
  DoctorOptions doctor = options();
  bool opened = false;
  doctor.open_camera =
      [&](std::string_view, const capture::CameraOptions&,
          const capture::SceneSource&) -> Result<std::unique_ptr<capture::Camera>> {
    opened = true;
    return hardwareError("must not be opened");
  };
  doctor.unit_state = [](const std::string&) -> Result<std::string> { return "active (running)"; };
  const std::vector<DoctorCheck> checks = runDoctor(doctor);
  EXPECT_EQ(check(checks, "camera").level, CheckLevel::kSkip);
  EXPECT_FALSE(opened);
  EXPECT_EQ(check(checks, "systemd").level, CheckLevel::kOk);
}

}  // namespace
}  // namespace glarecam::daemon
