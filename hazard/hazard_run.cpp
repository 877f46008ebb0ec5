#include "hazard/hazard_run.h"

#include <algorithm>
#include <map>
#include <memory>

#include "core/atomic_file.h"
#include "core/progress.h"
#include "core/time.h"
#include "hazard/hazard_pdf.h"
#include "hazard/hazard_report.h"
#include "hazard/profile_table.h"
#include "hazard/scene.h"

namespace glarecam::hazard {

Status HazardRunOptions::validate() const {
  if (scene.empty()) return badInput("hazard: no scene file given");
  if (out.empty()) return badInput("--out: no output directory given");
  if (profile && profile->empty()) return badInput("--profile: empty path");
  if (report) GLARECAM_CHECK(checkReportPath(*report));
  return hazard.validate();
}

Status checkReportPath(const std::filesystem::path& report) {
  if (report.empty()) return badInput("--report: empty path");
  std::error_code error;
  if (std::filesystem::is_directory(report, error))
    return badInput("--report " + report.string() + " is a directory, not a file to write");
  // The first ancestor that exists must be a directory: the missing ones are made when the
  // report is written.
  for (std::filesystem::path parent = report.parent_path(); !parent.empty();
       parent = parent.parent_path()) {
    if (!std::filesystem::exists(parent, error)) {
      if (parent == parent.parent_path()) break;
      continue;
    }
    if (!std::filesystem::is_directory(parent, error))
      return badInput("--report " + report.string() + ": " + parent.string() +
                      " is not a directory");
    break;
  }
  return {};
}

Result<HazardRunSummary> runHazard(const HazardRunOptions& options) {
  GLARECAM_CHECK(options.validate());
  Scene scene;
  GLARECAM_ASSIGN(scene, readScene(options.scene));
  // Each profile file read once, however many arrays name it.
  std::map<std::filesystem::path, std::unique_ptr<ProfileTable>> tables;
  std::vector<const ProfileTable*> profiles;
  for (const ArrayPolygon& array : scene.arrays) {
    const std::optional<std::filesystem::path>& path =
        array.profile ? array.profile : options.profile;
    if (!path) {
      return badInput(options.scene.string() + ": array \"" + array.name +
                      "\" has no profile (give --profile or the array's \"profile\")");
    }
    auto& table = tables[path->lexically_normal()];
    if (!table) {
      Result<ProfileTable> read = ProfileTable::read(*path);
      if (!read) return std::unexpected(read.error());
      table = std::make_unique<ProfileTable>(std::move(*read));
    }
    profiles.push_back(table.get());
  }

  HazardOptions hazard = options.hazard;
  if (options.sun_by_default && hazard.sun.kind != SunKind::kReference) {
    const auto without = std::find_if(profiles.begin(), profiles.end(), [](const ProfileTable* p) {
      return !p->ladderReferenceLx();
    });
    if (without != profiles.end()) {
      scene.warnings.push_back(
          (*without)->path().string() +
          ": the profile has no contour ladder referred to a reference illuminance, so the sun "
          "is the profile's reference at every step (--sun reference), not the clear sky's: "
          "low suns count as bright as the reference (a profile from referred stacks, with "
          "contours, has the ladder the clear sky needs)");
      hazard.sun = SunBrightness{};
    }
  }
  HazardResult result;
  {
    Progress progress("hazard " + std::to_string(hazard.year), daysInYear(hazard.year),
                      options.show_progress);
    int reported = 0;
    GLARECAM_ASSIGN(result, computeHazard(scene, profiles, hazard, [&](int done, int) {
                      for (; reported < done; ++reported) progress.advance();
                    }));
    progress.finish();
  }
  HazardReport report{.scene = &scene,
                      .profiles = profiles,
                      .options = &hazard,
                      .result = &result,
                      .picture_stems = pictureStems(scene, result),
                      .daylight_saving = options.daylight_saving};
  GLARECAM_CHECK(writeHazardOutputs(report, options.out));
  if (options.report) {
    if (options.report->has_parent_path())
      GLARECAM_CHECK(ensureDirectory(options.report->parent_path()));
    GLARECAM_CHECK(writeHazardReportPdf(report, *options.report));
  }
  return HazardRunSummary{.document = hazardJson(report),
                          .table = summaryText(report),
                          .warnings = reportWarnings(report)};
}

}  // namespace glarecam::hazard
