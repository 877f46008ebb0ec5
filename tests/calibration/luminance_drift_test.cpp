// The drift check of K on the simulated luminance target (capture/sim/calibration_targets.h):
// against a calibration with the true K, flat field and noise model, a meter reading of the true
// luminance gives no drift and one 6 % high a 6 % drift beyond twice its uncertainty; the CSV log
// gets its header once and a line a check; bad inputs are refused with one line.
#include "calibration/luminance_drift.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <sstream>

#include "capture/sim/calibration_targets.h"
#include "core/image_io.h"
#include "support/test_support.h"

namespace glarecam {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// The meter's ±2 % read as a rectangular distribution: the check's budget with one reading (the
// patch is uniform and its mean's noise ~0.01 %: calibration_procedures_test.cpp).
const double kMeterU = 0.02 / std::sqrt(3.0);

class LuminanceDrift : public ::testing::Test {
 protected:
  // The luminance target, and a calibration with its true K (u(K) 1 %), flat field and noise.
  static void SetUpTestSuite() {
    dir_ = std::make_unique<testing::TempDir>();
    capture::CalibrationTargetOptions options;
    options.target = capture::CalibrationTarget::kLuminance;
    auto stacks = capture::simulateCalibrationTarget(options);
    ASSERT_TRUE(stacks) << stacks.error().message;
    truth_ = stacks->front().truth;
    auto written =
        capture::writeCalibrationTargetStacks(dir_->path() / "field", options.target, *stacks);
    ASSERT_TRUE(written) << written.error().message;
    stack_ = written->front().string();
    fs::create_directories(dir_->path() / "rig");
    ASSERT_TRUE(writeExr(
        dir_->path() / "rig" / "flat.exr",
        capture::naturalVignetting(options.width, options.height, options.horizontal_fov_deg)));
    calibration_ = (dir_->path() / "rig" / "calibration.json").string();
    writeCalibration(calibration_, {{"luminance_factor", options.luminance_factor},
                                    {"luminance_factor_u", 0.01 * options.luminance_factor}});
  }
  static void TearDownTestSuite() { dir_.reset(); }

  static void writeCalibration(const std::string& path, const json& extra) {
    json document = {{"schema", "glarecam.calibration/1"},
                     {"camera", {{"serial", "SIM-0001"}}},
                     {"black_level_dn", 64},
                     {"saturation_dn", 4000},
                     {"reference_f_number", 8},
                     {"noise", {{"read_noise_dn", 2}, {"dn_per_electron", 0.5}}},
                     {"flat_field", "flat.exr"}};
    document.update(extra);
    testing::writeText(path, document.dump());
  }

  static calibration::DriftCheckOptions options(double reading_cd_m2) {
    const json& r = truth_["roi"];
    calibration::DriftCheckOptions options;
    options.stacks = {stack_};
    options.calibrations = {calibration_};
    options.roi =
        calibration::Roi{r[0].get<int>(), r[1].get<int>(), r[2].get<int>(), r[3].get<int>()};
    options.reference.readings_cd_m2 = {reading_cd_m2};
    return options;
  }

  static double trueReference() { return truth_["reference_cd_m2"].get<double>(); }

  static inline std::unique_ptr<testing::TempDir> dir_;
  static inline json truth_;
  static inline std::string stack_, calibration_;
};

TEST_F(LuminanceDrift, TheTrueKHasNoDrift) {
  const auto report = calibration::checkLuminanceDrift(options(trueReference()));
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_EQ(report->luminance_factor, 1500);
  // K is recovered to 0.3 % (calibration_procedures_test.cpp): so is the drift.
  EXPECT_NEAR(report->measured_luminance_factor, 1500, 4.5);
  EXPECT_NEAR(report->drift, 0, 0.003);
  // Its uncertainty: the meter's and the calibration's 1 % in quadrature.
  EXPECT_NEAR(report->drift_u, std::hypot(kMeterU, 0.01), 0.0005);
  EXPECT_FALSE(report->exceedsTwiceUncertainty());
  EXPECT_TRUE(report->verdict());
  EXPECT_EQ(report->stacks, std::vector<std::string>{stack_});
  EXPECT_EQ(report->captured_at, "2026-06-21T10:00:00Z");
}

TEST_F(LuminanceDrift, AReadingSixPercentHighIsASignificantDrift) {
  const auto report = calibration::checkLuminanceDrift(options(1.06 * trueReference()));
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_NEAR(report->drift, 0.06, 0.004);
  EXPECT_TRUE(report->exceedsTwiceUncertainty());
  const Status verdict = report->verdict();
  ASSERT_FALSE(verdict);
  EXPECT_NE(verdict.error().code, ErrorCode::kBadInput);  // a finding: exit 1, not 2
  EXPECT_NE(verdict.error().message.find("recalibrate K"), std::string::npos);
  const json document = report->toJson();
  EXPECT_EQ(document["drift"], report->drift);
  EXPECT_EQ(document["measured_luminance_factor"], report->measured_luminance_factor);
  EXPECT_EQ(document["stacks"], json::array({stack_}));
}

TEST_F(LuminanceDrift, WithoutTheCalibrationsUncertaintyOnlyTheChecksCounts) {
  const std::string bare = (dir_->path() / "rig" / "no-u.json").string();
  writeCalibration(bare, {{"luminance_factor", 1500}});
  calibration::DriftCheckOptions check = options(trueReference());
  check.calibrations = {bare};
  const auto report = calibration::checkLuminanceDrift(check);
  ASSERT_TRUE(report) << report.error().message;
  EXPECT_NEAR(report->drift_u, kMeterU, 0.0005);
}

TEST_F(LuminanceDrift, TheLogGetsAHeaderOnceAndALineACheck) {
  calibration::DriftCheckOptions check = options(trueReference());
  check.log = dir_->path() / "rig" / "drift.csv";
  const auto first = calibration::checkLuminanceDrift(check);
  ASSERT_TRUE(first) << first.error().message;
  check.reference.readings_cd_m2 = {1.06 * trueReference()};
  const auto second = calibration::checkLuminanceDrift(check);
  ASSERT_TRUE(second) << second.error().message;

  std::istringstream log(testing::readText(*check.log));
  std::string header, line1, line2, extra;
  std::getline(log, header);
  std::getline(log, line1);
  std::getline(log, line2);
  EXPECT_FALSE(std::getline(log, extra));
  EXPECT_EQ(header + "\n", calibration::kDriftLogHeader);
  EXPECT_EQ(line1 + "\n", first->logLine());
  EXPECT_EQ(line2 + "\n", second->logLine());
  EXPECT_EQ(line1.rfind("2026-06-21T10:00:00Z," + stack_ + ",1500,", 0), 0u) << line1;
}

TEST(DriftReport, TheLogLineHasTheCheckInFixedPrecision) {
  const calibration::DriftReport report{.stacks = {"field/a", "field/b"},
                                        .captured_at = "2026-07-01T12:00:00Z",
                                        .luminance_factor = 1500,
                                        .measured_luminance_factor = 1590.123456789,
                                        .drift = 0.0600823045,
                                        .drift_u = 0.0152753};
  EXPECT_EQ(report.logLine(), "2026-07-01T12:00:00Z,field/a,1500,1590.1235,0.060082,0.015275\n");
  EXPECT_TRUE(report.exceedsTwiceUncertainty());
  calibration::DriftReport within = report;
  within.drift = -0.03;
  EXPECT_FALSE(within.exceedsTwiceUncertainty());
}

// ---- bad inputs -------------------------------------------------------------------------------

void expectBadInput(const Result<calibration::DriftReport>& report, const std::string& part) {
  ASSERT_FALSE(report);
  EXPECT_EQ(report.error().code, ErrorCode::kBadInput) << report.error().message;
  EXPECT_EQ(report.error().message.find('\n'), std::string::npos) << report.error().message;
  EXPECT_NE(report.error().message.find(part), std::string::npos) << report.error().message;
}

TEST_F(LuminanceDrift, MissingOptionsAreNamed) {
  calibration::DriftCheckOptions check = options(trueReference());
  check.calibrations.clear();
  expectBadInput(calibration::checkLuminanceDrift(check),
                 "give the calibration to check with --calibration");
  check = options(trueReference());
  check.stacks.clear();
  expectBadInput(calibration::checkLuminanceDrift(check),
                 "give the recorded field stack(s) to check");
  check = options(trueReference());
  check.roi.reset();
  expectBadInput(calibration::checkLuminanceDrift(check),
                 "give the reference patch's region with --roi");
  check = options(-1);
  expectBadInput(calibration::checkLuminanceDrift(check), "--reference -1 must be a positive");
}

TEST_F(LuminanceDrift, BadFilesAreNamed) {
  calibration::DriftCheckOptions check = options(trueReference());
  check.stacks = {(dir_->path() / "no-stack").string()};
  expectBadInput(calibration::checkLuminanceDrift(check), (dir_->path() / "no-stack").string());

  const std::string broken = (dir_->path() / "rig" / "broken.json").string();
  testing::writeText(broken, "{\"schema\": \"glarecam.calibration/1\", \"luminance_factor\": ");
  check = options(trueReference());
  check.calibrations = {broken};
  expectBadInput(calibration::checkLuminanceDrift(check), broken + ": invalid JSON");

  const std::string no_k = (dir_->path() / "rig" / "no-k.json").string();
  writeCalibration(no_k, json::object());
  check.calibrations = {no_k};
  check.log = dir_->path() / "rig" / "never.csv";
  expectBadInput(calibration::checkLuminanceDrift(check),
                 "the calibration has no luminance_factor");
  EXPECT_FALSE(fs::exists(*check.log));

  // A K of zero would divide the drift by zero, a negative one flip its sign.
  const std::string zero_k = (dir_->path() / "rig" / "zero-k.json").string();
  writeCalibration(zero_k, {{"luminance_factor", 0}});
  check.calibrations = {zero_k};
  expectBadInput(calibration::checkLuminanceDrift(check),
                 "the calibration's luminance_factor 0 must be a positive finite number");
  const std::string negative_u = (dir_->path() / "rig" / "negative-u.json").string();
  writeCalibration(negative_u, {{"luminance_factor", 1500}, {"luminance_factor_u", -1}});
  check.calibrations = {negative_u};
  expectBadInput(calibration::checkLuminanceDrift(check),
                 "the calibration's luminance_factor_u -1 must be a non-negative");
  EXPECT_FALSE(fs::exists(*check.log));
}

}  // namespace
}  // namespace glarecam
