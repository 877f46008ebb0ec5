// glarecamd's command line: options in one struct, parsed and checked in one place, then the
// daemon (daemon/capture_daemon.h) runs until SIGTERM. Exit statuses: 0 stopped cleanly,
// 2 bad usage, 78 (EX_CONFIG, sysexits.h) an invalid config, which systemd must not restart on
// (RestartPreventExitStatus=78), 1 anything else (the camera lost for good).
#pragma once

namespace glarecam::apps {

inline constexpr int kExitConfig = 78;

int runGlarecamd(int argc, char** argv);

}  // namespace glarecam::apps
