#include "daemon/daemon_test_support.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "capture/camera_registry.h"
#include "capture/sim/sim_camera.h"

namespace glarecam::testing {

namespace {
// Waits in a row that move no time before ManualClock calls it a busy loop. A daemon step is
// tens of µs, so this is seconds of spinning; an honest loop waits for "now" a few times at most
// (a request queued while a capture is due) before time has to move.
constexpr int kMaxStalledWaits = 100'000;
}  // namespace

// ---- ManualClock ------------------------------------------------------------------------------

ManualClock::ManualClock(UtcTime start)
    : start_steady_(SteadyTime{} + std::chrono::hours(1000)),
      start_utc_(start),
      now_(start_steady_) {}

SteadyTime ManualClock::now() const {
  const std::lock_guard lock(mutex_);
  return now_;
}

UtcTime ManualClock::utcNow() const {
  const std::lock_guard lock(mutex_);
  return start_utc_ + std::chrono::duration_cast<std::chrono::microseconds>(now_ - start_steady_);
}

sun::ClockStatus ManualClock::clockStatus() const {
  const std::lock_guard lock(mutex_);
  return status_;
}

SteadyTime ManualClock::steadyAt(UtcTime utc) const {
  return start_steady_ + std::chrono::duration_cast<SteadyTime::duration>(utc - start_utc_);
}

void ManualClock::waitUntil(std::unique_lock<std::mutex>& lock, std::condition_variable&,
                            SteadyTime deadline, const std::function<bool()>& ready) {
  if (ready()) return;
  std::function<void()> alarm;
  {
    const std::lock_guard guard(mutex_);
    if (!alarms_.empty() && alarms_.begin()->first <= deadline) {
      now_ = std::max(now_, alarms_.begin()->first);
      alarm = std::move(alarms_.begin()->second);
      alarms_.erase(alarms_.begin());
      stalled_waits_ = 0;
    } else {
      stalled_waits_ = deadline <= now_ ? stalled_waits_ + 1 : 0;
      now_ = std::max(now_, deadline);
    }
  }
  if (stalled_waits_ > kMaxStalledWaits) {
    // Aborting names the test; hanging would only end at ctest's timeout.
    std::fputs("ManualClock: the loop waits for 'now' over and over (a busy loop)\n", stderr);
    std::abort();
  }
  if (!alarm) return;
  lock.unlock();  // the alarm posts to the queue whose lock this is
  alarm();
  lock.lock();
}

void ManualClock::at(std::chrono::nanoseconds offset, std::function<void()> action) {
  const std::lock_guard lock(mutex_);
  alarms_.emplace(start_steady_ + offset, std::move(action));
}

void ManualClock::advance(std::chrono::nanoseconds by) {
  const std::lock_guard lock(mutex_);
  now_ += by;
}

void ManualClock::setUtcStart(UtcTime start) {
  const std::lock_guard lock(mutex_);
  start_utc_ = start;
}

void ManualClock::setClockStatus(sun::ClockStatus status) {
  const std::lock_guard lock(mutex_);
  status_ = std::move(status);
}

std::chrono::nanoseconds ManualClock::elapsed() const {
  const std::lock_guard lock(mutex_);
  return now_ - start_steady_;
}

// ---- RecordingNotifier ------------------------------------------------------------------------

void RecordingNotifier::notify(const std::string& message) {
  const std::lock_guard lock(mutex_);
  messages_.push_back({clock_.elapsed(), message});
}

std::vector<Notification> RecordingNotifier::messages() const {
  const std::lock_guard lock(mutex_);
  return messages_;
}

std::vector<Notification> RecordingNotifier::matching(const std::string& prefix) const {
  std::vector<Notification> found;
  for (const Notification& n : messages())
    if (n.message.starts_with(prefix)) found.push_back(n);
  return found;
}

std::size_t RecordingNotifier::count(const std::string& message) const {
  std::size_t n = 0;
  for (const Notification& m : messages()) n += m.message == message;
  return n;
}

// ---- ScriptedDisk -----------------------------------------------------------------------------

Result<daemon::DiskState> ScriptedDisk::probe(const std::filesystem::path&) {
  const std::lock_guard lock(mutex_);
  ++probes_;
  return state_;
}

void ScriptedDisk::set(daemon::DiskState state) {
  const std::lock_guard lock(mutex_);
  state_ = state;
}

// ---- ScriptedCameras ----------------------------------------------------------------------------

// A sim: camera that fails or wedges on cue; it knows its scene's truth as the camera it wraps.
class ScriptedCamera final : public capture::Camera, public capture::SceneTruthSource {
 public:
  ScriptedCamera(std::unique_ptr<capture::Camera> camera, ScriptedCameras& script)
      : camera_(std::move(camera)), script_(script) {}
  const capture::CameraInfo& info() const override { return camera_->info(); }
  capture::CameraLimits limits() const override { return camera_->limits(); }
  capture::SensorFormat format() const override { return camera_->format(); }
  std::optional<nlohmann::json> sceneTruth() const override {
    return capture::sceneTruthOf(*camera_);
  }

 private:
  Result<std::vector<capture::CapturedFrame>> doCapture(
      std::span<const capture::ExposureRequest> requests) override {
    if (auto error = script_.beforeCapture(requests)) return std::unexpected(*error);
    return camera_->capture(requests);
  }

  std::unique_ptr<capture::Camera> camera_;
  ScriptedCameras& script_;
};

daemon::CameraOpener ScriptedCameras::opener() {
  return
      [this](std::string_view uri, const capture::CameraOptions& options,
             const capture::SceneSource& scene_source) -> Result<std::unique_ptr<capture::Camera>> {
        ++opens_;
        {
          const std::lock_guard lock(mutex_);
          if (opens_fail_) return hardwareError(std::string(uri) + ": no such camera (scripted)");
        }
        std::unique_ptr<capture::Camera> camera;
        GLARECAM_ASSIGN(camera, capture::openCamera(uri, options, scene_source));
        return std::unique_ptr<capture::Camera>(new ScriptedCamera(std::move(camera), *this));
      };
}

std::optional<Error> ScriptedCameras::beforeCapture(
    std::span<const capture::ExposureRequest> requests) {
  const int call = ++calls_;
  if (capture_hook_) capture_hook_();
  std::unique_lock lock(mutex_);
  if (exposure_clock_) {
    double exposures_us = 0;
    for (const capture::ExposureRequest& request : requests) exposures_us += request.exposure_us;
    exposure_clock_->advance(std::chrono::nanoseconds(std::llround(exposures_us * 1e3)) +
                             capture_time_);
  }
  if (wedge_at_ && call == *wedge_at_) {
    wedged_ = true;
    changed_.notify_all();
    changed_.wait(lock, [this] { return released_; });
  }
  if (lose_from_ && call >= *lose_from_) {
    opens_fail_ = true;
    return Error{ErrorCode::kHardware, "camera lost: control-lost (scripted)"};
  }
  return std::nullopt;
}

void ScriptedCameras::loseAtCall(int call) {
  const std::lock_guard lock(mutex_);
  lose_from_ = call;
}

void ScriptedCameras::failOpens() {
  const std::lock_guard lock(mutex_);
  opens_fail_ = true;
}

void ScriptedCameras::heal() {
  const std::lock_guard lock(mutex_);
  lose_from_.reset();
  opens_fail_ = false;
}

void ScriptedCameras::wedgeAtCall(int call) {
  const std::lock_guard lock(mutex_);
  wedge_at_ = call;
}

void ScriptedCameras::waitUntilWedged() {
  std::unique_lock lock(mutex_);
  changed_.wait(lock, [this] { return wedged_; });
}

void ScriptedCameras::release() {
  const std::lock_guard lock(mutex_);
  released_ = true;
  changed_.notify_all();
}

void ScriptedCameras::takeExposureTime(ManualClock& clock) {
  const std::lock_guard lock(mutex_);
  exposure_clock_ = &clock;
}

void ScriptedCameras::onCapture(std::function<void()> hook) {
  const std::lock_guard lock(mutex_);
  capture_hook_ = std::move(hook);
}

void ScriptedCameras::takeCaptureTime(ManualClock& clock, std::chrono::nanoseconds per_capture) {
  const std::lock_guard lock(mutex_);
  exposure_clock_ = &clock;
  capture_time_ = per_capture;
}

}  // namespace glarecam::testing
