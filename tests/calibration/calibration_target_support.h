// The simulated calibration targets (capture/sim/calibration_targets.h) as the calibration
// procedures take them: one target's first stack, its frames as input frames, and the simulated
// sensor's levels. For the tests of each procedure against the target's known truth.
#pragma once

#include <gtest/gtest.h>

#include <utility>
#include <vector>

#include "calibration/flat_calibration.h"
#include "calibration/input_frame.h"
#include "capture/sim/calibration_targets.h"

namespace glarecam::testing {

inline capture::CalibrationTargetStack target(capture::CalibrationTarget kind,
                                              capture::CalibrationTargetOptions options = {}) {
  options.target = kind;
  auto stacks = capture::simulateCalibrationTarget(options);
  EXPECT_TRUE(stacks) << stacks.error().message;
  return std::move(stacks->front());
}

// The stack's frames as the procedures take them, named "target/frame-NN.png".
inline std::vector<calibration::InputFrame> inputFrames(
    const capture::CalibrationTargetStack& stack) {
  std::vector<calibration::InputFrame> frames;
  for (std::size_t i = 0; i < stack.frames.size(); ++i) {
    frames.push_back({.frame = stack.frames[i],
                      .spec = stack.manifest.frames[i],
                      .name = "target/" + stack.manifest.frames[i].file,
                      .bit_depth = 16,
                      .stack = 0});
  }
  return frames;
}

// The simulated sensor's levels (capture::SensorModel defaults).
inline const calibration::SensorLevels kLevels{.black_level_dn = 64, .saturation_dn = 4000};

}  // namespace glarecam::testing
