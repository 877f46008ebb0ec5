// `glarecam capture` as one call: a series of bracketed stacks from a camera (capture_series.h),
// on a rig when a config is given. With a config the rig session (rig_session.h) measures α and
// the geometry block before each stack (the first before the camera opens, so that a simulated
// camera shows the rig's α and a rig that cannot measure fails before any exposure), drives the
// LED and, with on_button, waits for the operator's button; the config's camera and calibration
// are the defaults. Stacks land atomically under the series' output directory; staging
// directories an earlier capture left behind (killed while writing) are removed first.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "capture/capture_config.h"
#include "capture/capture_series.h"
#include "core/error.h"
#include "core/stack_manifest.h"

namespace glarecam::daemon {

struct CaptureRunOptions {
  std::optional<std::string> camera_uri;             // default: the config's
  std::optional<std::filesystem::path> config_path;  // the rig's config (TOML)
  capture::CaptureConfig capture;                    // the bracket and the camera's options
  std::optional<double> alpha_deg;                   // α given; contradicts a config that gives α
  std::optional<Calibration> calibration;            // default: the config's calibration file's
  std::optional<std::string> module;                 // default: the config's [output] module
  // --source-illuminance: the source's E for every stack of the series (a lab lamp).
  std::optional<SourceIlluminance> source_illuminance;
  capture::SeriesOptions series;
  bool on_button = false;  // before each stack, wait for the config's [gpio] button
  bool show_progress = true;

  // The first problem in words (kBadInput), or nothing.
  Status validate() const;
};

Status runCapture(const CaptureRunOptions& options);

// What the camera itself knows must not be contradicted (kBadInput: lens and filter options for a
// camera that knows its own), and what it lacks is warned about (no calibration, no α).
Status checkAgainstCamera(const capture::Camera& camera, const capture::CaptureSettings& settings);

}  // namespace glarecam::daemon
