// glarecam.calibration/1: parsing, writing, merging parts, and the checks before a calibration
// is used for a stack (camera serial, age).
#include "calibration/calibration_file.h"

#include <gtest/gtest.h>

#include "core/stack_io.h"
#include "support/test_support.h"

namespace glarecam {
namespace {

namespace fs = std::filesystem;
using calibration::CalibrationDocument;
using json = nlohmann::json;

CalibrationDocument part(const std::string& name, json values, const std::string& serial = "S1") {
  CalibrationDocument document;
  document.camera = {.model = "M", .serial = serial, .pixel_format = "Mono12"};
  document.values = std::move(values);
  document.parts[name] = {
      .measured_at = "2026-06-21T10:00:00Z", .method = "test", .inputs = {"stacks/" + name}};
  return document;
}

const json kIntrinsics = {{"fx", 1000}, {"fy", 1000}, {"cx", 319.5}, {"cy", 239.5}};

TEST(CalibrationFile, WritesAndReadsBackEveryField) {
  testing::TempDir dir;
  const CalibrationDocument written = part(
      "dark",
      {{"black_level_dn", 64.2}, {"dark_frame", "dark.exr"}, {"dark", {{"hot_pixel_count", 3}}}});
  ASSERT_TRUE(calibration::writeCalibrationDocument(dir.path() / "dark.json", written));
  const auto read = calibration::readCalibrationDocument(dir.path() / "dark.json");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->camera.serial, "S1");
  EXPECT_EQ(read->camera.pixel_format, "Mono12");
  EXPECT_EQ(read->values, written.values);
  ASSERT_EQ(read->parts.count("dark"), 1u);
  EXPECT_EQ(read->parts.at("dark").inputs, std::vector<std::string>{"stacks/dark"});
  EXPECT_EQ(toJson(*read)["schema"], "glarecam.calibration/1");
}

TEST(CalibrationFile, BadFilesAreRefusedNamingTheField) {
  const std::pair<json, std::string> cases[] = {
      {json::array(), "the document must be an object, not []"},
      {{{"schema", "glarecam.calibration/9"}}, "is not supported"},
      {{{"schema", "glarecam.calibration/1"}, {"camera", 3}}, "camera must be an object"},
      {{{"schema", "glarecam.calibration/1"}, {"parts", {{"dark", {{"method", "x"}}}}}},
       "parts.dark.measured_at is missing"},
      {{{"schema", "glarecam.calibration/1"}, {"flat_field", "../flat.exr"}},
       "flat_field must be a relative path inside"},
      {{{"schema", "glarecam.calibration/1"}, {"flat_field", 7}},
       "flat_field must be a relative path inside"},
  };
  for (const auto& [document, message] : cases) {
    const auto parsed = calibration::parseCalibrationDocument(document, "cal.json");
    ASSERT_FALSE(parsed) << document;
    EXPECT_NE(parsed.error().message.find("cal.json: "), std::string::npos);
    EXPECT_NE(parsed.error().message.find(message), std::string::npos) << parsed.error().message;
  }
}

TEST(CalibrationFile, MergedPartsMakeABlockAStackAccepts) {
  testing::TempDir dir;
  const CalibrationDocument parts[] = {
      part("dark", {{"black_level_dn", 64}}),
      part("linearity", {{"saturation_dn", 3900}}),
      part("luminance", {{"luminance_factor", 1500}, {"luminance_factor_u", 20}}),
      part("intrinsics", {{"intrinsics", kIntrinsics}}),
      part("dark", {{"black_level_dn", 63.5}}),  // a newer dark part
  };
  const fs::path directories[] = {dir.path() / "1.json", dir.path() / "2.json",
                                  dir.path() / "3.json", dir.path() / "4.json",
                                  dir.path() / "5.json"};
  std::vector<std::string> warnings;
  const auto merged = calibration::mergeCalibrationDocuments(parts, directories, warnings);
  ASSERT_TRUE(merged) << merged.error().message;
  EXPECT_EQ(merged->values["black_level_dn"], 63.5);
  EXPECT_EQ(merged->parts.size(), 4u);
  EXPECT_EQ(warnings.size(), 2u);  // the value and the part replaced
  const auto block = calibration::calibrationBlock(*merged, "rig.json");
  ASSERT_TRUE(block) << block.error().message;
  EXPECT_EQ(block->luminance_factor, 1500);

  // Written, it is accepted where a stack's calibration block is.
  ASSERT_TRUE(calibration::writeCalibrationDocument(dir.path() / "rig.json", *merged));
  const auto read = readCalibrationFile(dir.path() / "rig.json");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->black_level_dn, 63.5);
  EXPECT_EQ(read->source["camera"]["serial"], "S1");
}

TEST(CalibrationFile, AnIncompleteCalibrationNamesTheMissingParts) {
  const auto block =
      calibration::calibrationBlock(part("dark", {{"black_level_dn", 64}}), "d.json");
  ASSERT_FALSE(block);
  EXPECT_NE(block.error().message.find("no saturation_dn (calibrate linearity), luminance_factor "
                                       "(calibrate luminance), intrinsics (calibrate intrinsics)"),
            std::string::npos)
      << block.error().message;
}

TEST(CalibrationFile, PartsOfDifferentCamerasDoNotMerge) {
  testing::TempDir dir;
  const CalibrationDocument parts[] = {part("dark", {{"black_level_dn", 64}}, "S1"),
                                       part("flat", {{"saturation_dn", 4000}}, "S2")};
  const fs::path directories[] = {dir.path() / "a.json", dir.path() / "b.json"};
  std::vector<std::string> warnings;
  const auto merged = calibration::mergeCalibrationDocuments(parts, directories, warnings);
  ASSERT_FALSE(merged);
  EXPECT_NE(merged.error().message.find("b.json: camera serial \"S2\" differs from \"S1\""),
            std::string::npos)
      << merged.error().message;
}

// A flat field or intrinsics made at another size than the rest would be wrong for every stack:
// parts record their frames' size, and the merge refuses parts (or intrinsics) that disagree,
// naming both files.
TEST(CalibrationFile, PartsOfDifferentSizesDoNotMerge) {
  testing::TempDir dir;
  CalibrationDocument flat = part("flat", {{"flat_field", "flat.exr"}});
  flat.parts["flat"].width = 320;
  flat.parts["flat"].height = 256;
  ASSERT_TRUE(calibration::writeCalibrationDocument(dir.path() / "flat.json", flat));
  const auto read = calibration::readCalibrationDocument(dir.path() / "flat.json");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->parts.at("flat").width, 320);
  EXPECT_EQ(read->parts.at("flat").height, 256);

  json intrinsics = kIntrinsics;
  intrinsics["width"] = 640;
  intrinsics["height"] = 480;
  // The intrinsics' own recorded size counts even in a part written before parts had one.
  const CalibrationDocument parts[] = {*read, part("intrinsics", {{"intrinsics", intrinsics}})};
  const fs::path files[] = {dir.path() / "flat.json", dir.path() / "intrinsics.json"};
  std::vector<std::string> warnings;
  const auto merged = calibration::mergeCalibrationDocuments(parts, files, warnings);
  ASSERT_FALSE(merged);
  EXPECT_EQ(merged.error().code, ErrorCode::kBadInput);
  EXPECT_NE(
      merged.error().message.find((dir.path() / "intrinsics.json").string() +
                                  ": the intrinsics was measured at 640x480, but part flat of " +
                                  (dir.path() / "flat.json").string() + " at 320x256"),
      std::string::npos)
      << merged.error().message;

  intrinsics["width"] = 320;
  intrinsics["height"] = 256;
  const CalibrationDocument agreeing[] = {*read, part("intrinsics", {{"intrinsics", intrinsics}})};
  EXPECT_TRUE(calibration::mergeCalibrationDocuments(agreeing, files, warnings));

  const json bad_size = {
      {"schema", "glarecam.calibration/1"},
      {"parts",
       {{"flat", {{"measured_at", "2026-06-21T10:00:00Z"}, {"method", "x"}, {"width", 320}}}}}};
  const auto half = calibration::parseCalibrationDocument(bad_size, "cal.json");
  ASSERT_FALSE(half);
  EXPECT_NE(half.error().message.find("parts.flat gives width and height together or neither"),
            std::string::npos)
      << half.error().message;
}

TEST(CalibrationFile, MergeCopiesTheReferencedImagesBesideTheResult) {
  testing::TempDir dir;
  fs::create_directories(dir.path() / "parts");
  testing::writeText(dir.path() / "parts" / "flat-flat.exr", "not really an EXR");
  const CalibrationDocument parts[] = {part("flat", {{"flat_field", "flat-flat.exr"}})};
  const fs::path directories[] = {dir.path() / "parts" / "flat.json"};
  std::vector<std::string> warnings;
  auto merged = calibration::mergeCalibrationDocuments(parts, directories, warnings);
  ASSERT_TRUE(merged) << merged.error().message;
  fs::create_directories(dir.path() / "rig");
  const auto attached = calibration::attachFiles(*merged, dir.path() / "rig");
  ASSERT_TRUE(attached) << attached.error().message;
  EXPECT_EQ(merged->values["flat_field"], "flat-flat.exr");
  EXPECT_TRUE(fs::exists(dir.path() / "rig" / "flat-flat.exr"));
}

Calibration usable(const std::string& serial, const std::string& measured_at) {
  Calibration calibration;
  calibration.source = {{"camera", {{"serial", serial}}},
                        {"parts", {{"dark", {{"measured_at", measured_at}, {"method", "m"}}}}}};
  return calibration;
}

StackManifest stackOf(const std::string& serial) {
  StackManifest manifest;
  manifest.source = {{"camera", {{"serial", serial}}}};
  return manifest;
}

TEST(CalibrationUse, AnotherCamerasCalibrationIsRefusedUnlessForced) {
  const calibration::CalibrationUseOptions today{
      .today = std::chrono::sys_days(std::chrono::year(2026) / 7 / 1)};
  std::vector<std::string> warnings;
  const auto refused = calibration::checkCalibrationUse(usable("S1", "2026-06-21T10:00:00Z"),
                                                        stackOf("S2"), "cal.json", today, warnings);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("cal.json: made for camera serial S1, but the stack was "
                                         "taken with serial S2 (--force-calibration"),
            std::string::npos)
      << refused.error().message;
  auto forced = today;
  forced.force = true;
  EXPECT_TRUE(calibration::checkCalibrationUse(usable("S1", "2026-06-21T10:00:00Z"), stackOf("S2"),
                                               "cal.json", forced, warnings));
  EXPECT_EQ(warnings.size(), 1u);
  warnings.clear();
  // Same serial, or either unknown: used without a word.
  EXPECT_TRUE(calibration::checkCalibrationUse(usable("S1", "2026-06-21"), stackOf("S1"),
                                               "cal.json", today, warnings));
  EXPECT_TRUE(calibration::checkCalibrationUse(usable("", "2026-06-21"), stackOf("S1"), "cal.json",
                                               today, warnings));
  EXPECT_TRUE(warnings.empty());
}

TEST(CalibrationUse, OldPartsAreWarnedAbout) {
  const calibration::CalibrationUseOptions options{
      .max_age_days = 365, .today = std::chrono::sys_days(std::chrono::year(2026) / 7 / 1)};
  std::vector<std::string> warnings;
  ASSERT_TRUE(calibration::checkCalibrationUse(usable("S1", "2025-06-30T08:00:00Z"), stackOf("S1"),
                                               "cal.json", options, warnings));
  ASSERT_EQ(warnings.size(), 1u);
  EXPECT_NE(warnings[0].find("part dark was measured 366 days ago"), std::string::npos)
      << warnings[0];
  warnings.clear();
  ASSERT_TRUE(calibration::checkCalibrationUse(usable("S1", "2025-07-01"), stackOf("S1"),
                                               "cal.json", options, warnings));
  EXPECT_TRUE(warnings.empty());  // 365 days: not older than the limit
}

}  // namespace
}  // namespace glarecam
