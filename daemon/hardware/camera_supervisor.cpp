#include "daemon/hardware/camera_supervisor.h"

#include <fmt/format.h>

#include <algorithm>

namespace glarecam::daemon {

CameraSupervisor::CameraSupervisor(FaultConfig faults, CameraOpener opener,
                                   capture::SceneSource scene_source)
    : faults_(faults), opener_(std::move(opener)), scene_source_(std::move(scene_source)) {}

void CameraSupervisor::configure(std::string uri, capture::CameraOptions options,
                                 FaultConfig faults) {
  faults_ = faults;
  if (uri == uri_ && options == options_) return;
  uri_ = std::move(uri);
  options_ = std::move(options);
  camera_.reset();
}

Result<capture::Camera*> CameraSupervisor::acquire(SteadyTime now) {
  if (camera_) return camera_.get();
  if (retry_at_ && now < *retry_at_)
    return std::unexpected(last_error_.value_or(Error{ErrorCode::kHardware, uri_ + ": closed"}));
  auto opened = opener_(uri_, options_, scene_source_);
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

std::string CameraSupervisor::faultText(const Error& error, SteadyTime now,
                                        bool mid_bracket) const {
  const auto wait = retry_at_ ? std::chrono::ceil<std::chrono::seconds>(*retry_at_ - now)
                              : std::chrono::seconds(0);
  return fmt::format("{}{}; reopening in {} s (failure {} of {})", error.message,
                     mid_bracket ? "; the stack was discarded" : "", wait.count(), failures_,
                     faults_.camera_max_failures);
}

}  // namespace glarecam::daemon
