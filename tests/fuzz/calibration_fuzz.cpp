// libFuzzer target: a calibration file (glarecam.calibration/1, docs/calibration.md), read both
// as the calibration tools read it (readCalibrationDocument) and as a stack's calibration_file
// is read (readCalibrationFile).
#include <cstddef>
#include <cstdint>

#include "calibration/calibration_file.h"
#include "core/json.h"
#include "core/stack_io.h"
#include "core/stack_manifest.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glarecam::fuzz::silenceLogging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = glarecam::fuzz::writeScratchFile("calibration.json", data, size);
  const auto document = glarecam::calibration::readCalibrationDocument(path);
  if (document) (void)glarecam::jsonText(glarecam::calibration::toJson(*document));
  (void)glarecam::readCalibrationFile(path);
  return 0;
}
