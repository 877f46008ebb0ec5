#include "daemon/hardware/illuminance_session.h"

#include <spdlog/spdlog.h>

#include "daemon/hardware/simulated_rig.h"

namespace glarecam::daemon {

IlluminanceSession::IlluminanceSession() = default;
IlluminanceSession::~IlluminanceSession() { close(); }

void IlluminanceSession::close() {
  sampler_.reset();  // stops a sampling still running, before its instrument goes
  opened_ = {};
}

void IlluminanceSession::open(const rig::RigConfig& rig, DaemonState& state) {
  close();
  config_ = rig.illuminance;
  site_ = rig.site;
  state.illuminance_fault.clear();
  state.illuminance_instrument = config_ ? config_->description() : std::string();
  if (config_) openInstrument(state);
}

void IlluminanceSession::openInstrument(DaemonState& state) {
  auto opened = rig::openIlluminance(*config_);
  if (!opened) {
    failed(opened.error(), state);
    return;
  }
  opened_ = std::move(*opened);
  state.illuminance_instrument = opened_.instrument->info().description;
  sampler_ =
      std::make_unique<rig::IlluminanceSampler>(*opened_.instrument, config_->sample_interval);
}

void IlluminanceSession::startBracket(UtcTime utc, DaemonState& state) {
  if (!config_) return;
  if (!opened_.instrument) openInstrument(state);
  if (!sampler_) return;
  if (opened_.simulator && site_) {
    // The simulated sun: 0 (no direct light, so no source) while it is down.
    const auto lx = simulatedSourceIlluminance(utc, *site_);
    rig::setSimulatedIlluminance(opened_, lx ? *lx : 0.0);
  }
  sampler_->start();
}

std::optional<SourceIlluminance> IlluminanceSession::finishBracket(UtcTime utc,
                                                                   DaemonState& state) {
  if (!sampler_) return std::nullopt;
  auto source = sampler_->stop();
  if (!source) {
    failed(source.error(), state);
    return std::nullopt;
  }
  if (!state.illuminance_fault.empty())
    spdlog::info("glarecamd: illuminance: {} reads again", state.illuminance_instrument);
  state.illuminance_fault.clear();
  state.last_source_illuminance = *source;
  state.last_illuminance_time = utc;
  return *source;
}

void IlluminanceSession::failed(const Error& error, DaemonState& state) {
  ++state.illuminance_failures;
  if (error.message != state.illuminance_fault)
    spdlog::warn("glarecamd: illuminance: {}; the stacks are unreferred until it reads",
                 error.message);
  state.illuminance_fault = error.message;
}

}  // namespace glarecam::daemon
