// `glarecam process`'s library call: every output and a result matching the simulated scene's
// truth, the limit and thresholds, saturated and 8-bit frames, outputs never mixed with an old
// result; and every stack under tests/data/bad-stacks/ refused with a kBadInput error: one line,
// naming a file of the stack, containing the case's expect.txt, and no output written. Also run
// under AddressSanitizer + UBSan (make test-asan), so "never a crash" is checked, not assumed.
#include "pipeline/process_stack.h"

#include <gtest/gtest.h>
#include <stdlib.h>  // setenv

#include <algorithm>
#include <cctype>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "calibration/calibration_parts.h"
#include "capture/sim/calibration_targets.h"
#include "core/image_io.h"
#include "core/sha256.h"
#include "pipeline/limit_curve.h"
#include "support/sim_support.h"

namespace glarecam::pipeline {
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

ProcessOptions quiet() {
  ProcessOptions options;
  options.show_progress = false;
  return options;
}

TEST(ProcessStack, WritesEveryOutputAndAResultMatchingTheTruth) {
  testing::TempDir dir;
  const auto simulated = testing::writeSmallStack(dir / "s", testing::smallScene(65.0));
  auto summary = processStack(dir / "s", quiet());
  ASSERT_TRUE(summary) << summary.error().message;
  const fs::path out = dir / "s" / "result";
  EXPECT_EQ(summary->output_directory, out);
  for (const char* name : {"luminance.exr", "quality.exr", "luminance.png", "result.json"}) {
    EXPECT_TRUE(fs::is_regular_file(out / name)) << name;
  }
  const json result = json::parse(testing::readText(out / "result.json"));
  EXPECT_EQ(result, toJson(summary->result));
  EXPECT_EQ(result["schema"], "glarecam.result/1");
  EXPECT_EQ(result["stack"], *simulated.manifest.id);
  EXPECT_EQ(result["alpha_deg"], 65.0);
  EXPECT_NEAR(result["limit"]["limit_cd_m2"].get<double>(), *glareLimitCdM2(65.0), 1e-6);
  // The fitted maximum averages ~1 % per-pixel noise over its window: 1 % is several sigma.
  EXPECT_NEAR(result["luminance"]["max_cd_m2"].get<double>() / simulated.truth.peak_cd_m2, 1.0,
              0.01);
  EXPECT_EQ(result["luminance"]["max_method"], "quadratic_fit");
  EXPECT_NEAR(result["luminance"]["max_pixel"][0].get<double>(), simulated.centre_pixel[0], 3.0);
  EXPECT_NEAR(result["luminance"]["max_pixel"][1].get<double>(), simulated.centre_pixel[1], 3.0);
  EXPECT_EQ(result["luminance"]["valid_fraction"], 1.0);
  EXPECT_EQ(result["luminance"]["saturated_pixels"], 0);
  EXPECT_EQ(result["glare"], true);

  auto luminance = readExr(out / "luminance.exr");
  ASSERT_TRUE(luminance) << luminance.error().message;
  EXPECT_TRUE(luminance->sameSize(simulated.frames[0].width(), simulated.frames[0].height()));
}

// The outputs at their price (docs/process.md, "Output encodings"): by default the luminance is
// float32 rounded to 24 bits (within a relative 2^-16 of --float32's lossless copy, far inside the
// 0.1 % the issue allows), the uncertainty half (2^-11 of itself), the counts and flags exact; the
// two EXRs are smaller than the float32 ones, and other tools read them (OpenCV, as
// docs/process.md shows).
TEST(ProcessStack, CompactOutputsKeepTheLuminanceAndOthersReadThem) {
  testing::TempDir dir;
  testing::writeSmallStack(dir / "s", testing::smallScene(65.0));
  ProcessOptions compact = quiet();
  compact.output_directory = dir / "compact";
  ProcessOptions full = quiet();
  full.output_directory = dir / "full";
  full.float32 = true;
  ASSERT_TRUE(processStack(dir / "s", compact));
  ASSERT_TRUE(processStack(dir / "s", full));

  const auto compare = [&](const char* file, const char* channel, double tolerance) {
    const FloatImage a = readExr(dir / "compact" / file, channel).value();
    const FloatImage b = readExr(dir / "full" / file, channel).value();
    ASSERT_TRUE(a.sameSize(b.width(), b.height()));
    double worst = 0;
    for (std::size_t i = 0; i < a.pixelCount(); ++i) {
      const float x = a.data()[i], y = b.data()[i];
      ASSERT_EQ(std::isnan(x), std::isnan(y)) << file << " " << channel << " pixel " << i;
      if (!std::isnan(y) && y != 0)
        worst = std::max(worst, std::abs(static_cast<double>(x) / y - 1));
    }
    EXPECT_LE(worst, tolerance) << file << " " << channel;
  };
  compare("luminance.exr", "Y", std::ldexp(1.0, -16));
  compare("quality.exr", "relative_uncertainty", std::ldexp(1.0, -11));
  compare("quality.exr", "valid_frames", 0);
  compare("quality.exr", "bound", 0);
  for (const char* file : {"luminance.exr", "quality.exr"})
    EXPECT_LT(fs::file_size(dir / "compact" / file), fs::file_size(dir / "full" / file)) << file;

  // OpenCV reads EXR once allowed to (off by default since 4.5.2): OpenEXR's PIZ and the ZIP
  // glarecam encodes itself (core/exr_zip.h) alike.
  ::setenv("OPENCV_IO_ENABLE_OPENEXR", "1", 1);
  for (const char* run : {"compact", "full"}) {
    const cv::Mat read = cv::imread((dir / run / "luminance.exr").string(), cv::IMREAD_UNCHANGED);
    ASSERT_FALSE(read.empty()) << run;
    ASSERT_EQ(read.type(), CV_32FC1);
    const FloatImage ours = readExr(dir / run / "luminance.exr").value();
    ASSERT_EQ(read.cols, ours.width());
    ASSERT_EQ(read.rows, ours.height());
    for (int y = 0; y < read.rows; y += 7)
      for (int x = 0; x < read.cols; x += 7) EXPECT_EQ(read.at<float>(y, x), ours.at(x, y)) << run;
  }
}

// The dark frame against the truth: one simulated sensor (sensor seed 3) with a 6 DN fixed
// pattern and 150 hot pixels takes a glare stack and, lens capped, the dark target; `calibrate
// dark` measures the dark frame and hot pixels, and `process` with them must come back to what
// the same scene gives on a clean sensor, while the black level alone cannot.
struct DarkRun {
  json result;
  FloatImage luminance;
  RawFrame bound;
};

DarkRun processWith(const fs::path& stack, const std::optional<fs::path>& calibration) {
  ProcessOptions options = quiet();
  options.calibration_file = calibration;
  auto summary = processStack(stack, options);
  EXPECT_TRUE(summary) << summary.error().message;
  if (!summary) return {};
  auto luminance = readExr(summary->output_directory / "luminance.exr");
  auto bound = readExr(summary->output_directory / "quality.exr", "bound");
  EXPECT_TRUE(luminance && bound);
  if (!luminance || !bound) return {};
  RawFrame flags(bound->width(), bound->height());
  for (std::size_t i = 0; i < flags.pixelCount(); ++i)
    flags.data()[i] = static_cast<std::uint16_t>(bound->data()[i]);
  return {toJson(summary->result), std::move(*luminance), std::move(flags)};
}

// The RMS of (L - truth) / truth over the pixels `keep` accepts.
template <typename Keep>
double relativeRms(const FloatImage& luminance, const FloatImage& truth, Keep keep) {
  double sum = 0;
  std::size_t count = 0;
  for (int y = 0; y < truth.height(); ++y) {
    for (int x = 0; x < truth.width(); ++x) {
      if (!keep(x, y)) continue;
      const double e = (luminance.at(x, y) - truth.at(x, y)) / truth.at(x, y);
      sum += e * e;
      ++count;
    }
  }
  return std::sqrt(sum / static_cast<double>(count));
}

TEST(ProcessStack, DarkFrameAndHotPixelsBringASensorsDefectsBackToTheTruth) {
  testing::TempDir dir;
  capture::SimulationOptions scene = testing::smallScene(40.0, 160, 128);
  scene.sensor_seed = 3;
  const auto clean = testing::writeSmallStack(dir / "clean", scene);
  scene.defects = {.fixed_pattern_dn = 6.0, .hot_pixels = 150};
  const auto defective = testing::writeSmallStack(dir / "defective", scene);
  const json truth = json::parse(testing::readText(dir / "defective" / "truth.json"));
  ASSERT_EQ(truth["hot_pixels"].size(), 150u);

  capture::CalibrationTargetOptions target;
  static_cast<capture::SimulatedCameraModel&>(target) = scene;  // the same camera and sensor
  target.target = capture::CalibrationTarget::kDark;
  target.seed = 9;  // its own noise
  target.fixed_pattern_dn = 6.0;
  target.hot_pixels = 150;
  auto targets = capture::simulateCalibrationTarget(target);
  ASSERT_TRUE(targets) << targets.error().message;
  ASSERT_EQ(targets->front().truth["hot_pixels"], truth["hot_pixels"]);  // one sensor
  auto written = capture::writeCalibrationTargetStacks(dir / "targets", target.target, *targets);
  ASSERT_TRUE(written) << written.error().message;
  auto dark = calibration::calibrateDarkPart({.inputs = {.stacks = {written->front().string()},
                                                         .calibrations = {},
                                                         .out = dir / "cal" / "dark.json"}});
  ASSERT_TRUE(dark) << dark.error().message;
  // The stack's own calibration with the dark part's frame, exposure, current and hot pixels.
  json block = json::parse(testing::readText(dir / "defective" / "stack.json"))["calibration"];
  const json part = json::parse(testing::readText(dir / "cal" / "dark.json"));
  for (const char* key :
       {"dark_frame", "dark_frame_exposure_us", "dark_current_dn_per_us", "hot_pixels"})
    block[key] = part.at(key);
  testing::writeText(dir / "cal" / "calibration.json", block.dump());

  const DarkRun ideal = processWith(dir / "clean", std::nullopt);
  const DarkRun plain = processWith(dir / "defective", std::nullopt);
  const DarkRun corrected = processWith(dir / "defective", dir / "cal" / "calibration.json");
  ASSERT_FALSE(ideal.luminance.empty() || plain.luminance.empty() || corrected.luminance.empty());
  EXPECT_EQ(corrected.result["calibration"]["black"], "dark_frame");
  EXPECT_EQ(corrected.result["calibration"]["hot_pixels_masked"], true);
  EXPECT_EQ(plain.result["calibration"]["black"], "black_level");

  // Every hot pixel the sensor has is masked, and nothing else.
  EXPECT_EQ(corrected.result["luminance"]["masked_pixels"], 150);
  std::set<std::pair<int, int>> hot;
  for (const json& p : truth["hot_pixels"]) hot.insert({p[0].get<int>(), p[1].get<int>()});
  for (const auto& [x, y] : hot)
    EXPECT_EQ(corrected.bound.at(x, y), std::uint16_t(calibration::PixelBound::kMasked))
        << x << "," << y;

  const FloatImage& t = defective.true_luminance_cd_m2;
  const auto normal = [&](int x, int y) { return !hot.contains({x, y}); };
  const auto hot_only = [&](int x, int y) { return hot.contains({x, y}); };
  const double ideal_rms = relativeRms(ideal.luminance, t, normal);
  const double plain_rms = relativeRms(plain.luminance, t, normal);
  const double corrected_rms = relativeRms(corrected.luminance, t, normal);
  // The fixed pattern adds 6 DN to each pixel's error; the dark frame (32 frames of 2 DN read
  // noise) leaves 0.36 DN: the corrected error comes within a few percent of the clean sensor's,
  // the uncorrected one does not.
  EXPECT_LT(corrected_rms, 1.05 * ideal_rms) << plain_rms << " " << ideal_rms;
  EXPECT_GT(plain_rms, 1.2 * ideal_rms) << corrected_rms << " " << ideal_rms;
  // Hot pixels read their dark current as light; masked, each takes its neighbours' median:
  // within the noise of the clean sensor's pixels (a median of 8 neighbours, on a smooth scene).
  EXPECT_GT(relativeRms(plain.luminance, t, hot_only), 3 * ideal_rms);
  EXPECT_LT(relativeRms(corrected.luminance, t, hot_only), 1.5 * ideal_rms);
  // A dark frame taken at another gain holds other offsets: the black level is used instead, the
  // hot pixels stay masked.
  block["dark_frame_gain_db"] = 6.0;
  testing::writeText(dir / "cal" / "other-gain.json", block.dump());
  const DarkRun other_gain = processWith(dir / "defective", dir / "cal" / "other-gain.json");
  EXPECT_EQ(other_gain.result["calibration"]["black"], "black_level");
  EXPECT_EQ(other_gain.result["luminance"]["masked_pixels"], 150);
  // And the maximum and ellipse stay the clean sensor's, to a fraction of the merge's noise.
  EXPECT_NEAR(corrected.result["luminance"]["max_cd_m2"].get<double>() /
                  ideal.result["luminance"]["max_cd_m2"].get<double>(),
              1.0, 0.005);
}

TEST(ProcessStack, NoAlphaMeansNoLimitAndNoVerdict) {
  testing::TempDir dir;
  testing::writeSmallStack(dir / "s");
  json manifest = json::parse(testing::readText(dir / "s" / "stack.json"));
  manifest.erase("alpha_deg");
  testing::writeText(dir / "s" / "stack.json", manifest.dump());
  ProcessOptions options = quiet();
  options.output_directory = dir / "out";
  auto summary = processStack(dir / "s", options);
  ASSERT_TRUE(summary) << summary.error().message;
  EXPECT_TRUE(toJson(summary->result)["limit"]["limit_cd_m2"].is_null());
  EXPECT_TRUE(toJson(summary->result)["glare"].is_null());
  EXPECT_TRUE(fs::exists(dir / "out" / "result.json"));
}

// --alpha gives α to a stack that records none, recorded as given; the manifest's own α is
// confirmed by the same value and never overridden by another.
TEST(ProcessStack, AlphaGivenToAStackThatRecordsNone) {
  testing::TempDir dir;
  testing::writeSmallStack(dir / "s");
  json manifest = json::parse(testing::readText(dir / "s" / "stack.json"));
  const double recorded = manifest["alpha_deg"].get<double>();
  ProcessOptions options = quiet();
  options.alpha_deg = recorded;
  auto confirmed = processStack(dir / "s", options);
  ASSERT_TRUE(confirmed) << confirmed.error().message;
  EXPECT_EQ(toJson(confirmed->result)["alpha_source"], "manifest");
  options.alpha_deg = recorded + 10;
  auto contradicted = processStack(dir / "s", options);
  ASSERT_FALSE(contradicted);
  EXPECT_EQ(contradicted.error().code, ErrorCode::kBadInput);
  EXPECT_NE(contradicted.error().message.find("stack.json: records alpha_deg"), std::string::npos)
      << contradicted.error().message;

  manifest.erase("alpha_deg");
  testing::writeText(dir / "s" / "stack.json", manifest.dump());
  auto given = processStack(dir / "s", options);
  ASSERT_TRUE(given) << given.error().message;
  EXPECT_EQ(toJson(given->result)["alpha_deg"], recorded + 10);
  EXPECT_EQ(toJson(given->result)["alpha_source"], "given");
  EXPECT_EQ(toJson(given->result)["limit"]["limit_cd_m2"], glareLimitCdM2(recorded + 10));
  options.alpha_deg.reset();
  auto none = processStack(dir / "s", options);
  ASSERT_TRUE(none);
  EXPECT_TRUE(toJson(none->result)["alpha_source"].is_null());
  options.alpha_deg = 91;
  EXPECT_FALSE(processStack(dir / "s", options));
}

TEST(ProcessStack, BelowTheLimitDoesNotGlare) {
  testing::TempDir dir;
  capture::SimulationOptions options = testing::smallScene(30.0);
  options.peak_scale = 0.03;  // ~16 000 cd/m², below the 30 000 limit
  const auto simulated = testing::writeSmallStack(dir / "s", options);
  ASSERT_FALSE(simulated.truth.limit_axes.has_value());
  auto summary = processStack(dir / "s", quiet());
  ASSERT_TRUE(summary) << summary.error().message;
  EXPECT_EQ(toJson(summary->result)["glare"], false);
  EXPECT_LT(toJson(summary->result)["luminance"]["max_cd_m2"].get<double>(), 30'000.0);
  EXPECT_TRUE(toJson(summary->result)["limit"]["ellipse"].is_null());
  EXPECT_EQ(toJson(summary->result)["limit"]["status"], "below_level");
  EXPECT_EQ(toJson(summary->result)["fwhm"]["status"], "measured");
  EXPECT_TRUE(toJson(summary->result)["fwhm"]["ellipse"].is_object());
}

// The whole chain (simulated sensor noise, bracketing, merge, analysis) against the scene's
// truth at three angles of incidence: 16 px per degree, axes 35..130 px.
TEST(ProcessStack, EllipsesMatchTheTruthThroughTheWholeChain) {
  for (const double alpha : {5.0, 40.0, 70.0}) {
    testing::TempDir dir;
    capture::SimulationOptions options = testing::smallScene(alpha, 320, 256);
    options.horizontal_fov_deg = 20;
    options.seed = 7;
    const auto simulated = testing::writeSmallStack(dir / "s", options);
    auto summary = processStack(dir / "s", quiet());
    ASSERT_TRUE(summary) << summary.error().message;
    const json result = toJson(summary->result);
    // The tolerances: axes and maximum within 1 % of the truth. The merged image has
    // about 1 % noise per pixel; each axis averages hundreds of contour points (its scatter is
    // ~0.1 % at the limit, ~0.3 % at half maximum, which also carries the maximum's error).
    EXPECT_NEAR(result["luminance"]["max_cd_m2"].get<double>() / simulated.truth.peak_cd_m2, 1,
                0.01)
        << alpha;
    const auto expect_axes = [&](const json& ellipse, const capture::EllipseAxes& truth) {
      ASSERT_TRUE(ellipse.is_object()) << alpha;
      EXPECT_NEAR(ellipse["vertical_deg"].get<double>() / truth.vertical_deg, 1, 0.01) << alpha;
      EXPECT_NEAR(ellipse["horizontal_deg"].get<double>() / truth.horizontal_deg, 1, 0.01) << alpha;
      EXPECT_GT(ellipse["uncertainty"]["vertical_deg"].get<double>(), 0) << alpha;
      EXPECT_TRUE(ellipse["ellipticity_ok"].get<bool>()) << alpha;
      EXPECT_EQ(ellipse["regions"], 1) << alpha;
    };
    expect_axes(result["limit"]["ellipse"], *simulated.truth.limit_axes);
    expect_axes(result["fwhm"]["ellipse"], *simulated.truth.fwhm_axes);
    EXPECT_EQ(result["glare"], true);
    // A correct stack's frames agree with the merge.
    EXPECT_TRUE(result["luminance"]["frames_consistent"].get<bool>()) << alpha;
  }
}

// Swapped frame files merge "successfully" into wrong luminance; the frames' agreement with the
// merge catches it (and a correct stack passes).
TEST(ProcessStack, SwappedFramesAreFlaggedAsInconsistent) {
  testing::TempDir dir;
  testing::writeSmallStack(dir / "s");
  auto good = processStack(dir / "s", quiet());
  ASSERT_TRUE(good) << good.error().message;
  EXPECT_TRUE(toJson(good->result)["luminance"]["frames_consistent"].get<bool>());
  const json good_result = toJson(good->result);
  for (const json& frame : good_result["frames"]) {
    if (frame["median_ratio"].is_null()) continue;  // too few well-exposed pixels to judge
    // Noise and the merge's weighting leave a well-exposed frame within 1 % of the merge.
    EXPECT_NEAR(frame["median_ratio"].get<double>(), 1.0, 0.01) << frame;
  }
  json manifest = json::parse(testing::readText(dir / "s" / "stack.json"));
  std::swap(manifest["frames"][2]["file"], manifest["frames"][3]["file"]);
  testing::writeText(dir / "s" / "stack.json", manifest.dump());
  auto swapped = processStack(dir / "s", quiet());
  ASSERT_TRUE(swapped) << swapped.error().message;
  EXPECT_FALSE(toJson(swapped->result)["luminance"]["frames_consistent"].get<bool>());
  EXPECT_FALSE(toJson(swapped->result)["frames"][2]["agrees"].get<bool>());
  EXPECT_FALSE(toJson(swapped->result)["frames"][3]["agrees"].get<bool>());
}

TEST(ProcessStack, EllipseCarriesEveryDocumentedKey) {
  testing::TempDir dir;
  testing::writeSmallStack(dir / "s");
  auto summary = processStack(dir / "s", quiet());
  ASSERT_TRUE(summary) << summary.error().message;
  const json ellipse = toJson(summary->result)["limit"]["ellipse"];
  for (const char* key :
       {"vertical_deg", "horizontal_deg", "major_deg", "minor_deg", "orientation_deg", "center_px",
        "center_direction_deg", "semi_axes_px", "solid_angle_sr", "fit_rms_px", "ellipticity_ok",
        "regions", "uncertainty", "truncated", "shape_residual", "contour_points"}) {
    EXPECT_TRUE(ellipse.contains(key)) << key;
  }
  EXPECT_TRUE(ellipse["uncertainty"].contains("vertical_deg"));
  EXPECT_TRUE(ellipse["uncertainty"].contains("horizontal_deg"));
  EXPECT_EQ(toJson(summary->result)["limit"]["mode"], "alpha_curve");
  EXPECT_EQ(toJson(summary->result)["limit"]["status"], "measured");
  EXPECT_TRUE(toJson(summary->result)["thresholds"].empty());
}

TEST(ProcessStack, ConstantThresholdReplacesTheAlphaCurve) {
  testing::TempDir dir;
  testing::writeSmallStack(dir / "s", testing::smallScene(70.0));
  ProcessOptions options = quiet();
  auto curve = processStack(dir / "s", options);
  ASSERT_TRUE(curve) << curve.error().message;
  options.threshold_cd_m2 = kConstantGlareLimitCdM2;
  auto constant = processStack(dir / "s", options);
  ASSERT_TRUE(constant) << constant.error().message;
  EXPECT_EQ(toJson(constant->result)["limit"]["mode"], "constant");
  EXPECT_EQ(toJson(constant->result)["limit"]["limit_cd_m2"], 30'000.0);
  // At α 70 the curve's limit is 100 000: the constant 30 000 contour is wider.
  EXPECT_GT(toJson(constant->result)["limit"]["ellipse"]["vertical_deg"].get<double>(),
            toJson(curve->result)["limit"]["ellipse"]["vertical_deg"].get<double>());
}

// result.json says what its numbers rest on: the calibration file and its SHA-256, the camera and
// parts it states, K and u(K), and Lmax's uncertainty from noise alone and combined with u(K)
// (in quadrature: K scales every luminance of the stack alike).
TEST(ProcessStack, TheResultRecordsTheCalibrationItRestsOn) {
  testing::TempDir dir;
  testing::writeSmallStack(dir / "s");
  // Unreferred, so that u(K) is the only systematic term (ProcessStackReferred adds u(E)).
  json manifest = json::parse(testing::readText(dir / "s" / "stack.json"));
  manifest.erase("source");
  testing::writeText(dir / "s" / "stack.json", manifest.dump());
  auto inline_run = processStack(dir / "s", quiet());
  ASSERT_TRUE(inline_run) << inline_run.error().message;
  const json inline_cal = toJson(inline_run->result)["calibration"];
  EXPECT_EQ(inline_cal["origin"], "inline");
  EXPECT_TRUE(inline_cal["file"].is_null());
  EXPECT_TRUE(inline_cal["sha256"].is_null());
  EXPECT_TRUE(inline_cal["luminance_factor_u"].is_null());
  EXPECT_TRUE(
      toJson(inline_run->result)["luminance"]["max_relative_uncertainty_combined"].is_null());

  json calibration = json::parse(testing::readText(dir / "s" / "stack.json"))["calibration"];
  calibration.erase("flat_field");
  const double k = calibration["luminance_factor"].get<double>();
  calibration["luminance_factor_u"] = 0.0116 * k;  // the calibration walk-through's 1.16 %
  calibration["camera"] = {{"model", "simulated rig"}, {"serial", "SIM-0001"}};
  calibration["parts"] = {{"luminance",
                           {{"measured_at", "2026-06-21T10:00:00Z"},
                            {"method", "a 5000 cd/m² patch"},
                            {"inputs", {"stacks/luminance"}}}}};
  testing::writeText(dir / "calibration.json", calibration.dump());
  ProcessOptions options = quiet();
  options.calibration_file = dir / "calibration.json";
  auto run = processStack(dir / "s", options);
  ASSERT_TRUE(run) << run.error().message;
  const json cal = toJson(run->result)["calibration"];
  EXPECT_EQ(cal["file"], fs::absolute(dir / "calibration.json").lexically_normal().string());
  EXPECT_EQ(cal["sha256"], *sha256OfFile(dir / "calibration.json"));
  EXPECT_EQ(cal["camera"]["serial"], "SIM-0001");
  EXPECT_EQ(cal["parts"]["luminance"]["measured_at"], "2026-06-21T10:00:00Z");
  EXPECT_FALSE(cal["parts"]["luminance"].contains("inputs"));
  EXPECT_EQ(cal["luminance_factor"], k);
  EXPECT_DOUBLE_EQ(cal["luminance_factor_u"].get<double>(), 0.0116 * k);
  const json luminance = toJson(run->result)["luminance"];
  const double noise = luminance["max_relative_uncertainty"].get<double>();
  EXPECT_LT(noise, 0.0116);  // the merge's noise is the smaller part here
  EXPECT_NEAR(luminance["max_relative_uncertainty_combined"].get<double>(),
              std::hypot(noise, 0.0116), 1e-12);
}

TEST(ProcessStack, ThresholdSweepReportsOneEllipsePerLevel) {
  testing::TempDir dir;
  testing::writeSmallStack(dir / "s", testing::smallScene(60.0));
  ProcessOptions options = quiet();
  options.thresholds_cd_m2 = {50'000, 200'000, 1e12};
  auto summary = processStack(dir / "s", options);
  ASSERT_TRUE(summary) << summary.error().message;
  const json sweep = toJson(summary->result)["thresholds"];
  ASSERT_EQ(sweep.size(), 3u);
  EXPECT_EQ(sweep[0]["threshold_cd_m2"], 50'000.0);
  EXPECT_GT(sweep[0]["ellipse"]["major_deg"].get<double>(),
            sweep[1]["ellipse"]["major_deg"].get<double>());
  EXPECT_EQ(sweep[2]["status"], "below_level");
  EXPECT_TRUE(sweep[2]["ellipse"].is_null());
}

TEST(ProcessStack, DistortionThatCannotBeInvertedAtTheSpotLosesOnlyTheEllipses) {
  testing::TempDir dir;
  testing::writeSmallStack(dir / "s");
  json manifest = json::parse(testing::readText(dir / "s" / "stack.json"));
  // The small scene's focal length is ~570 px: k1 = -300 folds the lens over (1 + k1 r² = 0)
  // about 33 px from the centre, inside the glare spot's contour.
  manifest["calibration"]["intrinsics"]["distortion"] = {-300.0, 0.0, 0.0, 0.0, 0.0};
  testing::writeText(dir / "s" / "stack.json", manifest.dump());
  auto summary = processStack(dir / "s", quiet());
  ASSERT_TRUE(summary) << summary.error().message;
  EXPECT_EQ(toJson(summary->result)["limit"]["status"], "camera_model_not_invertible");
  EXPECT_TRUE(toJson(summary->result)["limit"]["ellipse"].is_null());
  EXPECT_EQ(toJson(summary->result)["glare"],
            true);  // the luminance verdict does not need the lens
  EXPECT_TRUE(fs::exists(dir / "s" / "result" / "luminance.png"));
}

// A lens with distortion (undistortPoints throws on an empty input) and a level below the
// background: the region is the whole image, with no observed contour point.
TEST(ProcessStack, LevelBelowTheBackgroundWithDistortionFillsTheImage) {
  testing::TempDir dir;
  capture::SimulationOptions options = testing::smallScene(40.0);
  options.distortion = {-0.05, 0, 0, 0, 0};
  testing::writeSmallStack(dir / "s", options);
  ProcessOptions process = quiet();
  process.thresholds_cd_m2 = {1000.0};  // the simulated background is 3000 cd/m²
  auto summary = processStack(dir / "s", process);
  ASSERT_TRUE(summary) << summary.error().message;
  EXPECT_EQ(toJson(summary->result)["thresholds"][0]["status"], "fills_image");
  EXPECT_EQ(toJson(summary->result)["limit"]["status"], "measured");
}

TEST(ProcessStack, InvalidThresholdsAreBadInput) {
  testing::TempDir dir;
  testing::writeSmallStack(dir / "s");
  ProcessOptions options = quiet();
  for (const double bad : {0.0, -1.0, std::nan(""), HUGE_VAL}) {
    options.threshold_cd_m2 = bad;
    auto summary = processStack(dir / "s", options);
    ASSERT_FALSE(summary);
    EXPECT_EQ(summary.error().code, ErrorCode::kBadInput);
  }
  options.threshold_cd_m2.reset();
  options.thresholds_cd_m2 = {1000, -5};
  EXPECT_FALSE(processStack(dir / "s", options));
  options.thresholds_cd_m2.assign(kMaxThresholds + 1, 1000.0);
  EXPECT_FALSE(processStack(dir / "s", options));
}

TEST(ProcessStack, SaturatedPeakIsReportedAsALowerBound) {
  testing::TempDir dir;
  const auto simulated = testing::writeSmallStack(dir / "s");
  // Drop the shortest frames: what remains saturates at the peak.
  json manifest = json::parse(testing::readText(dir / "s" / "stack.json"));
  json frames = manifest["frames"];
  manifest["frames"] = json::array({frames[4], frames[5]});
  testing::writeText(dir / "s" / "stack.json", manifest.dump());
  auto summary = processStack(dir / "s", quiet());
  ASSERT_TRUE(summary) << summary.error().message;
  EXPECT_GT(toJson(summary->result)["luminance"]["saturated_pixels"].get<int>(), 0);
  EXPECT_TRUE(toJson(summary->result)["luminance"]["max_is_lower_bound"].get<bool>());
  EXPECT_LT(toJson(summary->result)["luminance"]["max_cd_m2"].get<double>(),
            simulated.truth.peak_cd_m2);
  // The clipped top's position is the plateau's centroid, on the lobe's centre (not its edge).
  EXPECT_NEAR(toJson(summary->result)["luminance"]["max_position_px"][0].get<double>(),
              simulated.centre_pixel[0], 1.0);
  EXPECT_NEAR(toJson(summary->result)["luminance"]["max_position_px"][1].get<double>(),
              simulated.centre_pixel[1], 1.0);
  // Half of a lower bound is no FWHM level.
  EXPECT_EQ(toJson(summary->result)["fwhm"]["status"], "peak_is_bound");
  EXPECT_TRUE(toJson(summary->result)["fwhm"]["ellipse"].is_null());
}

TEST(ProcessStack, EightBitFramesSaturateAtTheirMaximum) {
  testing::TempDir dir;
  const auto simulated = testing::writeSmallStack(dir / "s");
  // Replace the frames by 8-bit ones that clip at 255 under the 12-bit calibration (4000 DN).
  for (std::size_t i = 0; i < simulated.frames.size(); ++i) {
    RawFrame clipped = simulated.frames[i];
    for (std::size_t p = 0; p < clipped.pixelCount(); ++p) {
      clipped.data()[p] = std::min<std::uint16_t>(clipped.data()[p], 255);
    }
    ASSERT_TRUE(writePngGray(dir / "s" / simulated.manifest.frames[i].file, clipped, 8));
  }
  auto summary = processStack(dir / "s", quiet());
  ASSERT_TRUE(summary) << summary.error().message;
  // The peak is clipped at 255 in every frame: a lower bound, not a measurement of 255 DN.
  EXPECT_TRUE(toJson(summary->result)["luminance"]["max_is_lower_bound"].get<bool>());
  EXPECT_GT(toJson(summary->result)["luminance"]["saturated_pixels"].get<int>(), 0);
}

TEST(ProcessStack, AFailedRunNeverLeavesAnOldResultBesideNewOutputs) {
  testing::TempDir dir;
  testing::writeSmallStack(dir / "a", testing::smallScene(20.0));
  testing::writeSmallStack(dir / "b", testing::smallScene(70.0));
  ProcessOptions options = quiet();
  options.output_directory = dir / "out";
  ASSERT_TRUE(processStack(dir / "a", options));
  // Make the picture of the second run unwritable: it fails after writing its EXRs.
  fs::remove(dir / "out" / "luminance.png");
  fs::create_directories(dir / "out" / "luminance.png" / "blocker");
  auto failed = processStack(dir / "b", options);
  ASSERT_FALSE(failed);
  EXPECT_EQ(failed.error().code, ErrorCode::kIo) << failed.error().message;
  // a's result.json must not vouch for b's luminance.exr.
  EXPECT_FALSE(fs::exists(dir / "out" / "result.json"));
}

TEST(ProcessStack, OutputDirectoryCleanupTouchesOnlyItsOwnFiles) {
  testing::TempDir dir;
  testing::writeSmallStack(dir / "s");
  fs::create_directories(dir / "out" / ".tmp-someone-elses");
  testing::writeText(dir / "out" / ".tmp-someone-elses" / "file", "theirs");
  const auto old_time = fs::file_time_type::clock::now() - std::chrono::hours(2);
  fs::last_write_time(dir / "out" / ".tmp-someone-elses", old_time);
  testing::writeText(dir / "out" / "result.json", "{\"my\": \"own results\"}");
  ProcessOptions options = quiet();
  options.output_directory = dir / "out";
  auto refused = processStack(dir / "s", options);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::kBadInput);
  EXPECT_NE(refused.error().message.find("not a glarecam result"), std::string::npos);
  EXPECT_EQ(testing::readText(dir / "out" / "result.json"), "{\"my\": \"own results\"}");
  EXPECT_TRUE(fs::exists(dir / "out" / ".tmp-someone-elses" / "file"));
}

TEST(ProcessStack, BadStackIsBadInput) {
  testing::TempDir dir;
  auto summary = processStack(dir / "nothing-here", quiet());
  ASSERT_FALSE(summary);
  EXPECT_EQ(summary.error().code, ErrorCode::kBadInput);
}

std::vector<fs::path> corpusCases() {
  std::vector<fs::path> cases;
  for (const auto& entry : fs::directory_iterator(testing::testDataDir() / "bad-stacks")) {
    if (entry.is_directory()) cases.push_back(entry.path());
  }
  std::sort(cases.begin(), cases.end());
  return cases;
}

std::string trim(std::string text) {
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  return text;
}

class BadStackCorpus : public ::testing::TestWithParam<fs::path> {};

TEST_P(BadStackCorpus, IsRefusedWithOneClearLine) {
  const fs::path stack = GetParam();
  const std::string expected = trim(testing::readText(stack / "expect.txt"));
  ASSERT_FALSE(expected.empty()) << stack;
  testing::TempDir out;
  pipeline::ProcessOptions options;
  options.output_directory = out / "result";
  options.show_progress = false;
  auto result = pipeline::processStack(stack, options);
  ASSERT_FALSE(result.has_value()) << stack << " was accepted";
  EXPECT_FALSE(fs::exists(out / "result" / "result.json"));
  const Error& error = result.error();
  EXPECT_EQ(error.code, ErrorCode::kBadInput) << error.message;
  EXPECT_NE(error.message.find(expected), std::string::npos)
      << "message: " << error.message << "\nexpected: " << expected;
  EXPECT_EQ(error.message.find('\n'), std::string::npos) << "not one line: " << error.message;
  EXPECT_NE(error.message.find(stack.filename().string()), std::string::npos)
      << "does not name the stack's file: " << error.message;
}

INSTANTIATE_TEST_SUITE_P(Corpus, BadStackCorpus, ::testing::ValuesIn(corpusCases()),
                         [](const ::testing::TestParamInfo<fs::path>& info) {
                           std::string name = info.param.filename().string();
                           std::replace_if(
                               name.begin(), name.end(),
                               [](char c) { return !std::isalnum(static_cast<unsigned char>(c)); },
                               '_');
                           return name;
                         });

TEST(BadStackCorpus, CoversTheListOfStackFormatMd) {
  // The cases the issue and docs/stack-format.md name; the corpus may hold more.
  const char* required[] = {"missing-manifest",
                            "invalid-json",
                            "wrong-schema",
                            "empty-frame-list",
                            "missing-frame",
                            "truncated-png",
                            "zero-byte-png",
                            "colour-png",
                            "frame-size-mismatch",
                            "exposure-zero",
                            "exposure-not-a-number",
                            "black-at-saturation",
                            "fx-zero",
                            "frame-path-dotdot",
                            "frame-path-absolute",
                            "calibration-path-missing",
                            "flat-field-escapes"};
  for (const char* name : required)
    EXPECT_TRUE(fs::is_directory(testing::testDataDir() / "bad-stacks" / name)) << name;
}

}  // namespace
}  // namespace glarecam::pipeline

namespace glarecam::pipeline {
namespace {

// One scene (40°, 16 px per degree) under a sun of `source_lx`, processed; the result as JSON.
json processedUnder(const fs::path& dir, double source_lx, bool record_source,
                    std::optional<SourceIlluminance> given = std::nullopt) {
  capture::SimulationOptions options = testing::smallScene(40.0, 320, 256);
  options.horizontal_fov_deg = 20;
  options.seed = 11;
  options.source_illuminance_lx = source_lx;
  options.source_illuminance_u_lx = 0.03 * source_lx;  // a pyrheliometer's 3 %
  options.record_source = record_source;
  testing::writeSmallStack(dir, options);
  ProcessOptions process = quiet();
  process.source_illuminance = given;
  auto summary = processStack(dir, process);
  EXPECT_TRUE(summary) << summary.error().message;
  return summary ? toJson(summary->result) : json();
}

// The check: the same scene under 60 and 100 klx, referred, gives one Lmax and one limit
// ellipse within their σ; unreferred, the dimmer sun's limit ellipse is smaller by the √ln law.
TEST(ProcessStackReferred, OneSceneUnderTwoSunsGivesOneReferredResult) {
  testing::TempDir dir;
  const json bright = processedUnder(dir / "bright", 100'000, true);
  const json dim = processedUnder(dir / "dim", 60'000, true);
  ASSERT_TRUE(bright.is_object() && dim.is_object());
  EXPECT_EQ(dim["illuminance"]["status"], "referred");
  EXPECT_EQ(dim["illuminance"]["reference_lx"], 100'000);
  EXPECT_EQ(dim["illuminance"]["source"]["origin"], "given");
  EXPECT_NEAR(dim["illuminance"]["factor"].get<double>(), 100.0 / 60.0, 1e-12);
  const auto lmax = [](const json& r) { return r["luminance"]["max_cd_m2"].get<double>(); };
  const auto sigma = [&](const json& r) {
    return r["luminance"]["max_relative_uncertainty_combined"].get<double>() * lmax(r);
  };
  // u(E) (3 %) enters the combined uncertainty on top of the merge's noise.
  EXPECT_GT(dim["luminance"]["max_relative_uncertainty_combined"].get<double>(), 0.03);
  EXPECT_NEAR(lmax(dim), lmax(bright), std::hypot(sigma(dim), sigma(bright)));
  EXPECT_NEAR(dim["luminance"]["measured_max_cd_m2"].get<double>(), lmax(dim) * 0.6,
              1e-9 * lmax(dim));
  for (const char* axis : {"vertical_deg", "horizontal_deg"}) {
    const json& a = dim["limit"]["ellipse"];
    const json& b = bright["limit"]["ellipse"];
    const double u =
        std::hypot(a["uncertainty"][axis].get<double>(), b["uncertainty"][axis].get<double>());
    EXPECT_NEAR(a[axis].get<double>(), b[axis].get<double>(), u) << axis;
  }
  // The axes' σ carry u(E) through the contour's gradient: larger than without it.
  const json unreferred_dim = processedUnder(dir / "unreferred", 60'000, false);
  EXPECT_EQ(unreferred_dim["illuminance"]["status"], "unreferred");
  EXPECT_TRUE(unreferred_dim["luminance"]["measured_max_cd_m2"].is_null());
  EXPECT_GT(dim["limit"]["ellipse"]["uncertainty"]["vertical_deg"].get<double>(),
            2 * unreferred_dim["limit"]["ellipse"]["uncertainty"]["vertical_deg"].get<double>());
  // Unreferred, the lobe is 0.6 times as bright: for a Gaussian lobe an axis goes as
  // √ln((L − B)/(T − B)), so the limit ellipse shrinks by that ratio. The background B scales
  // with the sun as well (3000 → 1800 cd/m²). Within 1 %, the chain's tolerance above.
  const double peak = lmax(bright), limit = *glareLimitCdM2(40.0);
  const double shrink = std::sqrt(std::log((0.6 * peak - 1800) / (limit - 1800)) /
                                  std::log((peak - 3000) / (limit - 3000)));
  for (const char* axis : {"vertical_deg", "horizontal_deg"}) {
    EXPECT_NEAR(unreferred_dim["limit"]["ellipse"][axis].get<double>() /
                    bright["limit"]["ellipse"][axis].get<double>(),
                shrink, 0.01)
        << axis;
  }
  EXPECT_LT(shrink, 0.95);  // the shift is real, not inside the tolerance
}

TEST(ProcessStackReferred, AGivenIlluminanceReplacesTheStacksOwn) {
  testing::TempDir dir;
  // The scene under 60 klx, recorded as if the sun were at the reference; the operator knows.
  SourceIlluminance given{.illuminance_lx = 60'000, .illuminance_u_lx = 1'000};
  const json fixed = processedUnder(dir / "s", 60'000, false, given);
  const json truth = processedUnder(dir / "t", 100'000, true);
  ASSERT_TRUE(fixed.is_object() && truth.is_object());
  EXPECT_EQ(fixed["illuminance"]["source"]["illuminance_lx"], 60'000);
  EXPECT_NEAR(
      fixed["luminance"]["max_cd_m2"].get<double>() / truth["luminance"]["max_cd_m2"].get<double>(),
      1, 0.01);
}

TEST(ProcessStackReferred, ABadReferenceIsRefused) {
  for (double reference : {0.0, -1.0, 2e5, std::nan("")}) {
    ProcessOptions options = quiet();
    options.reference_illuminance_lx = reference;
    const auto status = options.validate();
    ASSERT_FALSE(status) << reference;
    EXPECT_EQ(status.error().code, ErrorCode::kBadInput);
    EXPECT_NE(status.error().message.find("--reference-illuminance"), std::string::npos);
  }
}

}  // namespace
}  // namespace glarecam::pipeline
