#include "rig/illuminance/illuminance_sampler.h"

#include <fmt/format.h>

#include <cmath>
#include <condition_variable>

namespace glarecam::rig {

Result<SourceIlluminance> summariseReadings(std::span<const IlluminanceReading> readings,
                                            const IlluminanceInstrumentInfo& info,
                                            std::chrono::steady_clock::time_point bracket_start) {
  double sum = 0;
  int n = 0;
  int stale = 0;
  for (const IlluminanceReading& reading : readings) {
    if (reading.requested_at < bracket_start) {
      ++stale;
      continue;
    }
    sum += reading.illuminance_lx;
    ++n;
  }
  if (n == 0)
    return hardwareError(fmt::format(
        "{}: no reading from within the bracket ({} stale, older than its start): no source "
        "illuminance recorded",
        info.description, stale));
  const double mean = sum / n;
  double squares = 0;
  for (const IlluminanceReading& reading : readings)
    if (reading.requested_at >= bracket_start)
      squares += (reading.illuminance_lx - mean) * (reading.illuminance_lx - mean);
  const double spread = n > 1 ? std::sqrt(squares / (n - 1)) : 0.0;
  const double u_mean = spread / std::sqrt(static_cast<double>(n));
  const double u_instrument = info.instrument_u_rel * mean;
  const double u_efficacy = info.efficacy_u_rel * mean;
  return SourceIlluminance{
      .illuminance_lx = mean,
      .illuminance_u_lx =
          std::sqrt(u_mean * u_mean + u_instrument * u_instrument + u_efficacy * u_efficacy),
      .origin = IlluminanceOrigin::kSensor,
      .instrument = info.description,
      .samples = n,
      .spread_lx = spread};
}

IlluminanceSampler::IlluminanceSampler(IlluminanceInstrument& instrument,
                                       std::chrono::milliseconds interval)
    : instrument_(instrument), interval_(interval) {}

IlluminanceSampler::~IlluminanceSampler() {
  if (thread_.joinable()) {
    thread_.request_stop();
    thread_.join();
  }
}

void IlluminanceSampler::start() {
  if (thread_.joinable()) {
    thread_.request_stop();
    thread_.join();
  }
  readings_.clear();
  failure_.reset();
  bracket_start_ = std::chrono::steady_clock::now();
  thread_ = std::jthread([this](std::stop_token stop) { sample(stop); });
}

void IlluminanceSampler::sample(std::stop_token stop) {
  std::mutex pause_mutex;
  std::condition_variable_any pause;
  do {
    auto reading = instrument_.read();
    {
      std::lock_guard lock(mutex_);
      if (!reading) {
        failure_ = reading.error();
        return;  // the bracket gets no source: nothing more to read
      }
      readings_.push_back(*reading);
    }
    std::unique_lock lock(pause_mutex);
    pause.wait_for(lock, stop, interval_, [] { return false; });
  } while (!stop.stop_requested());
}

Result<SourceIlluminance> IlluminanceSampler::stop() {
  if (!thread_.joinable()) return fail(ErrorCode::kInternal, "illuminance sampler: not started");
  thread_.request_stop();
  thread_.join();
  std::lock_guard lock(mutex_);
  if (failure_) return std::unexpected(*failure_);
  return summariseReadings(readings_, instrument_.info(), bracket_start_);
}

}  // namespace glarecam::rig
