#include "core/stack_manifest.h"

#include <gtest/gtest.h>

namespace glarecam {
namespace {

using nlohmann::json;

json minimalManifest() {
  return json::parse(R"({
    "schema": "glarecam.stack/1",
    "calibration": {"black_level_dn": 64, "saturation_dn": 4000, "luminance_factor": 1500,
                    "intrinsics": {"fx": 2400, "fy": 2400, "cx": 1223.5, "cy": 1023.5}},
    "frames": [{"file": "frame-00.png", "exposure_us": 5.0}]
  })");
}

TEST(StackManifest, FillsDocumentedDefaults) {
  auto manifest = parseManifest(minimalManifest(), "stack.json");
  ASSERT_TRUE(manifest) << manifest.error().message;
  const FrameSpec& frame = manifest->frames.at(0);
  EXPECT_EQ(frame.gain_db, 0.0);
  EXPECT_FALSE(frame.f_number.has_value());  // = reference_f_number, resolved by radiometry
  EXPECT_EQ(frame.nd_transmission, 1.0);
  EXPECT_FALSE(manifest->alpha_deg.has_value());
  ASSERT_TRUE(manifest->calibration);
  for (double k : manifest->calibration->intrinsics.distortion) EXPECT_EQ(k, 0.0);
  EXPECT_FALSE(manifest->calibration->noise.has_value());
}

TEST(StackManifest, CalibrationMayBeAPath) {
  json document = minimalManifest();
  document["calibration"] = "../calib/rig1.json";
  auto manifest = parseManifest(document, "stack.json");
  ASSERT_TRUE(manifest) << manifest.error().message;
  EXPECT_EQ(manifest->calibration_path, "../calib/rig1.json");
  EXPECT_FALSE(manifest->calibration.has_value());
}

TEST(StackManifest, UnknownFieldsSurviveARoundTrip) {
  json document = minimalManifest();
  document["vendor_extension"] = {{"lens", "Kowa 8 mm"}};
  document["frames"][0]["sensor_temperature_c"] = 41.5;
  document["calibration"]["lab"] = "SPF";
  document["calibration"]["intrinsics"]["rms_px"] = 0.21;
  auto manifest = parseManifest(document, "stack.json");
  ASSERT_TRUE(manifest);
  manifest->alpha_deg = 55.0;
  json written = toJson(*manifest);
  EXPECT_EQ(written["vendor_extension"]["lens"], "Kowa 8 mm");
  EXPECT_EQ(written["frames"][0]["sensor_temperature_c"], 41.5);
  EXPECT_EQ(written["calibration"]["lab"], "SPF");
  EXPECT_EQ(written["calibration"]["intrinsics"]["rms_px"], 0.21);
  EXPECT_EQ(written["alpha_deg"], 55.0);
  auto reparsed = parseManifest(written, "stack.json");
  ASSERT_TRUE(reparsed) << reparsed.error().message;
  EXPECT_EQ(reparsed->frames.at(0).exposure_us, 5.0);
}

TEST(StackManifest, ErrorsNameTheFileAndTheField) {
  json document = minimalManifest();
  document["frames"][0]["gain_db"] = "high";
  auto manifest = parseManifest(document, "/data/s1/stack.json");
  ASSERT_FALSE(manifest);
  EXPECT_EQ(manifest.error().code, ErrorCode::kBadInput);
  EXPECT_EQ(manifest.error().message,
            "/data/s1/stack.json: frames[0].gain_db must be a number, not \"high\"");
}

TEST(StackManifest, RefusesPathsThatEscape) {
  EXPECT_TRUE(isContainedRelativePath("frame-00.png"));
  EXPECT_TRUE(isContainedRelativePath("frames/frame-00.png"));
  EXPECT_FALSE(isContainedRelativePath("../frame.png"));
  EXPECT_FALSE(isContainedRelativePath("frames/../../frame.png"));
  EXPECT_FALSE(isContainedRelativePath("/etc/passwd"));
  EXPECT_FALSE(isContainedRelativePath(""));
}

}  // namespace
}  // namespace glarecam
