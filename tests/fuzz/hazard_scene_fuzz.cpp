// libFuzzer target: a hazard scene (glarecam.hazard-scene/1, docs/hazard.md), read by
// parseScene() as `glarecam hazard` reads it. A relative `profile` path resolves in the scratch
// directory, which holds a valid profile named profile.json (seeds/glare_profile/'s, copied at
// start; the seeds name it), so the fuzzer reaches past the scene into the arrays' profiles.
#include <cstddef>
#include <cstdint>
#include <filesystem>

#include "core/json.h"
#include "hazard/scene.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glarecam::fuzz::silenceLogging();
  std::filesystem::copy_file(GLARECAM_FUZZ_SEEDS_DIR "/glare_profile/profile.json",
                             glarecam::fuzz::scratchDirectory() / "profile.json");
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto document = glarecam::parseJsonText(glarecam::fuzz::asText(data, size), "scene.json");
  if (!document) return 0;
  (void)glarecam::hazard::parseScene(*document, "scene.json", glarecam::fuzz::scratchDirectory());
  return 0;
}
