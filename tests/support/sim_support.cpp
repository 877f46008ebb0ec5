#include "support/sim_support.h"

#include <gtest/gtest.h>

#include <random>

#include "pipeline/process_stack.h"

namespace glarecam::testing {
namespace fs = std::filesystem;

capture::SimulationOptions smallScene(double alpha_deg, int width, int height) {
  capture::SimulationOptions options;
  options.alpha_deg = alpha_deg;
  options.width = width;
  options.height = height;
  // A narrow field of view keeps the lobe many pixels wide on a small frame.
  options.horizontal_fov_deg = 16.0;
  return options;
}

capture::SimulatedStack writeSmallStack(const fs::path& directory,
                                        const capture::SimulationOptions& options) {
  auto stack = capture::simulateStack(options);
  EXPECT_TRUE(stack.has_value()) << (stack ? "" : stack.error().message);
  if (!stack) return {};
  fs::create_directories(directory.parent_path());
  auto status = capture::writeSimulatedStack(directory, *stack);
  EXPECT_TRUE(status.has_value()) << (status ? "" : status.error().message);
  return std::move(*stack);
}

calibration::MergedImage measuredImage(int width, int height, float relative_uncertainty) {
  calibration::MergedImage merged;
  merged.luminance_cd_m2 = FloatImage(width, height);
  merged.relative_uncertainty = FloatImage(width, height, relative_uncertainty);
  merged.valid_frames = ByteImage(width, height, 1);
  merged.bound = ByteImage(width, height, 0);
  return merged;
}

capture::GlareLobe lobeAtLimit(double limit_cd_m2, double peak_cd_m2, double vertical_deg,
                               double horizontal_deg, double background_cd_m2) {
  auto lobe = capture::lobeWithAxesAt(limit_cd_m2, peak_cd_m2, background_cd_m2, vertical_deg,
                                      horizontal_deg);
  EXPECT_TRUE(lobe.has_value()) << (lobe ? "" : lobe.error().message);
  return lobe.value_or(capture::GlareLobe{});
}

RenderedScene renderScene(const SceneSpec& spec) {
  RenderedScene result;
  result.intrinsics =
      capture::pinholeIntrinsics(spec.width, spec.height, spec.horizontal_fov_deg, spec.distortion);
  const calibration::CameraModel camera(result.intrinsics);
  auto scene = capture::GlareScene::create(spec.lobe);
  EXPECT_TRUE(scene.has_value()) << (scene ? "" : scene.error().message);
  if (!scene) return result;
  result.truth = scene->truth(spec.limit_cd_m2);
  result.centre_px = camera.project(scene->centreRay());
  result.merged = measuredImage(spec.width, spec.height, static_cast<float>(spec.relative_noise));
  auto& merged = result.merged;
  merged.luminance_cd_m2 = scene->render(camera, spec.width, spec.height);
  std::mt19937 rng(spec.seed);
  std::normal_distribution<double> gauss(0.0, spec.relative_noise);
  if (spec.relative_noise > 0) {
    for (std::size_t i = 0; i < merged.luminance_cd_m2.pixelCount(); ++i)
      merged.luminance_cd_m2.data()[i] *= static_cast<float>(1.0 + gauss(rng));
  }
  return result;
}

nlohmann::json expectProcessedMatchesTruth(const std::filesystem::path& directory,
                                           const capture::SceneTruth& truth,
                                           double relative_tolerance) {
  pipeline::ProcessOptions options;
  options.show_progress = false;
  auto summary = pipeline::processStack(directory, options);
  EXPECT_TRUE(summary) << summary.error().message;
  if (!summary) return {};
  const nlohmann::json result = pipeline::toJson(summary->result);
  EXPECT_NEAR(result["luminance"]["max_cd_m2"].get<double>() / truth.peak_cd_m2, 1,
              relative_tolerance);
  const auto expect_axes = [&](const nlohmann::json& ellipse,
                               const std::optional<capture::EllipseAxes>& axes) {
    if (!axes) return;
    EXPECT_TRUE(ellipse.is_object()) << ellipse.dump();
    if (!ellipse.is_object()) return;
    EXPECT_NEAR(ellipse["vertical_deg"].get<double>() / axes->vertical_deg, 1, relative_tolerance);
    EXPECT_NEAR(ellipse["horizontal_deg"].get<double>() / axes->horizontal_deg, 1,
                relative_tolerance);
  };
  expect_axes(result["limit"]["ellipse"], truth.limit_axes);
  expect_axes(result["fwhm"]["ellipse"], truth.fwhm_axes);
  return result;
}

}  // namespace glarecam::testing
