#include "hazard/hazard_report.h"

#include <gtest/gtest.h>

#include "core/csv.h"
#include "tests/hazard/hazard_fixtures.h"
#include "tests/support/test_support.h"

namespace glarecam::hazard {
namespace {

TEST(HazardReport, LocalTimesCarryTheStandardOffset) {
  EXPECT_EQ(localTimeText(2027, 0, 1.0, false), "2027-01-01T00:00+01:00");
  EXPECT_EQ(localTimeText(2027, 79 * 86400 + 18 * 3600 + 125, 1.0, true),
            "2027-03-21T18:02:05+01:00");
  EXPECT_EQ(localTimeText(2028, 365 * 86400 + 60, -3.5, false), "2028-12-31T00:01-03:30");
  EXPECT_EQ(localTimeText(2027, 86400 * 2, 5.75, false), "2027-01-03T00:00+05:45");
}

TEST(HazardReport, PictureNamesAreSafeAndUnique) {
  Scene scene;
  for (const char* name : {"window 3/north", "window-3-north", "a"})
    scene.observers.push_back({.name = name, .position_m = {0, 0, 0}});
  const std::vector<std::string> stems = pictureStems(scene);
  EXPECT_EQ(stems[0], "glare-window-3-north");
  EXPECT_EQ(stems[1], "glare-window-3-north-2");
  EXPECT_EQ(stems[2], "glare-a");
}

class HazardReportOutputs : public ::testing::Test {
 protected:
  void SetUp() override {
    scene_ = testing::sceneOf(
        testing::zurichSite(), {testing::squareArray("roof", {0, 0, 0}, {0, 0, 1}, 10)},
        {{.name = "window", .position_m = {0, 30, 12}, .from_h = 6, .to_h = 22}});
    options_.year = 2027;
    options_.step_s = 60;
    options_.threads = 1;
    options_.models = {{ModelKind::kEllipse}, {ModelKind::kCircle}};
    // A result built by hand: two events on 21 March, ellipse only on its first minute.
    result_.year = 2027;
    result_.days = 365;
    result_.step_s = 60;
    result_.steps_per_day = 1440;
    ObserverHazard observer;
    observer.steps.assign(365 * 1440, 0);
    observer.steps[79 * 1440 + 18 * 60] = 1;
    observer.steps[79 * 1440 + 18 * 60 + 1] = 3;
    for (int m = 0; m < 2; ++m) {
      ModelSummary summary;
      summary.minutes_per_day.assign(365, 0);
      summary.first_last_step.assign(365, std::nullopt);
      summary.minutes_per_day[79] = 2 - m;
      summary.first_last_step[79] = std::pair{18 * 60 + m, 18 * 60 + 1};
      summary.minutes_per_year = 2 - m;
      summary.hours_per_year = (2 - m) / 60.0;
      summary.days_with_glare = 1;
      summary.max_minutes_per_day = 2 - m;
      for (const Criterion& criterion : options_.criteria)
        summary.verdicts.push_back(
            assess(criterion, summary.max_minutes_per_day, summary.hours_per_year));
      observer.models.push_back(summary);
    }
    result_.observers.push_back(observer);
    result_.events = {{.observer = 0,
                       .array = 0,
                       .model = 0,
                       .first_step = 79 * 1440 + 1080,
                       .end_step = 79 * 1440 + 1082,
                       .alpha_min_deg = 61.2,
                       .alpha_max_deg = 61.31,
                       .peak_luminance_cd_m2 = 123456.0,
                       .peak = {.step = 79 * 1440 + 1081,
                                .alpha_deg = 61.25,
                                .glare_azimuth_deg = 283.5,
                                .glare_elevation_deg = 2.1,
                                .distance_m = 35.47,
                                .sun_azimuth_deg = 270.1,
                                .sun_elevation_deg = 1.6,
                                .source_illuminance_lx = 41000.0,
                                .luminance_cd_m2 = 123456.0,
                                .ocular = OcularExposure{.retinal_irradiance_w_cm2 = 0.0123,
                                                         .subtended_angle_mrad = 4.56,
                                                         .ocular_class = OcularClass::kAfterImage}},
                       .worst_class = OcularClass::kAfterImage},
                      {.observer = 0,
                       .array = 0,
                       .model = 1,
                       .first_step = 79 * 1440 + 1081,
                       .end_step = 79 * 1440 + 1082,
                       .alpha_min_deg = 61.3,
                       .alpha_max_deg = 61.3,
                       .peak_luminance_cd_m2 = std::nullopt,
                       .peak = {},
                       .worst_class = std::nullopt}};
    report_ = {.scene = &scene_,
               .profiles = {&profile_},
               .options = &options_,
               .result = &result_,
               .picture_stems = pictureStems(scene_)};
  }

  Scene scene_;
  ProfileTable profile_ = testing::constantProfile(6, 4);
  HazardOptions options_;
  HazardResult result_;
  HazardReport report_;
};

TEST_F(HazardReportOutputs, HazardJsonHoldsInputsAndEveryObserversNumbers) {
  const nlohmann::json json = hazardJson(report_);
  EXPECT_EQ(json["schema"], "glarecam.hazard/1");
  EXPECT_EQ(json["inputs"]["year"], 2027);
  EXPECT_EQ(json["inputs"]["step_s"], 60);
  EXPECT_EQ(json["inputs"]["models"], nlohmann::json({"ellipse", "circle"}));
  EXPECT_EQ(json["inputs"]["criteria"]["lai"]["max_hours_per_year"], 30);
  EXPECT_EQ(json["inputs"]["criteria"]["ch"]["max_hours_per_year"], 50);
  EXPECT_EQ(json["inputs"]["profiles"][0]["module"], "test module");
  EXPECT_EQ(json["inputs"]["profiles"][0]["array"], "roof");
  const nlohmann::json& ellipse = json["observers"][0]["models"]["ellipse"];
  EXPECT_EQ(ellipse["minutes_per_day"].size(), 365u);
  EXPECT_EQ(ellipse["minutes_per_day"][79], 2);
  EXPECT_EQ(ellipse["minutes_per_year"], 2);
  EXPECT_EQ(ellipse["days_with_glare"], 1);
  EXPECT_EQ(ellipse["first_last_per_day"][79], nlohmann::json({"18:00", "18:02"}));
  EXPECT_TRUE(ellipse["first_last_per_day"][78].is_null());
  EXPECT_EQ(ellipse["verdicts"]["lai"]["verdict"], "not significant");
  EXPECT_EQ(ellipse["verdicts"]["ch"]["exceeded"], false);
  for (const char* key :
       {"hours_per_year", "max_minutes_per_day", "steps_beyond_method", "steps_unknown_spread"})
    EXPECT_TRUE(ellipse.contains(key)) << key;
  EXPECT_EQ(json["observers"][0]["picture"]["png"], "glare-window.png");
  EXPECT_EQ(json["observers"][0]["hours"], nlohmann::json({6.0, 22.0}));
}

TEST_F(HazardReportOutputs, EventsCsvHasOneRowPerEvent) {
  const std::string csv = eventsCsv(report_);
  EXPECT_EQ(csv,
            "observer,array,model,start_local,end_local,duration_min,alpha_min_deg,alpha_max_deg,"
            "peak_luminance_cd_m2,simulated,peak_local,glare_azimuth_deg,glare_elevation_deg,"
            "distance_m,sun_azimuth_deg,sun_elevation_deg,source_illuminance_lx,ocular_class,"
            "retinal_irradiance_w_cm2,subtended_angle_mrad,start_civil,end_civil\n"
            "window,roof,ellipse,2027-03-21T18:00+01:00,2027-03-21T18:02+01:00,2,61.20,61.31,"
            "1.235e+05,false,2027-03-21T18:01+01:00,283.50,2.10,35.5,270.10,1.60,41000,yellow,"
            "0.0123,4.56,2027-03-21T18:00+01:00,2027-03-21T18:02+01:00\n"
            "window,roof,circle,2027-03-21T18:01+01:00,2027-03-21T18:02+01:00,1,61.30,61.30,,"
            "false,2027-01-01T00:00+01:00,0.00,0.00,0.0,0.00,0.00,,,,,2027-03-21T18:01+01:00,"
            "2027-03-21T18:02+01:00\n");
  // Under the EU's rule 21 March is still winter; a summer event moves an hour on.
  report_.daylight_saving = DaylightSaving::kEu;
  EXPECT_NE(eventsCsv(report_).find(",2027-03-21T18:00+01:00,2027-03-21T18:02+01:00\n"),
            std::string::npos);
  EXPECT_EQ(civilTimeText(report_, std::int64_t{181} * 86400 + 12 * 3600, false),
            "2027-07-01T13:00+02:00");
}

TEST_F(HazardReportOutputs, ASimulatedProfileIsMarkedInEveryOutput) {
  nlohmann::json document = testing::constantProfileJson(6, 4);
  document["simulated"] = true;
  glarecam::testing::TempDir dir;
  const std::filesystem::path path = dir / "glare-profile.json";
  glarecam::testing::writeText(path, document.dump());
  const ProfileTable simulated = *ProfileTable::read(path);
  report_.profiles = {&simulated};
  const std::string mark = "SIMULATED profile of module \"test module\" (" + path.string() +
                           "), for array \"roof\": stacks of the simulated camera: not a "
                           "measurement";
  // stderr and hazard.json's warnings.
  EXPECT_EQ(reportWarnings(report_), std::vector<std::string>{mark});
  EXPECT_EQ(hazardJson(report_)["warnings"], nlohmann::json::array({mark}));
  // The table's first line.
  const std::string text = summaryText(report_);
  EXPECT_TRUE(text.starts_with(mark + "\n")) << text;
  // Every event's row.
  const std::string csv = eventsCsv(report_);
  EXPECT_NE(csv.find(",1.235e+05,true,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",61.30,,true,"), std::string::npos) << csv;
  // The picture's subtitle, and the module in it.
  const std::string subtitle = chartContent(report_, 0).subtitle;
  EXPECT_TRUE(
      subtitle.starts_with("SIMULATED: stacks of the simulated camera: not a measurement \u00b7 "))
      << subtitle;
  EXPECT_NE(subtitle.find("test module (SIMULATED)"), std::string::npos) << subtitle;
  // And across the picture, as on the data sheet.
  EXPECT_EQ(chartContent(report_, 0).mark, "SIMULATED");
  EXPECT_EQ(chartContent(report_, 0).mark_note,
            "stacks of the simulated camera: not a measurement");
}

TEST_F(HazardReportOutputs, AMeasuredProfileIsNotMarked) {
  EXPECT_TRUE(reportWarnings(report_).empty());
  EXPECT_EQ(summaryText(report_).find("SIMULATED"), std::string::npos);
  EXPECT_EQ(chartContent(report_, 0).subtitle.find("SIMULATED"), std::string::npos);
  EXPECT_TRUE(chartContent(report_, 0).mark.empty());
}

TEST_F(HazardReportOutputs, SummaryGivesEachArraysFacingTiltAndArea) {
  // A roof tilted 30° facing south (its normal 60° above the southern horizon), and a level one.
  scene_.arrays = {testing::squareArray("south", {0, 0, 0}, testing::unitToward(60, 180), 10),
                   testing::squareArray("flat", {0, 0, 0}, {0, 0, 1}, 2)};
  report_.profiles = {&profile_, &profile_};
  const std::string text = summaryText(report_);
  EXPECT_TRUE(
      text.starts_with("array south: faces 180° (S), tilt 30.0°, 100.0 m²\n"
                       "array flat: faces up (level), tilt 0.0°, 4.0 m²\n\n"
                       "observer "))
      << text;
  const nlohmann::json arrays = hazardJson(report_)["inputs"]["arrays"];
  EXPECT_NEAR(arrays[0]["facing_azimuth_deg"].get<double>(), 180, 1e-9);
  EXPECT_NEAR(arrays[0]["tilt_deg"].get<double>(), 30, 1e-9);
  EXPECT_TRUE(arrays[1]["facing_azimuth_deg"].is_null());
}

TEST_F(HazardReportOutputs, ChartCellsShowWhichModelGlares) {
  const HazardChartContent content = chartContent(report_, 0);
  ASSERT_EQ(content.models.size(), 2u);
  EXPECT_EQ(content.models[0].label, "ellipse");
  EXPECT_EQ(content.cells[79 * 1440 + 1080], HazardCell::kFirstOnly);
  EXPECT_EQ(content.cells[79 * 1440 + 1081], HazardCell::kBoth);
  EXPECT_EQ(content.cells[0], HazardCell::kNone);
  EXPECT_EQ(content.threshold_minutes_per_day, 30);
  // Each criterion's yearly limit, named as the table names it, for the year's column.
  ASSERT_EQ(content.yearly_limits.size(), 2u);
  EXPECT_EQ(content.yearly_limits[0].label, "LAI");
  EXPECT_EQ(content.yearly_limits[0].hours_per_year, 30);
  EXPECT_EQ(content.yearly_limits[1].label, "CH");
  EXPECT_EQ(content.yearly_limits[1].hours_per_year, 50);
}

TEST(HazardReport, WorstDaysAreTheMostGlaringMostFirst) {
  ModelSummary summary;
  summary.minutes_per_day = {0, 5, 12, 3, 12, 0, 30, 1};
  EXPECT_EQ(worstDays(summary, 3), (std::vector<std::size_t>{6, 2, 4}));
  // Never a day without glare, however many are asked for.
  EXPECT_EQ(worstDays(summary, 10), (std::vector<std::size_t>{6, 2, 4, 1, 3, 7}));
  EXPECT_TRUE(worstDays(ModelSummary{}, 5).empty());
}

TEST(HazardReport, OffsetsAndFacingsReadAsTheReportWritesThem) {
  EXPECT_EQ(utcOffsetText(1.0), "UTC+01:00");
  EXPECT_EQ(utcOffsetText(-3.5), "UTC-03:30");
  EXPECT_EQ(arrayFacingText(testing::squareArray("flat", {0, 0, 0}, {0, 0, 1}, 2)),
            "faces up (level), tilt 0.0°, 4.0 m²");
}

TEST_F(HazardReportOutputs, SummaryTableListsEveryObserverAndModel) {
  const std::string text = summaryText(report_);
  EXPECT_NE(text.find("observer"), std::string::npos);
  // Names left-aligned in a column as wide as "observer".
  EXPECT_NE(text.find("\nwindow    ellipse "), std::string::npos) << text;
  EXPECT_NE(text.find("\nwindow    circle "), std::string::npos) << text;
  EXPECT_NE(text.find("not significant"), std::string::npos) << text;
}

TEST_F(HazardReportOutputs, WritesEveryFile) {
  glarecam::testing::TempDir dir;
  ASSERT_TRUE(writeHazardOutputs(report_, dir / "out"));
  for (const char* name : {"hazard.json", "events.csv", "glare-window.png", "glare-window.svg"})
    EXPECT_TRUE(std::filesystem::exists(dir / "out" / name)) << name;
  const nlohmann::json json =
      nlohmann::json::parse(glarecam::testing::readText(dir / "out/hazard.json"));
  EXPECT_EQ(json["schema"], "glarecam.hazard/1");
}

}  // namespace
}  // namespace glarecam::hazard
