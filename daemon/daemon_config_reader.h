// Reading the daemon's sections of a rig config (daemon_config.h), for rig_config.cpp.
#pragma once

#include <toml++/toml.h>

#include <filesystem>

#include "core/error.h"
#include "daemon/daemon_config.h"

namespace glarecam::daemon {

// [capture], [schedule], [output] and [faults] of `root` (their defaults when absent); an output
// root relative to the config file's directory. `has_site`: the config has a [site] (the
// α-targets schedule needs the sun).
Result<DaemonConfig> readDaemonSections(const std::filesystem::path& file, const toml::table& root,
                                        bool has_site);

}  // namespace glarecam::daemon
