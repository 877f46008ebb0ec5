// Each calibration part end to end, from the simulated targets' stacks on disk (ground truth:
// capture/sim/calibration_targets.h) to its glarecam.calibration/1 file: what it measured, the
// images beside it, the provenance, the earlier parts it builds on; the merge of the parts; and
// bad inputs refused with one line naming the file or option and the problem.
#include "calibration/calibration_parts.h"

#include <gtest/gtest.h>

#include <map>
#include <memory>

#include "capture/sim/calibration_targets.h"
#include "core/image_io.h"
#include "support/test_support.h"

namespace glarecam {
namespace {

namespace fs = std::filesystem;
using calibration::PartInputs;
using capture::CalibrationTarget;
using json = nlohmann::json;

constexpr const char* kCapturedAt = "2026-06-21T10:00:00Z";  // the targets' captured_at

// The error is bad input, one line, and says each of `parts`.
void expectBadInput(const Error& error, std::initializer_list<std::string> parts) {
  EXPECT_EQ(error.code, ErrorCode::kBadInput) << error.message;
  EXPECT_EQ(error.message.find('\n'), std::string::npos) << error.message;
  for (const std::string& part : parts)
    EXPECT_NE(error.message.find(part), std::string::npos) << error.message << "\nlacks: " << part;
}

class CalibrationParts : public ::testing::Test {
 protected:
  // The targets (dark, linearity, noise, flat, luminance, and a board in 4 poses) and the dark
  // and linearity parts the others build on, each made on first use and kept for the process:
  // CTest runs every test in a process of its own, and simulating all six targets for each took
  // most of this suite's time under AddressSanitizer.
  static void SetUpTestSuite() { dir_ = std::make_unique<testing::TempDir>(); }
  static void TearDownTestSuite() {
    dir_.reset();
    stacks_.clear();
    truth_.clear();
  }

  static fs::path partFile(const std::string& name) {
    return dir_->path() / "cal" / (name + ".json");
  }

  // The target's stacks on disk, simulated and written on first use.
  static const std::vector<std::string>& stacks(CalibrationTarget target) {
    if (stacks_.contains(target)) return stacks_[target];
    std::vector<std::string>& paths = stacks_[target];
    capture::CalibrationTargetOptions options;
    options.target = target;
    if (target == CalibrationTarget::kBoard) {
      options.width = 640;
      options.height = 480;
      options.board_views = 4;
    }
    auto simulated = capture::simulateCalibrationTarget(options);
    if (!simulated) {
      ADD_FAILURE() << simulated.error().message;
      return paths;
    }
    auto written =
        capture::writeCalibrationTargetStacks(dir_->path() / "targets", target, *simulated);
    if (!written) {
      ADD_FAILURE() << written.error().message;
      return paths;
    }
    for (const fs::path& path : *written) paths.push_back(path.string());
    truth_[target] = simulated->front().truth;
    return paths;
  }

  // cal/<name>.json; the dark and linearity parts are calibrated on first use.
  static fs::path part(const std::string& name) {
    const fs::path file = partFile(name);
    if (fs::exists(file)) return file;
    if (name == "dark") {
      auto dark =
          calibration::calibrateDarkPart({.inputs = inputs(CalibrationTarget::kDark, "dark")});
      if (!dark) ADD_FAILURE() << dark.error().message;
    } else if (name == "linearity") {
      auto linearity = calibration::calibrateLinearityPart(
          {.inputs = inputs(CalibrationTarget::kLinearity, "linearity", {"dark"})});
      if (!linearity) ADD_FAILURE() << linearity.error().message;
    }
    return file;
  }

  // The target's stacks, building on the named parts, written to cal/<out>.json.
  static PartInputs inputs(CalibrationTarget target, const std::string& out,
                           std::initializer_list<std::string> priors = {}) {
    PartInputs inputs{.stacks = stacks(target), .calibrations = {}, .out = partFile(out)};
    for (const std::string& prior : priors) inputs.calibrations.push_back(part(prior).string());
    return inputs;
  }

  static const json& truth(CalibrationTarget target) {
    stacks(target);
    return truth_[target];
  }

  static inline std::unique_ptr<testing::TempDir> dir_;
  static inline std::map<CalibrationTarget, std::vector<std::string>> stacks_;
  static inline std::map<CalibrationTarget, json> truth_;
};

TEST_F(CalibrationParts, DarkWritesTheBlackLevelItsImagesAndTheProvenance) {
  const auto part =
      calibration::calibrateDarkPart({.inputs = inputs(CalibrationTarget::kDark, "rig/dark")});
  ASSERT_TRUE(part) << part.error().message;
  // Tolerances: calibration_procedures_test.cpp.
  EXPECT_NEAR(part->measured.black_level_dn,
              truth(CalibrationTarget::kDark)["black_level_dn"].get<double>(), 0.05);
  EXPECT_EQ(part->measured.hot_pixel_count, truth(CalibrationTarget::kDark)["hot_pixels"].size());

  const calibration::PartReport& report = part->report;
  EXPECT_EQ(report.part, "dark");
  EXPECT_EQ(report.file, partFile("rig/dark"));
  EXPECT_NE(report.method.find("dark frames at 2 exposures"), std::string::npos) << report.method;
  EXPECT_TRUE(report.warnings.empty());
  // The file holds what the report says, with the stacks and their time as provenance.
  const auto read = calibration::readCalibrationDocument(report.file);
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(calibration::toJson(*read), calibration::toJson(report.document));
  EXPECT_EQ(read->values["black_level_dn"], part->measured.black_level_dn);
  EXPECT_EQ(read->camera.serial, "SIM-0001");
  ASSERT_TRUE(read->parts.contains("dark"));
  EXPECT_EQ(read->parts.at("dark").measured_at, kCapturedAt);
  EXPECT_EQ(read->parts.at("dark").inputs, stacks(CalibrationTarget::kDark));
  // Its images beside it, named in its values: the hot-pixel map marks exactly the hot pixels.
  EXPECT_EQ(read->values["dark_frame"], "dark-dark.exr");
  EXPECT_TRUE(fs::exists(partFile("rig/dark").parent_path() / "dark-dark.exr"));
  const auto hot = readRawFrame(partFile("rig/dark").parent_path() / "dark-hot-pixels.png");
  ASSERT_TRUE(hot) << hot.error().message;
  std::size_t marked = 0;
  for (std::size_t i = 0; i < hot->pixels.pixelCount(); ++i) marked += hot->pixels.data()[i] == 255;
  EXPECT_EQ(marked, part->measured.hot_pixel_count);
}

TEST_F(CalibrationParts, LinearityAndNoiseBuildOnTheDarkPart) {
  const auto linearity = calibration::calibrateLinearityPart(
      {.inputs = inputs(CalibrationTarget::kLinearity, "linearity-2", {"dark"})});
  ASSERT_TRUE(linearity) << linearity.error().message;
  EXPECT_NEAR(linearity->measured.saturation_dn,
              truth(CalibrationTarget::kLinearity)["saturation_dn"].get<double>(), 20);
  EXPECT_TRUE(linearity->report.warnings.empty());

  // Read noise (2 DN, 2.02 with quantisation) and gain (0.5 DN/e-) to 3 %, as the CLI chain.
  const auto noise = calibration::calibrateNoisePart(
      {.inputs = inputs(CalibrationTarget::kNoise, "noise", {"dark", "linearity"})});
  ASSERT_TRUE(noise) << noise.error().message;
  EXPECT_NEAR(noise->measured.model.read_noise_dn, 2.02, 0.06);
  EXPECT_NEAR(noise->measured.model.dn_per_electron, 0.5, 0.015);
  EXPECT_EQ(noise->report.document.values["noise"]["dn_per_electron"],
            noise->measured.model.dn_per_electron);
}

TEST_F(CalibrationParts, ARampThatNeverBendsWarnsThatSaturationIsABound) {
  // At a 60 % tolerance the simulated bend (1 % at ~3630 DN) is never reached.
  auto options = calibration::LinearityPartOptions{
      .inputs = inputs(CalibrationTarget::kLinearity, "linearity-loose", {"dark"}),
      .roi = std::nullopt,
      .tolerance_percent = 60};
  const auto part = calibration::calibrateLinearityPart(options);
  ASSERT_TRUE(part) << part.error().message;
  EXPECT_FALSE(part->measured.bend_found);
  ASSERT_EQ(part->report.warnings.size(), 1u);
  EXPECT_NE(part->report.warnings[0].find("is a lower bound"), std::string::npos);
}

TEST_F(CalibrationParts, FlatIsNormalisedAtTheKnownPrincipalPoint) {
  const auto centred = calibration::calibrateFlatPart(
      {.inputs = inputs(CalibrationTarget::kFlat, "flat", {"dark", "linearity"})});
  ASSERT_TRUE(centred) << centred.error().message;
  // cos⁴ of the corner's field angle at 40° across 320x256 is 0.675 (the CLI chain's bound).
  EXPECT_NEAR(centred->measured.min_value, 0.665, 0.02);
  EXPECT_EQ(centred->measured.principal_x, 159.5);
  EXPECT_EQ(centred->measured.principal_y, 127.5);
  EXPECT_TRUE(fs::exists(partFile("flat").parent_path() / "flat-flat.exr"));

  // An earlier intrinsics part moves the point the field is 1 at.
  testing::writeText(partFile("intrinsics"),
                     R"({"schema": "glarecam.calibration/1", "intrinsics": )"
                     R"({"fx": 400, "fy": 400, "cx": 100, "cy": 90}})");
  const auto moved =
      calibration::calibrateFlatPart({.inputs = inputs(CalibrationTarget::kFlat, "flat-moved",
                                                       {"dark", "linearity", "intrinsics"})});
  ASSERT_TRUE(moved) << moved.error().message;
  EXPECT_EQ(moved->measured.principal_x, 100);
  EXPECT_EQ(moved->measured.principal_y, 90);
  EXPECT_NEAR(calibration::windowMean(moved->measured.flat_field, 100, 90,
                                      calibration::kFlatNormalisationWindowPx),
              1.0, 1e-6);
}

TEST_F(CalibrationParts, LuminanceRecoversKWithTheEarlierParts) {
  ASSERT_TRUE(calibration::calibrateNoisePart(
      {.inputs = inputs(CalibrationTarget::kNoise, "noise-k", {"dark", "linearity"})}));
  ASSERT_TRUE(calibration::calibrateFlatPart(
      {.inputs = inputs(CalibrationTarget::kFlat, "flat-k", {"dark", "linearity"})}));
  const json& truth = this->truth(CalibrationTarget::kLuminance);
  const double reference = truth["reference_cd_m2"].get<double>();
  const auto& r = truth["roi"];
  calibration::LuminancePartOptions options{
      .inputs = inputs(CalibrationTarget::kLuminance, "luminance",
                       {"dark", "linearity", "noise-k", "flat-k"}),
      .roi = calibration::Roi{r[0].get<int>(), r[1].get<int>(), r[2].get<int>(), r[3].get<int>()},
      .reference = {.readings_cd_m2 = {reference - 10, reference + 10}}};
  const auto part = calibration::calibrateLuminancePart(options);
  ASSERT_TRUE(part) << part.error().message;
  // K = 1500 to 0.5 % with the measured flat and noise; u(K) ~1.2 % from the ±2 % meter.
  EXPECT_NEAR(part->measured.luminance_factor, truth["luminance_factor"].get<double>(), 7.5);
  EXPECT_NEAR(part->measured.luminance_factor_u, 17.5, 2);
  const json& values = part->report.document.values;
  EXPECT_EQ(values["luminance_factor"], part->measured.luminance_factor);
  EXPECT_EQ(values["reference_f_number"], 8);  // the frames' own: no earlier part states one
  EXPECT_NE(part->report.method.find("(2 meter reading(s), ±2 %)"), std::string::npos)
      << part->report.method;
}

TEST_F(CalibrationParts, IntrinsicsTakesOneViewAStack) {
  calibration::IntrinsicsPartOptions options{
      .inputs = inputs(CalibrationTarget::kBoard, "intrinsics-board"),
      .board = {.inner_columns = 9, .inner_rows = 6, .square_mm = 30},
      .fit_k3 = false};
  const auto part = calibration::calibrateIntrinsicsPart(options);
  ASSERT_TRUE(part) << part.error().message;
  // Each stack's best exposed frame, named by its stack.
  const std::vector<std::string>& board = stacks(CalibrationTarget::kBoard);
  ASSERT_EQ(part->measured.views_used.size(), board.size());
  for (std::size_t i = 0; i < board.size(); ++i)
    EXPECT_EQ(part->measured.views_used[i].rfind(board[i] + "/", 0), 0u)
        << part->measured.views_used[i];
  // Four poses fix the focal length to about 1 %.
  const double fx = truth(CalibrationTarget::kBoard)["intrinsics"]["fx"].get<double>();
  EXPECT_NEAR(part->measured.intrinsics.fx / fx, 1.0, 0.02);
  EXPECT_EQ(part->report.document.values["intrinsics"]["fx"], part->measured.intrinsics.fx);
}

TEST_F(CalibrationParts, MergeCombinesThePartsAndCopiesTheirImages) {
  const fs::path out = dir_->path() / "rig1" / "calibration.json";
  const auto merged =
      calibration::mergeCalibrationParts({.files = {part("dark"), part("linearity")}, .out = out});
  ASSERT_TRUE(merged) << merged.error().message;
  EXPECT_EQ(merged->file, out);
  EXPECT_EQ(merged->document.parts.size(), 2u);
  EXPECT_EQ(merged->document.values["dark_frame"], "dark-dark.exr");
  EXPECT_TRUE(fs::exists(out.parent_path() / "dark-dark.exr"));
  EXPECT_TRUE(fs::exists(out.parent_path() / "dark-hot-pixels.png"));
  // Two parts do not make a calibration a stack accepts: the warning names what is missing.
  ASSERT_EQ(merged->warnings.size(), 1u);
  EXPECT_NE(merged->warnings[0].find("no luminance_factor (calibrate luminance)"),
            std::string::npos)
      << merged->warnings[0];
  const auto read = calibration::readCalibrationDocument(out);
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(calibration::toJson(*read), calibration::toJson(merged->document));
}

// ---- bad inputs -------------------------------------------------------------------------------

TEST_F(CalibrationParts, OptionsAreCheckedBeforeAnythingIsRead) {
  const PartInputs nowhere{.stacks = {"/nonexistent/stack"}, .calibrations = {}, .out = ""};
  const auto no_out = calibration::calibrateDarkPart({.inputs = nowhere});
  ASSERT_FALSE(no_out);
  expectBadInput(no_out.error(), {"--out FILE is required"});

  PartInputs directory = nowhere;
  directory.out = "rig1/";
  const auto not_a_file = calibration::calibrateFlatPart({.inputs = directory});
  ASSERT_FALSE(not_a_file);
  expectBadInput(not_a_file.error(), {"--out rig1/: expected a file name"});

  PartInputs valid = nowhere;
  valid.out = partFile("x");
  const auto tolerance = calibration::calibrateLinearityPart(
      {.inputs = valid, .roi = std::nullopt, .tolerance_percent = 100});
  ASSERT_FALSE(tolerance);
  expectBadInput(tolerance.error(), {"tolerance 1 must be in (0, 1)"});
  const auto reference = calibration::calibrateLuminancePart(
      {.inputs = valid, .roi = std::nullopt, .reference = {.readings_cd_m2 = {-5}}});
  ASSERT_FALSE(reference);
  expectBadInput(reference.error(), {"--reference -5 must be a positive luminance"});
  const auto board = calibration::calibrateIntrinsicsPart(
      {.inputs = valid, .board = {.inner_columns = 6, .inner_rows = 6, .square_mm = 25}});
  ASSERT_FALSE(board);
  expectBadInput(board.error(), {"board 6x6", "square board"});
}

TEST_F(CalibrationParts, BadStacksAndEarlierPartsNameTheFile) {
  PartInputs missing = inputs(CalibrationTarget::kDark, "x");
  missing.stacks = {(dir_->path() / "nothing").string()};
  const auto no_stack = calibration::calibrateDarkPart({.inputs = missing});
  ASSERT_FALSE(no_stack);
  expectBadInput(no_stack.error(), {(dir_->path() / "nothing").string()});

  // The board's frames are 640x480, the noise target's 320x256: both named.
  PartInputs mixed = inputs(CalibrationTarget::kNoise, "x", {"dark"});
  mixed.stacks.push_back(stacks(CalibrationTarget::kBoard).front());
  const auto sizes = calibration::calibrateNoisePart({.inputs = mixed});
  ASSERT_FALSE(sizes);
  expectBadInput(sizes.error(), {stacks(CalibrationTarget::kBoard).front(), "640x480",
                                 stacks(CalibrationTarget::kNoise).front(), "320x256"});

  const auto no_black =
      calibration::calibrateFlatPart({.inputs = inputs(CalibrationTarget::kFlat, "x")});
  ASSERT_FALSE(no_black);
  expectBadInput(no_black.error(),
                 {"calibrate flat: the black level is unknown", "glarecam calibrate dark"});

  testing::writeText(partFile("broken"), "{\"schema\": \"glarecam.calibration/1\",\n");
  const auto broken =
      calibration::calibrateFlatPart({.inputs = inputs(CalibrationTarget::kFlat, "x", {"broken"})});
  ASSERT_FALSE(broken);
  expectBadInput(broken.error(), {partFile("broken").string(), "invalid JSON"});

  const auto lit =
      calibration::calibrateDarkPart({.inputs = inputs(CalibrationTarget::kFlat, "x")});
  ASSERT_FALSE(lit);
  expectBadInput(lit.error(), {"frame-00.png: not a dark frame"});
  EXPECT_FALSE(fs::exists(partFile("x"))) << "nothing written for a failed part";
}

TEST_F(CalibrationParts, MergeRefusesTooFewFilesAndAnotherCamera) {
  const auto one = calibration::mergeCalibrationParts(
      {.files = {part("dark")}, .out = dir_->path() / "merged.json"});
  ASSERT_FALSE(one);
  expectBadInput(one.error(), {"calibrate merge: give two or more files"});

  testing::writeText(partFile("other"),
                     R"({"schema": "glarecam.calibration/1", "camera": {"serial": "OTHER"}})");
  const auto other = calibration::mergeCalibrationParts(
      {.files = {part("dark"), partFile("other")}, .out = dir_->path() / "merged.json"});
  ASSERT_FALSE(other);
  expectBadInput(other.error(), {partFile("other").string(), "camera serial \"OTHER\" differs"});
  EXPECT_FALSE(fs::exists(dir_->path() / "merged.json"));
}

}  // namespace
}  // namespace glarecam
