// What the BRDF route's tests share: one Gaussian lobe (its contours known in closed form before
// the sun's disc) and a noiseless lab.
#pragma once

#include "brdf/simulated_goniophotometer.h"
#include "surface/brdf_model.h"

namespace glarecam::brdf::testing {

// Narrower across than along the plane of incidence, on a floor far below the lobe.
inline constexpr surface::GaussianLobeParameters kTestLobe{.peak_brdf_sr = 60,
                                                           .sigma_horizontal_deg = 1.6,
                                                           .sigma_vertical_deg = 1.1,
                                                           .floor_brdf_sr = 0.02};

// The simulated goniophotometer without noise, rings every `fine_step_deg` out to 5°, every
// degree out to 20°.
inline GoniophotometerOptions noiselessLab(double fine_step_deg = 0.1) {
  GoniophotometerOptions o;
  o.fine_step_deg = fine_step_deg;
  o.medium_radius_deg = 20;
  o.relative_noise = 0;
  return o;
}

}  // namespace glarecam::brdf::testing
