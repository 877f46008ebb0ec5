// libFuzzer target: the inclinometer's zero-offset file (written by `glarecam inclinometer
// zero`, read by glarecamd at start), read by readZeroOffset().
#include <cstddef>
#include <cstdint>

#include "rig/inclinometer/zero_offset_file.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glarecam::fuzz::silenceLogging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = glarecam::fuzz::writeScratchFile("zero-offset.json", data, size);
  (void)glarecam::rig::readZeroOffset(path);
  return 0;
}
