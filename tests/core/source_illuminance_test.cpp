#include "core/source_illuminance.h"

#include <gtest/gtest.h>

#include <limits>

#include "core/stack_manifest.h"

namespace glarecam {
namespace {

using nlohmann::json;

json manifestWithSource(json source) {
  json document = json::parse(R"({
    "schema": "glarecam.stack/1",
    "calibration": {"black_level_dn": 64, "saturation_dn": 4000, "luminance_factor": 1500,
                    "intrinsics": {"fx": 2400, "fy": 2400, "cx": 1223.5, "cy": 1023.5}},
    "frames": [{"file": "frame-00.png", "exposure_us": 5.0}]
  })");
  document["source"] = std::move(source);
  return document;
}

TEST(SourceIlluminance, ReadsTheDocumentedBlockAndWritesItBack) {
  // The example of docs/stack-format.md.
  const json block = json::parse(R"json({"illuminance_lx": 92500, "illuminance_u_lx": 2800,
      "origin": "sensor", "instrument": "pyrheliometer modbus:/dev/ttyUSB0@1 (W/m², 93 lm/W)",
      "samples": 6, "spread_lx": 310})json");
  auto manifest = parseManifest(manifestWithSource(block), "stack.json");
  ASSERT_TRUE(manifest) << manifest.error().message;
  ASSERT_TRUE(manifest->source_illuminance);
  const SourceIlluminance& source = *manifest->source_illuminance;
  EXPECT_EQ(source.illuminance_lx, 92500);
  EXPECT_EQ(source.illuminance_u_lx, 2800);
  EXPECT_EQ(source.origin, IlluminanceOrigin::kSensor);
  EXPECT_EQ(source.samples, 6);
  EXPECT_EQ(source.spread_lx, 310);
  EXPECT_EQ(toJson(*manifest).at("source"), block);
  EXPECT_EQ(describe(source), "92.5 ± 2.8 klx (sensor)");
}

TEST(SourceIlluminance, AStackWithoutSourceIsUnreferred) {
  json document = manifestWithSource(nullptr);
  document.erase("source");
  auto manifest = parseManifest(document, "stack.json");
  ASSERT_TRUE(manifest) << manifest.error().message;
  EXPECT_FALSE(manifest->source_illuminance);
  EXPECT_FALSE(toJson(*manifest).contains("source"));
}

TEST(SourceIlluminance, RefusesBadBlocksNamingTheField) {
  struct Case {
    json block;
    std::string message;
  };
  const Case cases[] = {
      {{{"illuminance_lx", -5}, {"origin", "given"}}, "stack.json: source.illuminance_lx"},
      {{{"illuminance_lx", 0}, {"origin", "given"}}, "must be finite and positive"},
      {{{"illuminance_lx", 250000}, {"origin", "given"}}, "more than any sun gives"},
      {{{"illuminance_lx", "bright"}, {"origin", "given"}},
       "source.illuminance_lx must be a number"},
      {{{"illuminance_lx", 90000}, {"origin", "moon"}}, "source.origin"},
      {{{"illuminance_lx", 90000}}, "source.origin is missing"},
      {{{"illuminance_lx", 90000}, {"origin", "given"}, {"illuminance_u_lx", -1}},
       "source.illuminance_u_lx"},
      {{{"illuminance_lx", 90000}, {"origin", "sensor"}, {"samples", 0}}, "source.samples"},
      {json("92500"), "source must be an object"},
  };
  for (const Case& c : cases) {
    auto manifest = parseManifest(manifestWithSource(c.block), "stack.json");
    ASSERT_FALSE(manifest) << c.block.dump();
    EXPECT_EQ(manifest.error().code, ErrorCode::kBadInput);
    EXPECT_NE(manifest.error().message.find(c.message), std::string::npos)
        << manifest.error().message;
  }
}

TEST(SourceIlluminance, ParsesWhatAnOperatorTypes) {
  for (const char* text : {"92500±2800", "92500+-2800", "92500 +/- 2800", " 92500 ± 2800 "}) {
    auto source = parseGivenIlluminance(text, "--source-illuminance");
    ASSERT_TRUE(source) << text << ": " << source.error().message;
    EXPECT_EQ(source->illuminance_lx, 92500) << text;
    EXPECT_EQ(source->illuminance_u_lx, 2800) << text;
    EXPECT_EQ(source->origin, IlluminanceOrigin::kGiven);
  }
  auto bare = parseGivenIlluminance("60000", "--source-illuminance");
  ASSERT_TRUE(bare);
  EXPECT_EQ(bare->illuminance_u_lx, 0);
  EXPECT_NEAR(bare->relativeUncertainty(), 0, 0);
}

TEST(SourceIlluminance, RefusesWhatNoSunGivesNamingWhere) {
  const std::pair<const char*, const char*> cases[] = {
      {"-5", "finite and positive"},
      {"0", "finite and positive"},
      {"nan", "finite and positive"},
      {"inf", "finite and positive"},
      {"200000", "more than any sun"},
      {"92.5klx", "expected an illuminance"},
      {"", "expected an illuminance"},
      {"92500±", "uncertainty after ± is missing"},
      {"92500±-3", "must be a number >= 0"},
      {"92500±x", "must be a number >= 0"},
      {"900±1000", "as large as the illuminance"},
  };
  for (const auto& [text, message] : cases) {
    auto source = parseGivenIlluminance(text, "--source-illuminance");
    ASSERT_FALSE(source) << text;
    EXPECT_EQ(source.error().code, ErrorCode::kBadInput);
    EXPECT_NE(source.error().message.find("--source-illuminance \""), std::string::npos)
        << source.error().message;
    EXPECT_NE(source.error().message.find(message), std::string::npos)
        << text << ": " << source.error().message;
  }
}

TEST(SourceIlluminance, ChecksAReference) {
  EXPECT_TRUE(checkReferenceIlluminance(kDefaultReferenceIlluminanceLx, "x"));
  EXPECT_FALSE(checkReferenceIlluminance(0, "--reference-illuminance"));
  EXPECT_FALSE(checkReferenceIlluminance(std::numeric_limits<double>::quiet_NaN(), "x"));
  EXPECT_FALSE(checkReferenceIlluminance(1e6, "x"));
}

TEST(SourceIlluminance, OriginWordsRoundTrip) {
  for (IlluminanceOrigin origin :
       {IlluminanceOrigin::kSensor, IlluminanceOrigin::kGiven, IlluminanceOrigin::kClearSky})
    EXPECT_EQ(originFromWord(originWord(origin)), origin);
  EXPECT_EQ(originWord(IlluminanceOrigin::kClearSky), "clear_sky");
  EXPECT_FALSE(originFromWord("unreferred"));
}

}  // namespace
}  // namespace glarecam
