// The bracketer: one bracketed stack (glarecam.stack/1) from any Camera. With fixed exposures it
// captures them; with auto-bracketing it meters, plans and checks (auto_bracket.h). Frames stay
// in memory until the bracket is complete (no disk I/O while the camera streams), then the
// stack is written atomically: a capture that fails leaves nothing behind.
#pragma once

#include <chrono>
#include <filesystem>
#include <optional>
#include <vector>

#include "capture/auto_bracket.h"
#include "capture/camera.h"
#include "core/error.h"
#include "core/image.h"
#include "core/stack_io.h"
#include "core/stack_manifest.h"
#include "core/time.h"

namespace glarecam::capture {

struct CaptureSettings {
  std::optional<std::vector<double>> exposures_us;  // none: auto-bracket
  double gain_db = 0;
  // Written inline, its images (flat field, dark frame, hot pixels: calibrationImages()) copied
  // from its directory into the stack's calibration/ folder, so that the stack stands alone; its
  // black level and saturation also guide the auto-bracket.
  std::optional<Calibration> calibration;
  std::optional<double> alpha_deg;
  // The module measured (its name or serial), recorded as the manifest's "module": a sweep
  // refuses to mix stacks of different modules.
  std::optional<std::string> module;
  // Without alpha_deg: a simulated camera's scene α (glarecam capture --camera sim:). Off where
  // a rig measures α, so that an α it could not measure stays unknown.
  bool alpha_from_scene = true;
  // The source illuminance during the bracket (capture --source-illuminance, a rig instrument),
  // recorded as the manifest's `source`. Without it, and with alpha_from_scene, a simulated
  // camera's scene gives its simulated sun's.
  std::optional<SourceIlluminance> source_illuminance;
  std::optional<nlohmann::json> geometry;  // the rig's geometry block (rig_geometry.h), as measured
  CameraOptics optics;                     // overrides what the camera reports
  AutoBracketOptions auto_bracket;
  bool show_progress = false;
  // The stack's time (its id and captured_at); default the system clock's when the bracket
  // starts. The daemon's clock may differ (simulated time).
  std::optional<UtcTime> start_time;
};

struct CapturedStack {
  StackManifest manifest;
  std::vector<RawFrame> frames;
  int bit_depth = 16;                        // of the stack's PNG files
  std::optional<nlohmann::json> truth;       // a simulated camera's scene truth, as truth.json
  std::vector<StackAttachment> attachments;  // the calibration's images, into calibration/
};

Result<CapturedStack> captureStack(Camera& camera, const CaptureSettings& settings);

// α measured again after the bracket (for its middle): into the manifest, its geometry block and
// the α in the stack's id.
void recordAlpha(CapturedStack& stack, double alpha_deg, nlohmann::json geometry);

// Writes the stack atomically to `parent`/<its id> and returns that path; an id already taken
// gets a numeric suffix, so a series never overwrites a stack.
Result<std::filesystem::path> writeCapturedStack(const std::filesystem::path& parent,
                                                 const CapturedStack& stack);

}  // namespace glarecam::capture
