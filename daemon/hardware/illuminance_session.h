// The rig's illuminance instrument in glarecamd ([illuminance], docs/illuminance.md): sampled
// during every bracket (rig/illuminance/illuminance_sampler.h) and recorded as that stack's
// source illuminance (the manifest's `source`, origin `sensor`). The instrument never stops
// capture: when it cannot be opened or read, or a reading is refused (out of range, stale), the
// stack is taken unreferred (its daemon flags say `source_illuminance_unknown`), the failure is
// a warning in the journal (once per distinct message) and the status's illuminance fault, and
// the instrument is tried again at the next bracket. The last value and the fault are the status
// page's and /metrics'.
//
// A simulated instrument (transport "sim", as glarecamd --simulate writes it) is served on
// loopback and read through the same libmodbus backend; before each bracket it is given the
// simulated sun's direct normal illuminance at the bracket's (simulated) time and the rig's site
// (simulatedSourceIlluminance, simulated_rig.h).
#pragma once

#include <memory>
#include <optional>

#include "core/source_illuminance.h"
#include "core/time.h"
#include "daemon/status/daemon_status.h"
#include "rig/illuminance/illuminance_registry.h"
#include "rig/illuminance/illuminance_sampler.h"
#include "rig/rig_config.h"

namespace glarecam::daemon {

class IlluminanceSession {
 public:
  IlluminanceSession();
  ~IlluminanceSession();
  IlluminanceSession(const IlluminanceSession&) = delete;
  IlluminanceSession& operator=(const IlluminanceSession&) = delete;

  // Takes the rig's [illuminance] (none: nothing is sampled) and opens it; a failure is the
  // status's fault, and the next bracket opens it again.
  void open(const rig::RigConfig& rig, DaemonState& state);
  void close();
  bool configured() const { return config_.has_value(); }

  // The bracket starts at `utc` (the daemon's clock: simulated under a time lapse).
  void startBracket(UtcTime utc, DaemonState& state);
  // The bracket has ended: its source, or none (and why, logged and in `state`).
  std::optional<SourceIlluminance> finishBracket(UtcTime utc, DaemonState& state);

 private:
  void openInstrument(DaemonState& state);
  void failed(const Error& error, DaemonState& state);

  std::optional<rig::IlluminanceConfig> config_;
  std::optional<sun::SiteLocation> site_;
  rig::OpenedIlluminance opened_;
  std::unique_ptr<rig::IlluminanceSampler> sampler_;
};

}  // namespace glarecam::daemon
