// libFuzzer target: the rig's config file (TOML: the rig's sections and glarecamd's, docs/
// operator.md), read by readConfig() as glarecamd reads it at start and on SIGHUP.
#include <cstddef>
#include <cstdint>

#include "daemon/daemon_config.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glarecam::fuzz::silenceLogging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = glarecam::fuzz::writeScratchFile("glarecam.toml", data, size);
  (void)glarecam::daemon::readConfig(path);
  (void)glarecam::daemon::readRigConfig(path);
  return 0;
}
