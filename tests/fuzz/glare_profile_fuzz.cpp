// libFuzzer target: a module's glare profile (glarecam.glare-profile/1, docs/glare-profile.md),
// read as the hazard calculation reads it, then asked what the calculation asks of it at α
// across and beyond its range (interpolation between null and present rows).
#include <cstddef>
#include <cstdint>

#include "core/json.h"
#include "hazard/profile_table.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glarecam::fuzz::silenceLogging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto document = glarecam::parseJsonText(glarecam::fuzz::asText(data, size), "profile.json");
  if (!document) return 0;
  const auto table = glarecam::hazard::ProfileTable::fromJson(*document, "profile.json");
  if (!table) return 0;
  for (double alpha_deg : {-1.0, 0.0, 0.5, 12.25, 45.0, 79.9, 80.0, 80.5, 89.0}) {
    (void)table->at(alpha_deg);
    (void)table->luminancesAt(alpha_deg);
  }
  (void)table->glaresWithin(10.0, 70.0);
  return 0;
}
