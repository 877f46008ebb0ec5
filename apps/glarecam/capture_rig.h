// The rig around `glarecam capture --config`: the camera and calibration the config names, the
// sensors that give each stack its α and geometry block, the status LED (capturing during a
// bracket, ready between) and the operator's button (--on-button: one stack per press).
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "capture/bracketer.h"
#include "core/error.h"
#include "rig/gpio/rig_io.h"
#include "rig/gpio/status_led.h"
#include "rig/rig_config.h"
#include "rig/rig_geometry.h"

namespace glarecam::apps {

class CaptureRig {
 public:
  // Reads the config and opens its sensors and GPIO. kBadInput when --alpha contradicts a config
  // that gives α, or --on-button is asked of a config without a button.
  static Result<std::unique_ptr<CaptureRig>> open(const std::string& config_path, bool alpha_given,
                                                  bool on_button, bool show_progress);
  ~CaptureRig();

  const rig::RigConfig& config() const { return config_; }
  bool measuresAlpha() const { return sensors_ != nullptr; }
  bool waitsForButton() const { return on_button_; }

  // The config's camera calibration, when its calibration file holds one (it may hold only the
  // inclinometer's zero offset).
  Result<std::optional<Calibration>> cameraCalibration() const;

  // Measures the geometry now and records it in `settings` (α and the geometry block).
  Status measureInto(capture::CaptureSettings& settings);

  // After the bracket: α again at the bracket's middle (the sun moved while the inclinometer
  // was read and the frames exposed), into the stack's manifest.
  // A failure only warns: the stack keeps α from before the bracket.
  void finishStack(capture::CapturedStack& stack, UtcTime bracket_start, UtcTime bracket_end);

  // With --on-button: waits for a press (true) or a stop request (false). Without: true.
  Result<bool> waitForButton();

  void showCapturing(bool capturing);
  void showFault(rig::FaultCode fault);

 private:
  CaptureRig() = default;

  rig::RigConfig config_;
  std::unique_ptr<rig::RigSensors> sensors_;
  std::unique_ptr<rig::RigIo> io_;
  std::unique_ptr<rig::StatusLed> led_;
  std::optional<rig::RigGeometry> measured_;  // the last geometry measured
  bool on_button_ = false;
  bool show_progress_ = false;
};

}  // namespace glarecam::apps
