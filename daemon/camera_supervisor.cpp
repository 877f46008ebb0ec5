#include "daemon/camera_supervisor.h"

#include <algorithm>

namespace glarecam::daemon {

namespace {

bool sameOptions(const capture::CameraOptions& a, const capture::CameraOptions& b) {
  return a.pixel_format == b.pixel_format && a.max_frame_retries == b.max_frame_retries &&
         a.frame_timeout_s == b.frame_timeout_s && a.simulated_alpha_deg == b.simulated_alpha_deg &&
         a.genicam_features == b.genicam_features;
}

}  // namespace

CameraSupervisor::CameraSupervisor(FaultConfig faults, CameraOpener opener)
    : faults_(faults), opener_(std::move(opener)) {}

void CameraSupervisor::configure(std::string uri, capture::CameraOptions options,
                                 FaultConfig faults) {
  faults_ = faults;
  if (uri == uri_ && sameOptions(options, options_)) return;
  uri_ = std::move(uri);
  options_ = std::move(options);
  camera_.reset();
}

Result<capture::Camera*> CameraSupervisor::acquire(SteadyTime now) {
  if (camera_) return camera_.get();
  if (retry_at_ && now < *retry_at_)
    return std::unexpected(last_error_.value_or(Error{ErrorCode::kHardware, uri_ + ": closed"}));
  auto opened = opener_(uri_, options_);
  if (!opened) {
    failed(opened.error(), now);
    return std::unexpected(opened.error());
  }
  camera_ = std::move(*opened);
  retry_at_.reset();
  return camera_.get();
}

void CameraSupervisor::failed(const Error& error, SteadyTime now) {
  camera_.reset();
  ++failures_;
  last_error_ = error;
  retry_at_ = now + backoffAfter(failures_);
}

std::optional<SteadyTime> CameraSupervisor::retryAt() const {
  if (camera_) return std::nullopt;
  return retry_at_;
}

std::chrono::seconds CameraSupervisor::backoffAfter(int failures) const {
  std::chrono::seconds backoff = faults_.camera_backoff;
  for (int i = 1; i < failures && backoff < faults_.camera_backoff_max; ++i) backoff *= 2;
  return std::min(backoff, faults_.camera_backoff_max);
}

}  // namespace glarecam::daemon
