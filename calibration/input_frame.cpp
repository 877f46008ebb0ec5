#include "calibration/input_frame.h"

namespace glarecam::calibration {

std::vector<FrameSpec> specsOf(std::span<const InputFrame> frames) {
  std::vector<FrameSpec> specs;
  specs.reserve(frames.size());
  for (const InputFrame& frame : frames) specs.push_back(frame.spec);
  return specs;
}

}  // namespace glarecam::calibration
