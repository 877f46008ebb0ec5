// Test helpers on the simulator (capture/sim/), the ground truth of the tests from calibration up:
// small simulated scenes and stacks in one line, merged images rendered straight from a glare
// lobe, and a processed stack checked against its scene's truth. Core-only helpers are in
// support/test_support.h.
#pragma once

#include <array>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "calibration/hdr_merge.h"
#include "capture/sim/simulated_stack.h"
#include "support/test_support.h"

namespace glarecam::testing {

// Simulator options for a small, fast scene (the default sizes are for real use).
capture::SimulationOptions smallScene(double alpha_deg = 40.0, int width = 160, int height = 128);

// Simulates and writes a stack (creating its parent directories); fails the calling test on error.
capture::SimulatedStack writeSmallStack(const std::filesystem::path& directory,
                                        const capture::SimulationOptions& options = smallScene());

// A merged image in which every pixel is measured (one valid frame, no bounds), luminance 0, with
// the given relative uncertainty: tests then fill in the luminance they need.
calibration::MergedImage measuredImage(int width, int height, float relative_uncertainty);

// A glare lobe rendered straight into a merged luminance image (no sensor, no bracketing), with
// optional Gaussian noise of a given relative sigma, which is also the per-pixel relative
// uncertainty the merge would report. Ground truth comes from the scene (glare_scene.h).
struct SceneSpec {
  int width = 640, height = 512;
  double horizontal_fov_deg = 40.0;
  std::array<double, 5> distortion{};
  capture::GlareLobe lobe;
  double limit_cd_m2 = 30'000.0;
  double relative_noise = 0.0;
  unsigned seed = 1;
};

struct RenderedScene {
  calibration::MergedImage merged;
  Intrinsics intrinsics;
  capture::SceneTruth truth;
  calibration::PixelPoint centre_px;
};

// The lobe whose limit contour has the given axes, like the simulator's modules.
capture::GlareLobe lobeAtLimit(double limit_cd_m2, double peak_cd_m2, double vertical_deg,
                               double horizontal_deg, double background_cd_m2 = 3000.0);
RenderedScene renderScene(const SceneSpec& spec);

// Processes the stack at `directory` (no progress) and checks its maximum and both ellipses
// against `truth`, each within `relative_tolerance`; returns result.json for further checks.
nlohmann::json expectProcessedMatchesTruth(const std::filesystem::path& directory,
                                           const capture::SceneTruth& truth,
                                           double relative_tolerance);

}  // namespace glarecam::testing
