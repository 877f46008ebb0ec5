// One frame a calibration procedure measures, with everything the procedures know about it: its
// pixels, its settings as the stack's manifest states them (exposure, gain, f-number), a name for
// errors ("targets/dark/frame-03.png"), the bit depth of its file (an 8-bit frame saturates at
// 255) and which of the input stacks it came from (intrinsics: one board view a stack).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/stack_manifest.h"

namespace glarecam::calibration {

struct InputFrame {
  RawFrame frame;
  FrameSpec spec;
  std::string name;
  int bit_depth = 16;
  std::size_t stack = 0;  // index of its stack among the inputs
};

// The frames' specs, in order (groupByExposure, radiometry).
std::vector<FrameSpec> specsOf(std::span<const InputFrame> frames);

}  // namespace glarecam::calibration
