// libFuzzer target: a GenICam preset file (`[camera] genicam_preset`, docs/operator.md), read
// by readGenicamPreset() before it is handed to the camera.
#include <cstddef>
#include <cstdint>

#include "daemon/daemon_config.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glarecam::fuzz::silenceLogging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = glarecam::fuzz::writeScratchFile("preset.txt", data, size);
  (void)glarecam::daemon::readGenicamPreset(path);
  return 0;
}
