// The values a procedure builds on: read from the --calibration files (later ones win, paths made
// absolute) or the first stack's own block, typed (absent or non-numeric values unknown), and
// turned into the levels and the merge's calibration, with errors naming the file or procedure.
#include "calibration/prior_calibration.h"

#include <gtest/gtest.h>

#include "capture/sim/calibration_targets.h"
#include "support/test_support.h"

namespace glarecam {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

TEST(PriorCalibration, KnowsTheNumbersItFinds) {
  const auto prior = calibration::priorCalibrationOf({{"black_level_dn", 64},
                                                      {"saturation_dn", "high"},
                                                      {"intrinsics", {{"cx", 100}, {"cy", "x"}}},
                                                      {"reference_f_number", 8},
                                                      {"luminance_factor", 1500},
                                                      {"flat_field", "/rig/flat.exr"},
                                                      {"linearity", {{"points", 20}}}});
  EXPECT_EQ(prior.black_level_dn, 64);
  EXPECT_FALSE(prior.saturation_dn);  // not a number: unknown
  EXPECT_EQ(prior.principal_x_px, 100);
  EXPECT_FALSE(prior.principal_y_px);
  EXPECT_EQ(prior.reference_f_number, 8);
  EXPECT_EQ(prior.luminance_factor, 1500);
  EXPECT_FALSE(prior.luminance_factor_u);
  EXPECT_EQ(prior.flat_field, fs::path("/rig/flat.exr"));
  EXPECT_EQ(prior.source["linearity"]["points"], 20);  // everything kept for the merge's block

  const auto empty = calibration::priorCalibrationOf(json::object());
  EXPECT_FALSE(empty.black_level_dn || empty.principal_x_px || empty.flat_field);
}

TEST(PriorCalibration, LaterFilesWinAndPathsBecomeAbsolute) {
  testing::TempDir dir;
  fs::create_directories(dir.path() / "parts");
  testing::writeText(dir.path() / "parts" / "flat.json",
                     R"({"schema": "glarecam.calibration/1", "black_level_dn": 60,)"
                     R"( "flat_field": "flat-flat.exr"})");
  // A bare calibration block is accepted as well.
  testing::writeText(dir.path() / "dark.json",
                     R"({"black_level_dn": 64, "saturation_dn": 4000, "luminance_factor": 1,)"
                     R"( "intrinsics": {"fx": 400, "fy": 400, "cx": 150, "cy": 120}})");
  const std::vector<std::string> files = {(dir.path() / "parts" / "flat.json").string(),
                                          (dir.path() / "dark.json").string()};
  const auto prior = calibration::readPriorCalibration(files, {});
  ASSERT_TRUE(prior) << prior.error().message;
  EXPECT_EQ(prior->black_level_dn, 64);
  EXPECT_EQ(prior->saturation_dn, 4000);
  EXPECT_EQ(prior->principal_x_px, 150);
  EXPECT_EQ(prior->flat_field, fs::absolute(dir.path() / "parts" / "flat-flat.exr"));
  EXPECT_EQ(prior->source["flat_field"], prior->flat_field->string());

  const std::vector<std::string> missing = {(dir.path() / "none.json").string()};
  const auto refused = calibration::readPriorCalibration(missing, {});
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::kBadInput);
  EXPECT_NE(refused.error().message.find((dir.path() / "none.json").string()), std::string::npos)
      << refused.error().message;
}

TEST(PriorCalibration, WithoutFilesTheFirstStacksOwnBlock) {
  testing::TempDir dir;
  capture::CalibrationTargetOptions options;
  options.target = capture::CalibrationTarget::kDark;
  auto stacks = capture::simulateCalibrationTarget(options);
  ASSERT_TRUE(stacks) << stacks.error().message;
  auto bare = capture::writeCalibrationTargetStacks(dir.path() / "bare", options.target, *stacks);
  ASSERT_TRUE(bare) << bare.error().message;
  Calibration block;
  block.black_level_dn = 62;
  block.saturation_dn = 4000;
  block.luminance_factor = 1500;
  block.reference_f_number = 8;  // the frames state theirs
  block.intrinsics = {.fx = 400, .fy = 400, .cx = 160, .cy = 128, .distortion = {}};
  stacks->front().manifest.calibration = block;
  auto calibrated =
      capture::writeCalibrationTargetStacks(dir.path() / "calibrated", options.target, *stacks);
  ASSERT_TRUE(calibrated) << calibrated.error().message;

  const std::vector<std::string> paths = {calibrated->front().string(), bare->front().string()};
  auto inputs = calibration::readCalibrationInputs(paths, false);
  ASSERT_TRUE(inputs) << inputs.error().message;
  const auto prior = calibration::readPriorCalibration({}, *inputs);
  ASSERT_TRUE(prior) << prior.error().message;
  EXPECT_EQ(prior->black_level_dn, 62);
  EXPECT_EQ(prior->principal_x_px, 160);

  const std::vector<std::string> reversed = {paths[1], paths[0]};
  inputs = calibration::readCalibrationInputs(reversed, false);
  ASSERT_TRUE(inputs) << inputs.error().message;
  const auto none = calibration::readPriorCalibration({}, *inputs);
  ASSERT_TRUE(none) << none.error().message;
  EXPECT_FALSE(none->black_level_dn);
}

TEST(PriorCalibration, LevelsFallBackToThePixelFormatsRange) {
  calibration::CalibrationInputs inputs;
  inputs.camera.pixel_format = "Mono12";
  const auto mono12 = calibration::sensorLevels(
      calibration::priorCalibrationOf({{"black_level_dn", 64}}), inputs, "noise");
  ASSERT_TRUE(mono12) << mono12.error().message;
  EXPECT_EQ(mono12->black_level_dn, 64);
  EXPECT_EQ(mono12->saturation_dn, 4095);
  // An unknown format: the deepest file's range.
  inputs.camera.pixel_format.clear();
  inputs.frames.push_back(
      {.frame = RawFrame(2, 2), .spec = {}, .name = "a", .bit_depth = 8, .stack = 0});
  inputs.frames.push_back(
      {.frame = RawFrame(2, 2), .spec = {}, .name = "b", .bit_depth = 16, .stack = 0});
  const auto sixteen = calibration::sensorLevels(
      calibration::priorCalibrationOf({{"black_level_dn", 64}}), inputs, "noise");
  ASSERT_TRUE(sixteen) << sixteen.error().message;
  EXPECT_EQ(sixteen->saturation_dn, 65535);

  const auto unknown =
      calibration::sensorLevels(calibration::priorCalibrationOf(json::object()), inputs, "flat");
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().message,
            "calibrate flat: the black level is unknown: measure it first (glarecam calibrate "
            "dark) and give that file with --calibration");
  const auto above = calibration::sensorLevels(
      calibration::priorCalibrationOf({{"black_level_dn", 5000}, {"saturation_dn", 4000}}), inputs,
      "linearity");
  ASSERT_FALSE(above);
  EXPECT_EQ(above.error().message,
            "calibrate linearity: black level 5000 DN must be in [0, saturation 4000)");
}

TEST(PriorCalibration, TheMergesCalibrationTakesTheLevelsNoiseAndFlatField) {
  const auto prior =
      calibration::priorCalibrationOf({{"black_level_dn", 60},
                                       {"reference_f_number", 5.6},
                                       {"noise", {{"read_noise_dn", 2}, {"dn_per_electron", 0.5}}},
                                       {"flat_field", "/rig/flat-flat.exr"}});
  const auto merge =
      calibration::mergeCalibration(prior, {.black_level_dn = 64, .saturation_dn = 4000});
  ASSERT_TRUE(merge) << merge.error().message;
  EXPECT_EQ(merge->black_level_dn, 64);
  EXPECT_EQ(merge->saturation_dn, 4000);
  EXPECT_EQ(merge->reference_f_number, 5.6);
  ASSERT_TRUE(merge->noise);
  EXPECT_EQ(merge->noise->dn_per_electron, 0.5);
  EXPECT_EQ(merge->flat_field, "/rig/flat-flat.exr");

  const auto bad = calibration::mergeCalibration(
      calibration::priorCalibrationOf({{"noise", {{"read_noise_dn", 2}, {"dn_per_electron", -1}}}}),
      {.black_level_dn = 64, .saturation_dn = 4000});
  ASSERT_FALSE(bad);
  EXPECT_EQ(bad.error().code, ErrorCode::kBadInput);
  EXPECT_NE(bad.error().message.find("--calibration"), std::string::npos) << bad.error().message;
  EXPECT_NE(bad.error().message.find("dn_per_electron"), std::string::npos) << bad.error().message;
}

}  // namespace
}  // namespace glarecam
