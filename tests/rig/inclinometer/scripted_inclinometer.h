// An inclinometer replaying scripted samples, and noisy samples of a known attitude to script:
// for the tests of what is computed from an inclinometer's samples (tilt, the zero offset file).
#pragma once

#include <deque>
#include <random>
#include <utility>

#include "rig/inclinometer/inclinometer.h"
#include "rig/inclinometer/tilt.h"

namespace glarecam::testing {

// An inclinometer replaying scripted samples (or an error).
class ScriptedInclinometer final : public rig::Inclinometer {
 public:
  explicit ScriptedInclinometer(std::deque<Result<rig::AccelerationSample>> samples)
      : samples_(std::move(samples)) {}
  const rig::InclinometerInfo& info() const override { return info_; }
  Result<rig::AccelerationSample> read() override {
    if (samples_.empty()) return hardwareError("script exhausted");
    auto next = samples_.front();
    samples_.pop_front();
    return next;
  }

 private:
  rig::InclinometerInfo info_{
      .uri = "test:scripted", .backend = "test", .model = "", .detail = "", .full_scale_g = 2};
  std::deque<Result<rig::AccelerationSample>> samples_;
};

// `n` samples of the attitude `tilt` (no mounting error) with white noise of `noise_g` per axis.
inline std::deque<Result<rig::AccelerationSample>> noisySamples(rig::AxisTilt tilt, int n,
                                                                double noise_g,
                                                                rig::AxisTilt offset = {},
                                                                unsigned seed = 7) {
  std::mt19937 random(seed);
  std::normal_distribution<double> noise(0.0, noise_g);
  std::deque<Result<rig::AccelerationSample>> samples;
  for (int i = 0; i < n; ++i) {
    rig::AccelerationSample s = rig::mountedGravity(tilt, offset);
    s.x_g += noise(random);
    s.y_g += noise(random);
    s.z_g += noise(random);
    s.temperature_c = 24.0;
    samples.push_back(s);
  }
  return samples;
}

}  // namespace glarecam::testing
