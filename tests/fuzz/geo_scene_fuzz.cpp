// libFuzzer target: a geographic hazard scene (docs/hazard.md, "Geographic scenes") as
// `glarecam hazard` reads it: KML when the input starts like XML (parseKmlScene, pugixml), else
// GeoJSON (parseGeoJsonScene), both through PROJ into the scene's east–north–up frame.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "core/json.h"
#include "hazard/geo_scene.h"
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  glarecam::fuzz::silenceLogging();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = glarecam::fuzz::asText(data, size);
  if (text.find_first_not_of(" \t\r\n") != std::string_view::npos &&
      text[text.find_first_not_of(" \t\r\n")] == '<') {
    (void)glarecam::hazard::parseKmlScene(text, "scene.kml", glarecam::fuzz::scratchDirectory());
    return 0;
  }
  const auto document = glarecam::parseJsonText(text, "scene.geojson");
  if (!document) return 0;
  (void)glarecam::hazard::parseGeoJsonScene(*document, "scene.geojson",
                                            glarecam::fuzz::scratchDirectory());
  return 0;
}
