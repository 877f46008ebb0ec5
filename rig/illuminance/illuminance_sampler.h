// The source illuminance of one bracket: the instrument read repeatedly from the bracket's start
// to its end on a thread of its own (no disk I/O; the camera's thread is not held up), then
// summarised as the manifest's `source` block (origin `sensor`):
//
//   E         the mean of the readings
//   spread_lx their standard deviation (0 for one reading), samples their number n
//   u(E)      √((spread/√n)² + (u_instrument·E)² + (u_efficacy·E)²): the scatter of the mean, and
//             the instrument's and the efficacy's relative uncertainties, which do not average
//             out (every reading shares them)
//
// A source is recorded only from readings requested at or after the bracket's start: a reading
// older than the bracket (stale) is never used. Any failed read during the bracket (a timeout,
// an exception reply, a value out of range, a lost connection) means no source for that stack,
// with the first failure as the reason: never a wrong number. At least one reading is always
// attempted, however short the bracket.
#pragma once

#include <chrono>
#include <mutex>
#include <optional>
#include <span>
#include <thread>
#include <vector>

#include "core/error.h"
#include "core/source_illuminance.h"
#include "rig/illuminance/illuminance_instrument.h"

namespace glarecam::rig {

// The readings of a bracket that began at `bracket_start` as its source (see above); kHardware
// "stale" when none was requested at or after it.
Result<SourceIlluminance> summariseReadings(std::span<const IlluminanceReading> readings,
                                            const IlluminanceInstrumentInfo& info,
                                            std::chrono::steady_clock::time_point bracket_start);

class IlluminanceSampler {
 public:
  IlluminanceSampler(IlluminanceInstrument& instrument, std::chrono::milliseconds interval);
  ~IlluminanceSampler();  // stops a sampling still running
  IlluminanceSampler(const IlluminanceSampler&) = delete;
  IlluminanceSampler& operator=(const IlluminanceSampler&) = delete;

  // The bracket starts: readings from now on (the previous bracket's are forgotten).
  void start();
  // The bracket has ended: waits for the read in flight, then the source, or why there is none.
  Result<SourceIlluminance> stop();

 private:
  void sample(std::stop_token stop);

  IlluminanceInstrument& instrument_;
  std::chrono::milliseconds interval_;
  std::chrono::steady_clock::time_point bracket_start_{};
  std::mutex mutex_;
  std::vector<IlluminanceReading> readings_;
  std::optional<Error> failure_;
  std::jthread thread_;
};

}  // namespace glarecam::rig
