// The glare profile: the SGHAT-equivalent beam spread of an ellipse, one row per degree from a
// sweep's fits, and the document: what is written reads back equal, the docs' example and older
// profiles read, and what is not a profile is refused naming the file and the field.
#include "pipeline/glare_profile.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <numbers>
#include <regex>

#include "core/angles.h"
#include "pipeline/process_stack.h"
#include "pipeline/sweep_fits_test_support.h"
#include "support/sim_support.h"
#include "support/test_support.h"

namespace glarecam::pipeline {
namespace {

using testing::fitsOf;

constexpr double kMradPerDeg = 1000.0 * radians(1.0);

TEST(CircularBeamSpread, ACircleIsItsOwnEquivalentCone) {
  // A circular ellipse of full angle 5°: the equal-solid-angle cone is the same cone, so beta is
  // 5° exactly (1e-9 relative: the trapezoid rule is exact for a constant radius).
  const CircularBeamSpread beam = circularBeamSpread(5.0, 5.0);
  EXPECT_NEAR(beam.beta_mrad, 5.0 * kMradPerDeg, 1e-9 * beam.beta_mrad);
  EXPECT_NEAR(beam.slope_error_mrad, beam.beta_mrad / 2 - kSunHalfAngleMrad, 1e-12);
  EXPECT_NEAR(beam.solid_angle_sr, 2 * std::numbers::pi * (1 - std::cos(2.5 * kMradPerDeg / 1e3)),
              1e-12);
}

TEST(CircularBeamSpread, AnEllipseMapsToTheGeometricMeanForSmallAngles) {
  // Small cones: Ω ≈ π a b, so the circular equivalent's full angle ≈ √(V H); at 8° × 2° the
  // curvature of the sphere changes that by < 1e-3 relative.
  const CircularBeamSpread beam = circularBeamSpread(8.0, 2.0);
  EXPECT_NEAR(beam.beta_mrad, 4.0 * kMradPerDeg, 1e-3 * beam.beta_mrad);
}

TEST(CircularBeamSpread, NarrowerThanTheSunGivesANegativeSlopeError) {
  EXPECT_LT(circularBeamSpread(0.3, 0.3).slope_error_mrad, 0);  // 0.3° < the sun's 0.53°
}

// A sweep with Lmax = lmax_at_0 e^(α / 20) and axes 3 + α/40, 4 - α/40 from `axes_from_deg` on.
SweepTable exponentialSweep(double lmax_at_0_cd_m2, double axes_from_deg) {
  SweepTable table;
  for (double alpha : {5.0, 20.0, 40.0, 55.0, 70.0, 80.0}) {
    SweepRow row;
    row.alpha_deg = alpha;
    row.lmax_cd_m2 = lmax_at_0_cd_m2 * std::exp(alpha / 20);
    if (alpha >= axes_from_deg) {
      row.vertical_deg = 3 + alpha / 40;
      row.horizontal_deg = 4 - alpha / 40;
    }
    table.rows.push_back(row);
  }
  return table;
}

TEST(GlareProfile, OneRowPerDegreeFromTheFitsWithLimitAndGlare) {
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(table);
  const SweepFits fits = fitsOf(*table);
  const auto rows = glareProfile(fits, {});
  ASSERT_EQ(rows.size(), 81u);
  EXPECT_TRUE(rows[0].extrapolated);  // the table starts at 5°
  EXPECT_FALSE(rows[5].extrapolated);
  EXPECT_EQ(rows[60].limit_cd_m2, 40000);
  EXPECT_DOUBLE_EQ(*rows[60].lmax_cd_m2, fits.biquadratic.curve(60));  // the better fit
  EXPECT_TRUE(rows[60].glares);
  ASSERT_TRUE(rows[60].vertical_deg && rows[60].beam);
  EXPECT_DOUBLE_EQ(*rows[60].vertical_deg, fits.vertical.logistic->curve(60));
  const CircularBeamSpread expected =
      circularBeamSpread(*rows[60].vertical_deg, *rows[60].horizontal_deg);
  EXPECT_DOUBLE_EQ(rows[60].beam->beta_mrad, expected.beta_mrad);

  const nlohmann::json j =
      toJson(makeGlareProfile({"standard", "2026-11-26", "t.csv"}, *table, fits, {}));
  EXPECT_EQ(j["schema"], "glarecam.glare-profile/2");
  EXPECT_EQ(j["profile"].size(), 81u);
  EXPECT_EQ(j["measured"].size(), 9u);
  EXPECT_TRUE(j["fits"]["vertical"]["logistic"]["r2"].is_number());
  EXPECT_TRUE(j["profile"][60]["circular_beam"]["slope_error_mrad"].is_number());
  EXPECT_EQ(j["simulated"], false);
  EXPECT_TRUE(j["cameras"].empty());  // Table III says nothing of its camera

  // A sweep of the simulated camera makes a simulated profile, naming the camera and calibration.
  SweepTable simulated = *table;
  for (SweepRow& row : simulated.rows) {
    row.camera_backend = "sim";
    row.camera_serial = "SIM-0001";
    row.calibration_id = "0123456789abcdef";
  }
  const nlohmann::json s =
      toJson(makeGlareProfile({"standard", "2026-11-26", "t.csv"}, simulated, fits, {}));
  EXPECT_EQ(s["simulated"], true);
  EXPECT_EQ(s["cameras"], nlohmann::json::array({"sim SIM-0001"}));
  EXPECT_EQ(s["calibrations"], nlohmann::json::array({"0123456789abcdef"}));
  EXPECT_EQ(s["illuminance"]["status"], "unreferred");
  EXPECT_TRUE(s["illuminance"]["sources"].is_null());
  // Referred rows: the reference and where their sources came from flow into the profile.
  for (std::size_t i = 0; i < simulated.rows.size(); ++i) {
    simulated.rows[i].source_illuminance_lx = 70'000 + 1'000.0 * i;
    simulated.rows[i].source_origin = "clear_sky";
    simulated.rows[i].reference_illuminance_lx = 100'000;
  }
  const nlohmann::json referred =
      toJson(makeGlareProfile({"standard", "2026-11-26", "t.csv"}, simulated, fits, {}));
  EXPECT_EQ(referred["illuminance"]["status"], "referred");
  EXPECT_EQ(referred["illuminance"]["reference_lx"], 100'000.0);
  EXPECT_EQ(referred["illuminance"]["sources"], "70.0\u201378.0 klx (clear_sky)");
}

// A logistic extrapolated past its rows can leave physical values (issue 18: a day sheet's
// vertical fit fell to 0° at α ≈ 42°): an axis is exported only within (0, 180°].
TEST(GlareProfile, AnAxisFitThatLeavesPhysicalValuesIsNotExported) {
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(table);
  SweepFits fits = fitsOf(*table);
  ASSERT_TRUE(fits.vertical.logistic);
  // y = 10 / (1 + exp(-(α - 50) 0.5)) - 2: below zero under ~47°, 8° at 80°.
  fits.vertical.logistic->curve = {.a = 10, .b = 50, .c = -2, .d = 0.5};
  const auto rows = glareProfile(fits, {});
  ASSERT_TRUE(rows[10].glares && rows[80].glares);  // Table III glares throughout
  EXPECT_FALSE(rows[10].vertical_deg);
  EXPECT_FALSE(rows[10].beam);
  ASSERT_TRUE(rows[80].vertical_deg);
  EXPECT_NEAR(*rows[80].vertical_deg, 8, 1e-5);
  EXPECT_TRUE(isPhysicalAxisDeg(180));
  EXPECT_FALSE(isPhysicalAxisDeg(0));
  EXPECT_FALSE(isPhysicalAxisDeg(180.5));
}

TEST(GlareProfile, NoAxesWhereTheModuleDoesNotGlare) {
  // Lmax crosses the 30 000 limit at 22°: ellipses from the 40° row on.
  const auto rows = glareProfile(fitsOf(exponentialSweep(10000, 40)), {});
  EXPECT_FALSE(rows[10].glares);
  EXPECT_FALSE(rows[10].vertical_deg);
  EXPECT_FALSE(rows[10].beam);
  EXPECT_TRUE(rows[80].glares);
}

TEST(GlareProfile, AConstantLimitReplacesTheCurve) {
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(table);
  const auto rows = glareProfile(fitsOf(*table), {.constant_cd_m2 = 5e6});
  EXPECT_EQ(rows[30].limit_cd_m2, 5e6);
  EXPECT_FALSE(rows[30].glares);  // ~570 000 cd/m² < 5e6
  EXPECT_TRUE(rows[80].glares);   // ~50e6
}

TEST(GlareProfile, AxesFittedOnANarrowerRangeAreFlaggedExtrapolated) {
  // Axes measured from 40° only: at 30° the module glares, the Lmax fit interpolates, but the
  // axis fits extrapolate.
  const auto rows = glareProfile(fitsOf(exponentialSweep(5e5, 40)), {});
  EXPECT_TRUE(rows[30].glares);
  EXPECT_TRUE(rows[30].extrapolated);
  EXPECT_FALSE(rows[50].extrapolated);
}

GlareProfile tableIIIProfile(const GlareLimit& limit = {}) {
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  EXPECT_TRUE(table);
  for (SweepRow& row : table->rows) {  // what a measured table also says
    row.camera_backend = "sim";
    row.camera_serial = "SIM-0001";
    row.calibration_id = "0123456789abcdef";
    row.calibration_date = "2026-06-21";
    row.luminance_factor = 1500;
  }
  table->rows[2].lmax_bound = "lower";
  return makeGlareProfile({"Standard module", "2026-11-26", "t.csv"}, *table, fitsOf(*table),
                          limit);
}

void expectRoundTrip(const GlareProfile& profile, const std::string& what) {
  const nlohmann::json written = toJson(profile);
  const auto read = glareProfileFromJson(nlohmann::json::parse(jsonText(written)), "p.json");
  ASSERT_TRUE(read) << what << ": " << read.error().message;
  EXPECT_EQ(*read, profile) << what;
  EXPECT_EQ(toJson(*read), written) << what;
}

TEST(GlareProfileDocument, WhatIsWrittenReadsBackEqual) {
  // The table's rows say no route: the camera's, as the paper measured them.
  EXPECT_EQ(tableIIIProfile().routes, std::vector<std::string>{"camera"});
  expectRoundTrip(tableIIIProfile(), "alpha curve");
  expectRoundTrip(tableIIIProfile({.constant_cd_m2 = 5e6}), "constant limit");
  expectRoundTrip(makeGlareProfile({"dim", "2026-11-26", "d.csv"}, exponentialSweep(10000, 40),
                                   fitsOf(exponentialSweep(10000, 40)), {}),
                  "glares in part of the range");
}

TEST(GlareProfileDocument, WrittenToAFileByTheDataSheetAndReadBack) {
  testing::TempDir dir;
  const GlareProfile profile = tableIIIProfile();
  ASSERT_TRUE(writeJsonFile(dir / "glare-profile.json", toJson(profile)));
  const auto read = readGlareProfile(dir / "glare-profile.json");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(*read, profile);
  EXPECT_NE(readGlareProfile(dir / "none.json").error().message.find("none.json"),
            std::string::npos);
}

// A profile written before glarecam recorded its identity, limit, fits and beam details: the
// required four keys and rows of α alone (and a beam of beta alone) still read.
TEST(GlareProfileDocument, AnEarlierVersionsProfileReads) {
  nlohmann::json rows = nlohmann::json::array();
  for (int alpha = 0; alpha <= kProfileAlphaMaxDeg; ++alpha) {
    nlohmann::json row{{"alpha_deg", alpha}};
    if (alpha == 60) row["circular_beam"] = {{"beta_mrad", 100.0}};
    rows.push_back(row);
  }
  const nlohmann::json old{{"schema", "glarecam.glare-profile/1"},
                           {"module", "old module"},
                           {"glare_ranges_deg", {{50.0, 80.0}}},
                           {"profile", rows}};
  const auto read = glareProfileFromJson(old, "old.json");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->module, "old module");
  EXPECT_FALSE(read->date || read->source || read->luminance_fit || read->generator);
  EXPECT_FALSE(read->simulated);
  EXPECT_EQ(read->limit, GlareLimit{});
  EXPECT_EQ(read->glare_ranges, (std::vector<AlphaRange>{{50, 80}}));
  ASSERT_EQ(read->rows.size(), 81u);
  EXPECT_FALSE(read->rows[10].lmax_cd_m2);
  ASSERT_TRUE(read->rows[60].beam);
  // The beam's other numbers follow from beta: Ω = 2π (1 − cos(β/2)), σ = β/2 − 4.65 mrad.
  EXPECT_NEAR(read->rows[60].beam->solid_angle_sr, 2 * std::numbers::pi * (1 - std::cos(0.05)),
              1e-15);
  EXPECT_NEAR(read->rows[60].beam->slope_error_mrad, 50 - kSunHalfAngleMrad, 1e-12);
  expectRoundTrip(*read, "an earlier version's, as read");
}

// The docs' example (docs/glare-profile.md, generated by scripts/doc-examples from the same table
// and abbreviated there) is what the reader takes: with the rows it leaves out taken from a fresh
// profile of Table III, it parses, and its α = 60° row is the fresh one.
TEST(GlareProfileDocument, TheDocsExampleParses) {
  const std::filesystem::path doc =
      testing::testDataDir().parent_path().parent_path() / "docs" / "glare-profile.md";
  const std::string text = testing::readText(doc);
  const std::regex block(
      "<!-- generated: glare-profile \\(scripts/doc-examples\\) -->\\n```json\\n([^`]*)```");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(text, match, block)) << doc;
  auto example = parseJsonText(match[1].str(), doc.string());
  ASSERT_TRUE(example) << example.error().message;
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(table);
  const nlohmann::json fresh = toJson(
      makeGlareProfile({"Standard module", "2026-11-26", "t.csv"}, *table, fitsOf(*table), {}));
  nlohmann::json rows = fresh["profile"];
  const nlohmann::json& documented = (*example)["profile"][1];
  ASSERT_EQ(documented["alpha_deg"], 60.0);
  // Within scripts/doc-examples' own tolerance (1e-3 relative): another CPU's last digits.
  for (auto& [key, value] : documented.items()) {
    if (value.is_number()) {
      EXPECT_NEAR(value.get<double>(), rows[60][key].get<double>(),
                  1e-3 * std::abs(value.get<double>()))
          << key;
    }
  }
  rows[60] = documented;
  (*example)["profile"] = rows;
  (*example)["measured"] = fresh["measured"];
  (*example)["fits"] = fresh["fits"];
  const auto read = glareProfileFromJson(*example, doc.string());
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_EQ(read->module, "Standard module");
}

TEST(GlareProfileDocument, RefusesWhatIsNotAProfileNamingTheField) {
  const std::vector<std::pair<std::function<void(nlohmann::json&)>, std::string>> cases{
      {[](nlohmann::json& d) { d["schema"] = "glarecam.fits/1"; },
       "p.json: schema \"glarecam.fits/1\" is not supported (a glare profile's is "
       "\"glarecam.glare-profile/2\" or \"glarecam.glare-profile/1\")"},
      {[](nlohmann::json& d) { d.erase("module"); }, "p.json: module is missing"},
      {[](nlohmann::json& d) { d.erase("glare_ranges_deg"); },
       "p.json: glare_ranges_deg is missing"},
      {[](nlohmann::json& d) {
         d["glare_ranges_deg"] = {{20, 10}};
       },
       "p.json: glare_ranges_deg[0] runs backwards (from > to)"},
      {[](nlohmann::json& d) {
         d["glare_ranges_deg"] = nlohmann::json::array({nlohmann::json::array({"a", 10})});
       },
       "p.json: glare_ranges_deg[0][0] must be a number, not \"a\""},
      {[](nlohmann::json& d) { d["profile"].erase(37); }, "p.json: profile has no row for α = 37°"},
      {[](nlohmann::json& d) { d["profile"][3]["alpha_deg"] = 2; },
       "p.json: profile[3].alpha_deg repeats an earlier row's α"},
      {[](nlohmann::json& d) { d["profile"][3]["alpha_deg"] = 2.5; },
       "p.json: profile[3].alpha_deg is not a whole degree"},
      {[](nlohmann::json& d) { d["profile"][3]["vertical_deg"] = -1; },
       "p.json: profile[3].vertical_deg -1° is outside [0, 180]"},
      {[](nlohmann::json& d) { d["profile"][3]["vertical_deg"] = "6"; },
       "p.json: profile[3].vertical_deg must be a number, not \"6\""},
      {[](nlohmann::json& d) { d["profile"][3]["circular_beam"] = 5; },
       "p.json: profile[3].circular_beam must be an object, not 5"},
      {[](nlohmann::json& d) { d["profile"] = nlohmann::json::object(); },
       "p.json: profile must be an array, not {}"},
      {[](nlohmann::json& d) { d["limit"]["mode"] = "constant"; },
       "p.json: limit.mode \"constant\" does not match constant_cd_m2 (alpha_curve without one, "
       "constant with one)"},
      {[](nlohmann::json& d) { d["luminance_fit"] = "spline"; },
       "p.json: luminance_fit \"spline\" is not cos or biquadratic"},
      {[](nlohmann::json& d) { d["measured"][0]["lmax_bound"] = "maybe"; },
       "p.json: measured[0].lmax_bound \"maybe\" is not lower or upper"},
      {[](nlohmann::json& d) { d["cameras"] = {7}; }, "p.json: cameras[0] must be a string, not 7"},
      {[](nlohmann::json& d) { d["routes"] = {"camera", "lidar"}; },
       "p.json: routes [1] \"lidar\" is not a route (camera or brdf)"},
      {[](nlohmann::json& d) { d["fits"] = "none"; },
       "p.json: fits must be an object, not \"none\""},
  };
  const nlohmann::json good = toJson(tableIIIProfile());
  for (const auto& [change, expected] : cases) {
    nlohmann::json document = good;
    change(document);
    Result<GlareProfile> read = badInput("not run");
    EXPECT_NO_THROW(read = glareProfileFromJson(document, "p.json")) << expected;
    ASSERT_FALSE(read) << expected;
    EXPECT_EQ(read.error().code, ErrorCode::kBadInput);
    EXPECT_EQ(read.error().message, expected);
  }
}

}  // namespace
}  // namespace glarecam::pipeline

namespace glarecam::pipeline {
namespace {

// ---- the contour ladder (/2) ------------------------------------------------------------------

ContourRow measuredRung(double alpha_deg, double level_cd_m2, ContourKind kind, double vertical_deg,
                        double horizontal_deg, double orientation_deg) {
  return {.stack_id = fmt::format("s{:g}", alpha_deg),
          .alpha_deg = alpha_deg,
          .level_cd_m2 = level_cd_m2,
          .kind = kind,
          .status = EllipseStatus::kMeasured,
          .vertical_deg = vertical_deg,
          .horizontal_deg = horizontal_deg,
          .orientation_deg = orientation_deg,
          .solid_angle_sr = vertical_deg * horizontal_deg * 1e-4,
          .vertical_uncertainty_deg = 0.1,
          .horizontal_uncertainty_deg = 0.2,
          .orientation_uncertainty_deg = 1.0,
          .solid_angle_uncertainty_sr = 1e-5,
          .reference_illuminance_lx = 100'000.0};
}

// Two stacks, at α 20° and 30°: rungs at 1e4 and 2.15e4 in both, 4.64e4 at 30° alone, the half
// maxima at 1e5 and 2e5, a limit rung (not in the profile) and a rung without an ellipse.
ContourTable twoStackLadder() {
  ContourTable table;
  table.rows = {measuredRung(20, 1e4, ContourKind::kLadder, 10, 8, 89),
                measuredRung(20, 2.15e4, ContourKind::kLadder, 8, 6, 89),
                measuredRung(20, 3e4, ContourKind::kLimit, 7, 5, 89),
                measuredRung(20, 1e5, ContourKind::kHalfMaximum, 4, 3, 89),
                measuredRung(30, 1e4, ContourKind::kLadder, 12, 10, -89),
                measuredRung(30, 2.15e4, ContourKind::kLadder, 10, 8, -89),
                measuredRung(30, 4.64e4, ContourKind::kLadder, 8, 6, -89),
                measuredRung(30, 2e5, ContourKind::kHalfMaximum, 5, 4, -89)};
  ContourRow none = measuredRung(30, 1e6, ContourKind::kLadder, 1, 1, 0);
  none.status = EllipseStatus::kBelowLevel;
  table.rows.push_back(none);
  return table;
}

TEST(ProfileLadder, RungsPerWholeDegreeLinearInAlphaBetweenTheStacks) {
  const std::vector<ProfileLadderRow> ladder = profileLadder(twoStackLadder());
  ASSERT_EQ(ladder.size(), 11u);  // 20 … 30°
  EXPECT_EQ(ladder.front().alpha_deg, 20);
  EXPECT_EQ(ladder.back().alpha_deg, 30);
  // At a measured α: its rungs (fixed, then the half maximum), without the limit's.
  ASSERT_EQ(ladder.back().contours.size(), 4u);
  EXPECT_EQ(ladder.back().contours[2].level_cd_m2, 4.64e4);
  EXPECT_EQ(ladder.back().contours[3].kind, ContourKind::kHalfMaximum);
  // Between: the levels both stacks measured, axes linear in α, the half maximum's level
  // log-linear, the orientation the short way round (89° and -89° are 2° apart, through 90°).
  const ProfileLadderRow& at25 = ladder[5];
  EXPECT_EQ(at25.alpha_deg, 25);
  ASSERT_EQ(at25.contours.size(), 3u);
  EXPECT_EQ(at25.contours[0].level_cd_m2, 1e4);
  EXPECT_DOUBLE_EQ(at25.contours[0].vertical_deg, 11);
  EXPECT_DOUBLE_EQ(at25.contours[0].horizontal_deg, 9);
  EXPECT_NEAR(at25.contours[0].orientation_deg, 90, 1e-12);
  EXPECT_NEAR(at25.contours[2].level_cd_m2, std::sqrt(1e5 * 2e5), 1e-6);
  EXPECT_EQ(at25.contours[2].kind, ContourKind::kHalfMaximum);
  EXPECT_NEAR(ladder[3].contours[0].orientation_deg, 89.6, 1e-9);   // α 23°: 89 + 0.3 · 2
  EXPECT_NEAR(ladder[7].contours[0].orientation_deg, -89.6, 1e-9);  // α 27°
  EXPECT_TRUE(profileLadder(ContourTable{}).empty());
}

GlareProfile ladderProfile() {
  GlareProfile profile;
  profile.module = "ladder module";
  profile.referred = true;
  profile.reference_illuminance_lx = 100'000;
  profile.ladder = profileLadder(twoStackLadder());
  return profile;
}

TEST(ContourAt, LinearInLnLevelBetweenRungsThenInAlpha) {
  const GlareProfile profile = ladderProfile();
  // At a rung: the rung.
  const auto rung = contourAt(profile, 20, 1e4);
  ASSERT_TRUE(rung);
  EXPECT_EQ(rung->vertical_deg, 10);
  // Between 1e4 and 2.15e4 at 20°: a quarter of the way in ln level.
  const double level = 1e4 * std::pow(2.15, 0.25);
  const auto between = contourAt(profile, 20, level);
  ASSERT_TRUE(between);
  EXPECT_NEAR(between->vertical_deg, 10 - 2 * 0.25, 1e-12);
  EXPECT_EQ(between->level_cd_m2, level);
  EXPECT_EQ(between->kind, ContourKind::kLadder);
  // And at 20.5°: halfway to 21°'s (whose rungs are 0.1 of the way to 30°'s: +0.2°).
  const auto off_degree = contourAt(profile, 20.5, level);
  ASSERT_TRUE(off_degree);
  EXPECT_NEAR(off_degree->vertical_deg, 10 - 0.5 + 0.1, 1e-12);
  EXPECT_NEAR(off_degree->solid_angle_sr,
              (contourAt(profile, 20, level)->solid_angle_sr +
               contourAt(profile, 21, level)->solid_angle_sr) /
                  2,
              1e-15);
  // None above the highest rung (the half maximum here), below the lowest, or outside the α.
  EXPECT_FALSE(contourAt(profile, 20, 1.01e5));
  EXPECT_TRUE(contourAt(profile, 30, 1.01e5));  // 30°'s half maximum is at 2e5
  EXPECT_FALSE(contourAt(profile, 20, 9e3));
  EXPECT_FALSE(contourAt(profile, 19.5, 2e4));
  EXPECT_FALSE(contourAt(profile, 30.5, 2e4));
  EXPECT_FALSE(contourAt(profile, 25, std::nan("")));
  EXPECT_FALSE(contourAt(GlareProfile{}, 25, 2e4));
}

TEST(ContourAt, UnderASourceIlluminanceTheReferredContourAtTheScaledLevel) {
  const GlareProfile profile = ladderProfile();
  // A 50 klx sun reaches 1e4 cd/m² where the 100 klx reference reaches 2e4.
  const auto dim = contourAt(profile, 25, 1e4, 50'000);
  ASSERT_TRUE(dim) << dim.error().message;
  ASSERT_TRUE(*dim);
  EXPECT_EQ(**dim, *contourAt(profile, 25, 2e4));
  GlareProfile unreferred = profile;
  unreferred.referred = false;
  unreferred.reference_illuminance_lx.reset();
  const auto refused = contourAt(unreferred, 25, 1e4, 50'000);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::kBadInput);
  EXPECT_NE(refused.error().message.find("is unreferred"), std::string::npos)
      << refused.error().message;
  EXPECT_FALSE(contourAt(profile, 25, 1e4, 0.0));
  EXPECT_FALSE(contourAt(profile, 25, 1e4, -5.0));
}

TEST(GlareProfileDocument, TheLadderAndReferenceReadBackAndBadLaddersAreRefused) {
  GlareProfile profile = tableIIIProfile();
  profile.referred = true;
  profile.reference_illuminance_lx = 100'000;
  profile.sources = "61.2\u201398.4 klx (sensor)";
  profile.ladder = profileLadder(twoStackLadder());
  expectRoundTrip(profile, "a ladder");
  const nlohmann::json good = toJson(profile);
  EXPECT_EQ(good["schema"], "glarecam.glare-profile/2");
  EXPECT_EQ(good["illuminance"], (nlohmann::json{{"status", "referred"},
                                                 {"reference_lx", 1e5},
                                                 {"sources", "61.2\u201398.4 klx (sensor)"}}));
  const std::vector<std::pair<std::function<void(nlohmann::json&)>, std::string>> cases{
      {[](nlohmann::json& d) { d.erase("ladder"); },
       "p.json: ladder is missing (a /2 profile has one, maybe empty)"},
      {[](nlohmann::json& d) { d.erase("illuminance"); },
       "p.json: illuminance is missing (a /2 profile says what it refers to)"},
      {[](nlohmann::json& d) { d["illuminance"]["reference_lx"] = nullptr; },
       "p.json: illuminance.reference_lx must be given exactly when the status is referred"},
      {[](nlohmann::json& d) { d["ladder"][1]["alpha_deg"] = 20.5; },
       "p.json: ladder[1].alpha_deg is not a whole degree"},
      {[](nlohmann::json& d) { d["ladder"][1]["alpha_deg"] = 20; },
       "p.json: ladder[1].alpha_deg is not above the previous row's: the ladder ascends in α"},
      {[](nlohmann::json& d) { d["ladder"][0]["contours"][0]["kind"] = "limit"; },
       "p.json: ladder[0].contours[0].kind \"limit\" is not ladder or half_maximum"},
      {[](nlohmann::json& d) { d["ladder"][0]["contours"][0]["level_cd_m2"] = 1.5e4; },
       "p.json: ladder[0].contours[0].level_cd_m2 15000 cd/m² is not a level of the ladder (1, "
       "2.15 or 4.64 × 10ⁿ from 10 000 cd/m²)"},
      {[](nlohmann::json& d) { d["ladder"][0]["contours"][1]["level_cd_m2"] = 1e4; },
       "p.json: ladder[0].contours[1].level_cd_m2 is not above the previous contour's: levels "
       "ascend"},
      {[](nlohmann::json& d) { d["ladder"][0]["contours"][0]["vertical_deg"] = 200; },
       "p.json: ladder[0].contours[0].vertical_deg 200° is outside [0, 180]"},
      {[](nlohmann::json& d) {
         d["ladder"][0]["contours"][0]["uncertainty"].erase("vertical_deg");
       },
       "p.json: ladder[0].contours[0].uncertainty.vertical_deg is missing"},
  };
  for (const auto& [change, message] : cases) {
    nlohmann::json document = good;
    change(document);
    const auto read = glareProfileFromJson(document, "p.json");
    ASSERT_FALSE(read) << message;
    EXPECT_EQ(read.error().code, ErrorCode::kBadInput);
    EXPECT_EQ(read.error().message, message);
  }
  // A /1 profile with neither reads, and says nothing about its reference.
  nlohmann::json v1 = good;
  v1["schema"] = "glarecam.glare-profile/1";
  v1.erase("ladder");
  v1.erase("illuminance");
  const auto read = glareProfileFromJson(v1, "p.json");
  ASSERT_TRUE(read) << read.error().message;
  EXPECT_FALSE(read->referred);
  EXPECT_TRUE(read->ladder.empty());
  expectRoundTrip(*read, "a /1 profile, as read");
  EXPECT_EQ(toJson(*read)["illuminance"]["status"], "unstated");
}

// The check of the issue: a contour between two rungs, from a processed stack's ladder through
// the profile, agrees with the ellipse measured directly at that level (process --thresholds)
// within its standard uncertainty, which includes the interpolation's own error (the stack's
// pixel noise alone is far smaller: the axes of a Gaussian lobe go as √ln(L/T), and the chord
// between rungs falls short of that curve by some 0.1 % of an axis).
TEST(ContourAt, BetweenTwoRungsItAgreesWithADirectMeasurement) {
  testing::TempDir dir;
  testing::writeSmallStack(dir / "s", testing::smallScene(40.0));
  const double level = std::sqrt(2.15e4 * 4.64e4);
  ProcessOptions options;
  options.show_progress = false;
  options.thresholds_cd_m2 = {level};
  const auto processed = processStack(dir / "s", options);
  ASSERT_TRUE(processed) << processed.error().message;
  const StackResult& result = processed->result;
  ASSERT_TRUE(result.thresholds[0].ellipse) << toString(result.thresholds[0].status);
  const ResultEllipse& direct = *result.thresholds[0].ellipse;
  ContourTable table;
  table.rows = contourRowsFromResult(result);
  GlareProfile profile;
  profile.ladder = profileLadder(table);
  const auto contour = contourAt(profile, 40, level);
  ASSERT_TRUE(contour);
  EXPECT_NEAR(contour->vertical_deg, direct.vertical_deg, contour->vertical_uncertainty_deg);
  EXPECT_NEAR(contour->horizontal_deg, direct.horizontal_deg, contour->horizontal_uncertainty_deg);
  EXPECT_NEAR(contour->solid_angle_sr, direct.solid_angle_sr, contour->solid_angle_uncertainty_sr);
  // Its σ is no blanket: a fraction of a per cent of the axes.
  EXPECT_LT(contour->vertical_uncertainty_deg, 0.005 * contour->vertical_deg);
  // And the interpolation is no coincidence: the rungs around it differ by many σ.
  const auto low = contourAt(profile, 40, 2.15e4), high = contourAt(profile, 40, 4.64e4);
  ASSERT_TRUE(low && high);
  EXPECT_GT(low->vertical_deg - high->vertical_deg, 5 * direct.vertical_uncertainty_deg);
}

}  // namespace
}  // namespace glarecam::pipeline
