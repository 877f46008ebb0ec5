// The daemon's one camera, kept open between stacks and reopened after it fails. A failure (the
// camera lost mid-bracket, an open that fails) closes it; the next open is allowed only after a
// backoff that starts at FaultConfig::camera_backoff and doubles up to camera_backoff_max; after
// camera_max_failures failures in a row the supervisor is exhausted and the daemon exits so that
// systemd restarts it (StartLimitBurst keeps that from looping fast). A success clears the count.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "capture/camera.h"
#include "capture/camera_registry.h"
#include "core/error.h"
#include "daemon/daemon_clock.h"
#include "daemon/daemon_config.h"

namespace glarecam::daemon {

// Opens a camera by URI, as capture::openCamera (the default) does.
using CameraOpener = std::function<Result<std::unique_ptr<capture::Camera>>(
    std::string_view uri, const capture::CameraOptions&, const capture::SceneSource&)>;

class CameraSupervisor {
 public:
  // `scene_source`: given to every camera it opens (the rig's measured α, for a simulated one).
  CameraSupervisor(FaultConfig faults, CameraOpener opener, capture::SceneSource scene_source);

  // The camera to open; an open camera is closed when the URI or the options change.
  void configure(std::string uri, capture::CameraOptions options, FaultConfig faults);

  // The open camera, opening it when closed and the backoff has passed. An open that fails is
  // counted as a failure (and returned).
  Result<capture::Camera*> acquire(SteadyTime now);
  capture::Camera* camera() const { return camera_.get(); }

  // A capture failed: closes the camera and starts the backoff.
  void failed(const Error& error, SteadyTime now);
  void succeeded() { failures_ = 0; }

  // When the next open may be tried, while the camera is closed after a failure.
  std::optional<SteadyTime> retryAt() const;
  int failures() const { return failures_; }
  int maxFailures() const { return faults_.camera_max_failures; }
  bool exhausted() const { return failures_ >= faults_.camera_max_failures; }
  const std::optional<Error>& lastError() const { return last_error_; }
  void close() { camera_.reset(); }

  // What the status says after `error` at `now`: "<error>[; the stack was discarded]; reopening in
  // 8 s (failure 2 of 8)".
  std::string faultText(const Error& error, SteadyTime now, bool mid_bracket) const;

  // The backoff after `failures` failures in a row.
  std::chrono::seconds backoffAfter(int failures) const;

 private:
  FaultConfig faults_;
  CameraOpener opener_;
  capture::SceneSource scene_source_;
  std::string uri_;
  capture::CameraOptions options_;
  std::unique_ptr<capture::Camera> camera_;
  int failures_ = 0;
  std::optional<SteadyTime> retry_at_;
  std::optional<Error> last_error_;
};

}  // namespace glarecam::daemon
