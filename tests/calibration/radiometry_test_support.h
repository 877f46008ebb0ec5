// A calibration and frame specs in one line, for the tests of the radiometry and of the merge.
#pragma once

#include <optional>

#include "core/stack_manifest.h"

namespace glarecam::testing {

inline Calibration basicCalibration() {
  Calibration calibration;
  calibration.black_level_dn = 64;
  calibration.saturation_dn = 4000;
  calibration.luminance_factor = 1500;
  calibration.reference_f_number = 8.0;
  calibration.intrinsics = {1000, 1000, 8, 8, {}};
  calibration.noise = NoiseModel{2.0, 0.5};
  return calibration;
}

inline FrameSpec frame(double exposure_us, double gain_db = 0, std::optional<double> f_number = {},
                       double nd = 1) {
  FrameSpec spec;
  spec.file = "f.png";
  spec.exposure_us = exposure_us;
  spec.gain_db = gain_db;
  spec.f_number = f_number;
  spec.nd_transmission = nd;
  return spec;
}

}  // namespace glarecam::testing
