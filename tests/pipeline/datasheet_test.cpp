// The data sheet files: PDF, SVG and PNG written atomically, and a missing directory an error.
#include "pipeline/datasheet.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <regex>
#include <string>

#include "pipeline/sweep_fits_test_support.h"
#include "pipeline/sweep_table.h"
#include "support/test_support.h"

namespace glarecam::pipeline {
namespace {

using testing::fitsOf;

// The sheet of `table` and its fits for module "standard" on 2026-11-26, without the facet model,
// at the method's limit curve.
Status writeStandardSheet(const SweepTable& table, const SweepFits& fits,
                          const std::filesystem::path& directory) {
  return writeDatasheet({.module = "standard",
                         .date = "2026-11-26",
                         .table = &table,
                         .fits = &fits,
                         .model_beta_deg = std::nullopt,
                         .limit = {}},
                        directory);
}

TEST(Datasheet, WritesPdfSvgAndPng) {
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(table);
  const SweepFits fits = fitsOf(*table);
  testing::TempDir dir;
  auto status = writeDatasheet({.module = "standard",
                                .date = "2026-11-26",
                                .table = &*table,
                                .fits = &fits,
                                .model_beta_deg = 1.25,
                                .limit = {.constant_cd_m2 = 30000}},
                               dir.path());
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_EQ(testing::readText(dir / kDatasheetPdf).substr(0, 5), "%PDF-");
  const std::string svg = testing::readText(dir / kDatasheetSvg);
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  EXPECT_EQ(testing::readText(dir / kDatasheetPng).substr(1, 3), "PNG");
  for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
    EXPECT_NE(entry.path().filename().string().rfind(".tmp-", 0), 0u) << entry.path();
}

// Stacks of the simulated camera mark the sheet's face (and name the camera in the subtitle): the
// same table drawn with and without a "sim" row differs.
TEST(Datasheet, ASimulatedSweepIsMarkedOnTheSheet) {
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(table);
  const SweepFits fits = fitsOf(*table);
  testing::TempDir dir;
  const auto draw = [&](const SweepTable& drawn, const std::filesystem::path& out) {
    std::filesystem::create_directories(out);
    auto status = writeStandardSheet(drawn, fits, out);
    EXPECT_TRUE(status) << status.error().message;
    return testing::readText(out / kDatasheetPng);
  };
  const std::string plain = draw(*table, dir / "plain");
  EXPECT_EQ(draw(*table, dir / "again"), plain);  // drawing is deterministic
  SweepTable simulated = *table;
  for (SweepRow& row : simulated.rows) row.camera_backend = "sim";
  ASSERT_TRUE(isSimulated(simulated));
  EXPECT_FALSE(isSimulated(*table));
  EXPECT_NE(draw(simulated, dir / "simulated"), plain);
}

// α in the table is rounded to its own uncertainty (4.99985 ± 0.05° is "5.00", not "4.99985"),
// to 0.1° when the row records none.
TEST(Datasheet, AlphaIsShownToItsOwnUncertainty) {
  SweepTable table;
  table.rows.resize(2);
  for (SweepRow& row : table.rows) {
    row.limit_cd_m2 = 30000;
    row.lmax_cd_m2 = 5e5;
  }
  table.rows[0].alpha_deg = 4.99985;
  table.rows[0].alpha_uncertainty_deg = 0.05;
  table.rows[1].alpha_deg = 10.0432;
  const render::TextTable cells = datasheetSweepTable(table);
  ASSERT_EQ(cells.rows.size(), 3u);
  EXPECT_EQ(cells.rows[1][0], "5.00");
  EXPECT_EQ(cells.rows[2][0], "10.0");
}

// The words of a PDF page as pdftotext (poppler-utils) lays them out: each word's box in points.
struct PdfWord {
  std::string text;
  double x_max_pt = 0, height_pt = 0;
};

std::vector<PdfWord> pdfWords(const std::filesystem::path& pdf) {
  const std::filesystem::path html = pdf.parent_path() / "words.html";
  const std::string command = "pdftotext -bbox '" + pdf.string() + "' '" + html.string() + "'";
  if (std::system(command.c_str()) != 0) return {};
  const std::string text = testing::readText(html);
  const std::regex word(
      R"re(<word xMin="([0-9.]+)" yMin="([0-9.]+)" xMax="([0-9.]+)" yMax="([0-9.]+)">([^<]*)</word>)re");
  std::vector<PdfWord> words;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), word); it != std::sregex_iterator();
       ++it)
    words.push_back({.text = (*it)[5],
                     .x_max_pt = std::stod((*it)[3]),
                     .height_pt = std::stod((*it)[4]) - std::stod((*it)[2])});
  return words;
}

// The subtitle of a real sheet (camera and calibration named, two calibrations) wraps: it stays
// at its 7.5 pt on the page, never below 7 pt, and inside the page. Before, it was scaled to one
// line: about 2 pt. Checked in the PDF as written, with the page's own title as the ruler.
TEST(Datasheet, ALongSubtitleWrapsAndStaysReadable) {
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(table);
  for (std::size_t i = 0; i < table->rows.size(); ++i) {
    SweepRow& row = table->rows[i];
    row.camera_backend = "aravis";
    row.camera_serial = i % 2 ? "Basler-acA2440-20gm-24026331" : "Basler-acA2440-20gm-24026332";
    row.calibration_id = i % 2 ? "55e5f09d95ab9da6" : "0c1d2e3f40516273";
    row.calibration_date = i % 2 ? "2026-06-21" : "2026-07-02";
    row.luminance_factor = i % 2 ? 1500.0 : 1512.5;
    row.luminance_factor_u = 18.9;
  }
  const SweepFits fits = fitsOf(*table);
  testing::TempDir dir;
  auto status = writeStandardSheet(*table, fits, dir.path());
  ASSERT_TRUE(status) << status.error().message;
  const std::vector<PdfWord> words = pdfWords(dir / kDatasheetPdf);
  ASSERT_FALSE(words.empty()) << "pdftotext (poppler-utils, scripts/install-deps.sh) read nothing";
  std::map<std::string, PdfWord> first;
  for (const PdfWord& word : words) first.try_emplace(word.text, word);
  // A word's box is the font's ascent plus descent: the title, drawn at 16 pt, gives the ratio.
  ASSERT_TRUE(first.contains("Glare"));
  const double box_per_pt = first["Glare"].height_pt / 16.0;
  constexpr double kA4LandscapeWidthPt = 841.89, kMarginPt = 28;
  // Words only the subtitle has: its start, the middle, the camera and the last calibration.
  for (const char* text :
       {"stacks,", "normal).", "Camera", "aravis", "calibration", "DN/\u00b5s."}) {
    ASSERT_TRUE(first.contains(text)) << text;
    // 7 pt: the issue's floor; the subtitle is drawn at 7.5 pt. pdftotext rounds boxes to
    // hundredths of a point, far inside the half point between the two.
    EXPECT_GE(first[text].height_pt / box_per_pt, 7.0) << text;
    EXPECT_LE(first[text].x_max_pt, kA4LandscapeWidthPt - kMarginPt + 0.5) << text;
  }
}

// The sheet says what its luminances refer to: the reference and the sweep's sources in the
// subtitle and a column of each row's source, or an UNREFERRED mark across the face.
TEST(Datasheet, TheSheetSaysWhatItsLuminancesReferTo) {
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(table);
  const SweepFits fits = fitsOf(*table);
  const auto words = [&](const SweepTable& drawn, const std::filesystem::path& out) {
    std::filesystem::create_directories(out);
    auto status = writeStandardSheet(drawn, fits, out);
    EXPECT_TRUE(status) << status.error().message;
    std::string text;
    for (const PdfWord& word : pdfWords(out / kDatasheetPdf)) text += word.text + " ";
    return text;
  };
  testing::TempDir dir;
  const std::string unreferred = words(*table, dir / "unreferred");
  // The mark is drawn diagonally, which pdftotext reads letter by letter: the word is asked of
  // the function the drawing uses, its note's letters of the page.
  const auto mark = datasheetPageMark(*table);
  ASSERT_TRUE(mark);
  EXPECT_EQ(mark->word, "UNREFERRED");
  EXPECT_EQ(mark->note, kUnreferredNote);
  EXPECT_NE(unreferred.find("Luminances unreferred:"), std::string::npos) << unreferred;
  SweepTable referred = *table;
  for (std::size_t i = 0; i < referred.rows.size(); ++i) {
    referred.rows[i].source_illuminance_lx = 61'200 + 4'650.0 * i;
    referred.rows[i].source_origin = "sensor";
    referred.rows[i].reference_illuminance_lx = 100'000;
  }
  const std::string text = words(referred, dir / "referred");
  EXPECT_FALSE(datasheetPageMark(referred));
  EXPECT_NE(text.find("Luminances at E = 100 klx direct normal, referred from sources of "
                      "61.2\u201398.4 klx (sensor)."),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("E (klx)"), std::string::npos) << text;
  EXPECT_NE(text.find("98.4"), std::string::npos) << text;
  // A simulated sweep is marked SIMULATED, referred or not.
  for (SweepRow& row : referred.rows) row.camera_backend = "sim";
  ASSERT_TRUE(datasheetPageMark(referred));
  EXPECT_EQ(datasheetPageMark(referred)->word, "SIMULATED");
}

TEST(Datasheet, MissingDirectoryIsAnErrorNotACrash) {
  auto table = readSweepTable(testing::testDataDir() / "standard-module-table3.csv");
  ASSERT_TRUE(table);
  const SweepFits fits = fitsOf(*table);
  auto status = writeStandardSheet(*table, fits, "/nonexistent/dir");
  EXPECT_FALSE(status);
}

}  // namespace
}  // namespace glarecam::pipeline
