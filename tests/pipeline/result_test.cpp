// The result document: one type, one writer, one reader. Everything written reads back equal,
// from processed simulated stacks (every status and method the pipeline gives) and from a result
// with every optional field set; the docs' example parses; and what is not a result is refused
// naming the file and the field, never with an exception.
#include "pipeline/result.h"

#include <gtest/gtest.h>

#include <fstream>
#include <limits>
#include <regex>
#include <sstream>

#include "pipeline/process_stack.h"
#include "support/sim_support.h"
#include "support/test_support.h"
#include "tests/pipeline/result_fixture.h"

namespace glarecam::pipeline {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// Read back from its own text, a result equals itself, and its text is unchanged.
void expectRoundTrip(const StackResult& result, const std::string& what) {
  const json written = toJson(result);
  const auto read = resultFromJson(json::parse(jsonText(written)), "result.json");
  ASSERT_TRUE(read) << what << ": " << read.error().message;
  EXPECT_EQ(*read, result) << what;
  EXPECT_EQ(toJson(*read), written) << what;
}

TEST(Result, ProcessedStacksReadBackEqual) {
  testing::TempDir dir;
  // α 65 (the curve's limit, measured ellipses), no α (no limit), a constant threshold with a
  // threshold sweep (some levels below the peak, some above), a saturated top (a lower bound).
  struct Case {
    std::string name;
    capture::SimulationOptions scene;
    ProcessOptions options;
  };
  std::vector<Case> cases;
  cases.push_back({"alpha65", testing::smallScene(65.0), ProcessOptions()});
  cases.push_back({"no-alpha", testing::smallScene(50.0), ProcessOptions()});
  Case thresholds{"thresholds", testing::smallScene(40.0), ProcessOptions()};
  thresholds.options.threshold_cd_m2 = 30'000.0;
  thresholds.options.thresholds_cd_m2 = {1e4, 1e5, 1e7, 1e9};
  cases.push_back(thresholds);
  cases.push_back({"saturated", testing::smallScene(30.0), ProcessOptions()});
  int measured = 0, bounds = 0;
  for (const Case& c : cases) {
    testing::writeSmallStack(dir / c.name, c.scene);
    json manifest = json::parse(testing::readText(dir / c.name / "stack.json"));
    if (c.name == "saturated") {  // the longest frames alone: the top clips (a lower bound)
      const json frames = manifest["frames"];
      manifest["frames"] = json::array({frames[4], frames[5]});
    }
    if (c.name == "no-alpha") manifest.erase("alpha_deg");  // no α: no limit
    testing::writeText(dir / c.name / "stack.json", manifest.dump());
    ProcessOptions options = c.options;
    options.show_progress = false;
    const auto summary = processStack(dir / c.name, options);
    ASSERT_TRUE(summary) << c.name << ": " << summary.error().message;
    expectRoundTrip(summary->result, c.name);
    // What process wrote to disk is what it returned.
    const auto on_disk = readResult(summary->output_directory / kResultFileName);
    ASSERT_TRUE(on_disk) << on_disk.error().message;
    EXPECT_EQ(*on_disk, summary->result) << c.name;
    measured += summary->result.fwhm.ellipse.has_value();
    bounds += summary->result.luminance.isLowerBound();
  }
  // The cases do exercise the ellipses and the bounds.
  EXPECT_GT(measured, 0);
  EXPECT_EQ(bounds, 1);
}

TEST(Result, EveryOptionalFieldReadsBackEqual) {
  StackResult result = testing::minimalResult(5.4e5, 42.5);
  result.alpha_source = "given";
  result.alpha_uncertainty_deg = 0.07;
  result.camera = {{"backend", "sim"}, {"serial", "SIM-0001"}, {"vendor_field", {1, 2}}};
  result.module = "Standard module";
  result.calibration = {
      .origin = "calibration.json",
      .file = "/rig/calibration.json",
      .sha256 = std::string(64, 'a'),
      .camera = {{"model", "M"}},
      .parts =
          std::map<std::string, CalibrationPart>{
              {"dark", {.measured_at = "2026-06-20T10:00:00Z", .method = "mean"}}, {"flat", {}}},
      .id = "0123456789abcdef",
      .luminance_factor = 1500.5,
      .luminance_factor_u = 18.25,
      .noise_model_assumed = true,
      .dark_frame = true,
      .hot_pixels = true};
  ResultLuminance& l = result.luminance;
  l.max_pixel = {611, 511};
  l.max_position_px = {611.25, 510.75};
  l.max_method = PeakMethod::kUpperBound;
  l.max_relative_uncertainty = 0.012;
  l.max_relative_uncertainty_combined = 0.017;
  l.valid_fraction = 0.875;
  l.saturated_pixels = 12;
  l.dark_pixels = 3;
  l.masked_pixels = 150;
  l.median_relative_uncertainty = 0.02;
  l.frames_consistent = false;
  result.frames = {{.file = "frame-00.png", .median_ratio = 1.01, .samples = 900, .agrees = true},
                   {.file = "frame-01.png"}};
  ResultEllipse e;
  e.vertical_deg = 7.5;
  e.horizontal_deg = 4.25;
  e.major_deg = 7.5;
  e.minor_deg = 4.25;
  e.orientation_deg = -89.5;
  e.center_px = {611, 512.5};
  e.center_direction_deg = {-0.25, 30.5};
  e.semi_axes_px = {120.5, 70.25};
  e.solid_angle_sr = 0.008;
  e.fit_rms_px = 0.3;
  e.fit_rms_deg = 0.01;
  e.shape_residual = 0.02;
  e.ellipticity_ok = true;
  e.truncated = true;
  e.regions = 2;
  e.contour_points = 400;
  e.region_pixels = 30'000;
  e.smoothing_radius_px = 3;
  e.vertical_uncertainty_deg = 0.05;
  e.horizontal_uncertainty_deg = 0.04;
  e.orientation_uncertainty_deg = 0.5;
  e.solid_angle_uncertainty_sr = 1e-4;
  e.unweighted_contour_points = 7;
  result.limit = {.limit_cd_m2 = 30'000.0,
                  .mode = LimitMode::kConstant,
                  .status = EllipseStatus::kMeasured,
                  .ellipse = e};
  result.fwhm = {.level_cd_m2 = 2.7e5, .status = EllipseStatus::kMeasured, .ellipse = e};
  result.thresholds = {{.level_cd_m2 = 1e4, .status = EllipseStatus::kFillsImage},
                       {.level_cd_m2 = 1e5, .status = EllipseStatus::kMeasured, .ellipse = e},
                       {.level_cd_m2 = 1e9, .status = EllipseStatus::kBelowLevel}};
  result.contours = std::vector<ResultContour>{
      {ContourKind::kLadder, {.level_cd_m2 = 1e4, .status = EllipseStatus::kFillsImage}},
      {ContourKind::kLadder,
       {.level_cd_m2 = 2.15e4, .status = EllipseStatus::kMeasured, .ellipse = e}},
      {ContourKind::kLimit,
       {.level_cd_m2 = 30'000.0, .status = EllipseStatus::kMeasured, .ellipse = e}},
      {ContourKind::kLadder,
       {.level_cd_m2 = 4.64e4, .status = EllipseStatus::kMeasured, .ellipse = e}},
      {ContourKind::kHalfMaximum,
       {.level_cd_m2 = 2.7e5, .status = EllipseStatus::kMeasured, .ellipse = e}}};
  result.glare = true;
  result.generator = {.name = "glarecam", .version = "9.8.7"};
  expectRoundTrip(result, "every field");
  result.contours = std::vector<ResultContour>{};
  expectRoundTrip(result, "an empty ladder (the maximum below 10 000 cd/m²)");
  // And the least a result holds.
  expectRoundTrip(testing::minimalResult(0.0), "minimal");
}

// The docs' example (docs/process.md, generated from a real run by scripts/doc-examples) is a
// result as the reader takes it.
TEST(Result, TheDocsExampleParses) {
  const fs::path doc = testing::testDataDir().parent_path().parent_path() / "docs" / "process.md";
  const std::string text = testing::readText(doc);
  const std::regex block(
      "<!-- generated: process-result \\(scripts/doc-examples\\) -->\\n```json\\n([^`]*)```");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(text, match, block)) << doc;
  const auto document = parseJsonText(match[1].str(), doc.string());
  ASSERT_TRUE(document) << document.error().message;
  const auto result = resultFromJson(*document, doc.string());
  ASSERT_TRUE(result) << result.error().message;
  EXPECT_TRUE(result->limit.ellipse);
  EXPECT_EQ(toJson(*result), *document);
}

std::string refusal(const json& document) {
  Result<StackResult> read = badInput("not run");
  EXPECT_NO_THROW(read = resultFromJson(document, "r.json"));
  if (read) return "(read)";
  EXPECT_EQ(read.error().code, ErrorCode::kBadInput);
  return read.error().message;
}

TEST(Result, WhatIsNotAResultIsRefusedNamingTheField) {
  const json good = toJson(testing::minimalResult(5e5, 40.0));
  const auto changed = [&](auto change) {
    json document = good;
    change(document);
    return refusal(document);
  };
  EXPECT_EQ(refusal(json::array()), "r.json: the document must be an object, not []");
  EXPECT_EQ(changed([](json& d) { d.erase("schema"); }),
            "r.json: schema is missing (a result's is \"glarecam.result/1\")");
  EXPECT_EQ(changed([](json& d) { d["schema"] = "glarecam.result/2"; }),
            "r.json: schema \"glarecam.result/2\" is not supported (a result's is "
            "\"glarecam.result/1\")");
  // A renamed key fails loudly instead of reading as nothing.
  EXPECT_EQ(changed([](json& d) {
              d["luminance"]["max_cdm2"] = d["luminance"]["max_cd_m2"];
              d["luminance"].erase("max_cd_m2");
            }),
            "r.json: luminance.max_cd_m2 is missing");
  EXPECT_EQ(changed([](json& d) { d["alpha_deg"] = "forty"; }),
            "r.json: alpha_deg must be a number, not \"forty\"");
  EXPECT_EQ(changed([](json& d) { d["alpha_deg"] = 95; }),
            "r.json: alpha_deg 95° is outside [0, 90]");
  EXPECT_EQ(changed([](json& d) {
              d["calibration"] = json::array({1, 2});
            }),
            "r.json: calibration must be an object, not [1,2]");
  EXPECT_EQ(changed([](json& d) { d["camera"] = "sim"; }),
            "r.json: camera must be an object, not \"sim\"");
  EXPECT_EQ(changed([](json& d) { d["luminance"]["max_method"] = "guess"; }),
            "r.json: luminance.max_method \"guess\" is not a peak method");
  EXPECT_EQ(changed([](json& d) { d["luminance"]["max_is_lower_bound"] = true; }),
            "r.json: luminance.max_method \"quadratic_fit\" contradicts max_is_lower/upper_bound");
  EXPECT_EQ(changed([](json& d) { d["luminance"]["frames_consistent"] = "yes"; }),
            "r.json: luminance.frames_consistent must be true or false, not \"yes\"");
  EXPECT_EQ(changed([](json& d) { d["image"]["width"] = 1e300; }),
            "r.json: image.width must be a whole number in [1, 1048576], not 1e+300");
  EXPECT_EQ(changed([](json& d) { d["fwhm"]["status"] = "measured"; }),
            "r.json: fwhm.ellipse is missing though status is measured");
  EXPECT_EQ(changed([](json& d) { d["fwhm"]["status"] = 3; }),
            "r.json: fwhm.status must be a string, not 3");
  EXPECT_EQ(changed([](json& d) { d["limit"]["status"] = "measured"; }),
            "r.json: limit.status \"measured\" does not match limit_cd_m2");
  EXPECT_EQ(changed([](json& d) { d["glare"] = true; }),
            "r.json: glare is a verdict without a limit");
  EXPECT_EQ(changed([](json& d) {
              d["thresholds"] = {{{"threshold_cd_m2", 1e4}}};
            }),
            "r.json: thresholds[0].status is missing");
  // The contour ladder: known kinds, the fixed levels, ascending, the limit's and the half
  // maximum's rungs at their levels.
  const auto rung = [](double level, const char* kind) {
    return json{
        {"level_cd_m2", level}, {"kind", kind}, {"status", "below_level"}, {"ellipse", nullptr}};
  };
  EXPECT_EQ(changed([&](json& d) { d["contours"] = json::array({rung(1e4, "rung")}); }),
            "r.json: contours[0].kind \"rung\" is not ladder, limit or half_maximum");
  EXPECT_EQ(changed([&](json& d) { d["contours"] = json::array({rung(3e4, "ladder")}); }),
            "r.json: contours[0].level_cd_m2 30000 cd/m² is not a level of the ladder (1, 2.15 or "
            "4.64 × 10ⁿ from 10 000 cd/m²)");
  EXPECT_EQ(changed([&](json& d) {
              d["contours"] = json::array({rung(1e5, "ladder"), rung(1e4, "ladder")});
            }),
            "r.json: contours[1].level_cd_m2 is below the previous contour's: the ladder ascends");
  EXPECT_EQ(changed([&](json& d) { d["contours"] = json::array({rung(3e4, "limit")}); }),
            "r.json: contours[0].level_cd_m2 of the limit contour is not limit.limit_cd_m2");
  EXPECT_EQ(changed([&](json& d) {
              d["contours"] = json::array({rung(1e4, "half_maximum")});
              d["fwhm"]["level_cd_m2"] = 1e4;
              d["contours"].push_back(rung(1e4, "half_maximum"));
            }),
            "r.json: contours[1].kind a second \"half_maximum\" contour");
  EXPECT_EQ(changed([](json& d) { d["contours"] = "none"; }),
            "r.json: contours must be an array, not \"none\"");
  EXPECT_EQ(changed([](json& d) {
              d["frames"] = {{{"file", "f.png"}, {"samples", -1}}};
            }),
            "r.json: frames[0].samples must be a whole number in [0, 9007199254740992], not -1");
  EXPECT_EQ(changed([](json& d) {
              d["generator"] = {{"name", "glarecam"}};
            }),
            "r.json: generator.version is missing");
}

TEST(Result, ReadingAFileNamesIt) {
  testing::TempDir dir;
  EXPECT_NE(readResult(dir / "none.json").error().message.find("none.json: file is missing"),
            std::string::npos);
  testing::writeText(dir / "r.json", "{\"schema\": \"glarecam.result/1\"}");
  EXPECT_EQ(readResult(dir / "r.json").error().message,
            (dir / "r.json").string() + ": stack is missing");
  EXPECT_TRUE(hasResultSchema(json::parse("{\"schema\": \"glarecam.result/1\"}")));
  EXPECT_FALSE(hasResultSchema(json::parse("{\"my\": \"own results\"}")));
  EXPECT_FALSE(hasResultSchema(json::array()));
}

TEST(FrameRatio, APercentageNearTheOthersAFactorFarFromThem) {
  EXPECT_EQ(formatFrameRatio(1.09), "+9 %");
  EXPECT_EQ(formatFrameRatio(0.6), "-40 %");
  EXPECT_EQ(formatFrameRatio(17.1), "17.1 times");
  EXPECT_EQ(formatFrameRatio(0.002), "1/500 of");  // a 500th: not "-100 %"
  EXPECT_EQ(formatFrameRatio(2), "2 times");
}

TEST(FrameRatio, TwoFramesThatReadEachOthersExposureLookSwapped) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Frames 1 and 3 swapped across a bracket step of 500: one reads 500, the other 1/500.
  EXPECT_EQ(swappedFramePairs({1, 498, 1, 0.00201, 1}),
            (std::vector<std::pair<std::size_t, std::size_t>>{{1, 3}}));
  EXPECT_TRUE(swappedFramePairs({1, 1.3, 0.8, 1}).empty());    // within a factor of 2
  EXPECT_TRUE(swappedFramePairs({1, 10, 1, 0.5, 1}).empty());  // not the same factor
  EXPECT_TRUE(swappedFramePairs({1, 10, 1, 20}).empty());      // the same direction
  EXPECT_TRUE(swappedFramePairs({1, nan, 1, 0.002}).empty());  // one not judged
}

}  // namespace
}  // namespace glarecam::pipeline
