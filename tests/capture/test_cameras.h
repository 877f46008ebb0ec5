// Cameras for the tests of capture/: a backend that counts what reaches the Camera base class and
// answers as told, and the sim: camera (capture/sim/sim_camera.h) with its sensor's range and
// limits like a camera's.
#pragma once

#include <gtest/gtest.h>

#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "capture/camera.h"
#include "capture/camera_registry.h"

namespace glarecam::testing {

inline constexpr double kSimRangeDn = 3936.0;  // the simulated sensor: 4000 saturation - 64 black

inline const capture::CameraLimits kSimLimits{.min_exposure_us = 10,
                                              .max_exposure_us = 2e6,
                                              .exposure_step_us = 1,
                                              .min_gain_db = 0,
                                              .max_gain_db = 24};

inline std::unique_ptr<capture::Camera> openSim(const std::string& id, double alpha_deg = 40.0) {
  auto camera = capture::openCamera(
      "sim:" + id, {}, [alpha_deg] { return capture::SceneState{.alpha_deg = alpha_deg}; });
  EXPECT_TRUE(camera) << camera.error().message;
  return camera ? std::move(*camera) : nullptr;
}

// A backend that counts what reaches it and answers as told.
class CountingCamera final : public capture::Camera {
 public:
  enum class Answer { kFrames, kTooFew, kThrow, kError, kNamedError };

  explicit CountingCamera(capture::CameraLimits limits, Answer answer = Answer::kFrames)
      : limits_(limits), answer_(answer) {
    info_.uri = "test:counting";
  }
  const capture::CameraInfo& info() const override { return info_; }
  capture::CameraLimits limits() const override { return limits_; }
  capture::SensorFormat format() const override { return {"Mono8", 4, 4, 8}; }
  int calls() const { return calls_; }

 private:
  Result<std::vector<capture::CapturedFrame>> doCapture(
      std::span<const capture::ExposureRequest> requests) override {
    ++calls_;
    switch (answer_) {
      case Answer::kThrow:
        throw std::runtime_error("driver exploded");
      case Answer::kError:
        return hardwareError("control-lost");
      case Answer::kNamedError:
        return hardwareError("test:counting: control-lost");
      case Answer::kTooFew:
        return std::vector<capture::CapturedFrame>(requests.size() - 1);
      case Answer::kFrames:
        break;
    }
    std::vector<capture::CapturedFrame> frames(requests.size());
    for (std::size_t i = 0; i < requests.size(); ++i)
      frames[i].exposure_us = requests[i].exposure_us;
    return frames;
  }

  capture::CameraInfo info_;
  capture::CameraLimits limits_;
  Answer answer_;
  int calls_ = 0;
};

}  // namespace glarecam::testing
