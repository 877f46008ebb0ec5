#include "hazard/hazard_run.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>

#include "core/atomic_file.h"
#include "core/progress.h"
#include "core/sha256.h"
#include "core/text_file.h"
#include "core/time.h"
#include "hazard/candidate_pairs.h"
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
  if (screen && report)
    return badInput(
        "--report: a screening writes no PDF report (run the receptors of interest "
        "without --screen for one)");
  if (shard && !screen) return badInput("--shard: only with --screen");
  // Every array a candidate of every point: lists of points × arrays, which a district does not
  // fit in memory (and LAI's guidance never asks for).
  if (screen && !std::isfinite(hazard.max_distance_m))
    return badInput("--max-distance: a screening needs a finite distance in metres");
  return hazard.validate();
}

Status HazardMergeOptions::validate() const {
  if (shards.empty()) return badInput("hazard merge: no shard directory given");
  if (out.empty()) return badInput("--out: no output directory given");
  return {};
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

namespace {

// Each profile file read once, however many arrays name it.
struct SceneProfiles {
  std::map<std::filesystem::path, std::unique_ptr<ProfileTable>> tables;
  std::vector<const ProfileTable*> profiles;  // per array
};

Status readProfiles(const Scene& scene, const std::filesystem::path& scene_path,
                    const std::optional<std::filesystem::path>& fallback, SceneProfiles& read) {
  for (const ArrayPolygon& array : scene.arrays) {
    const std::optional<std::filesystem::path>& path = array.profile ? array.profile : fallback;
    if (!path) {
      return badInput(scene_path.string() + ": array \"" + array.name +
                      "\" has no profile (give --profile or the array's \"profile\")");
    }
    auto& table = read.tables[path->lexically_normal()];
    if (!table) {
      Result<ProfileTable> loaded = ProfileTable::read(*path);
      if (!loaded) return std::unexpected(loaded.error());
      table = std::make_unique<ProfileTable>(std::move(*loaded));
    }
    read.profiles.push_back(table.get());
  }
  return {};
}

// An ordinary run's receptor points that see the front of an array beyond the distance: they are
// not computed against it, which a report must not hide. Checked pair by pair up to
// kMaxDistanceCheckPairs (a scene of that size is screened, whose counts say it).
constexpr std::size_t kMaxDistanceCheckPairs = 1'000'000;
std::optional<std::string> beyondDistanceWarning(const Scene& scene, double max_distance_m) {
  if (!std::isfinite(max_distance_m) ||
      scene.observers.size() * scene.arrays.size() > kMaxDistanceCheckPairs)
    return std::nullopt;
  std::size_t points = 0;
  std::string example;
  for (const Observer& observer : scene.observers) {
    bool counted = false;
    for (const ArrayPolygon& array : scene.arrays) {
      if (!seesFront(array, observer.position_m)) continue;
      const double distance_m = distanceToArrayM(array, observer.position_m);
      if (distance_m <= max_distance_m) continue;
      if (example.empty())
        example = fmt::format("\"{}\" is {:.0f} m from array \"{}\"", observer.name, distance_m,
                              array.name);
      if (!counted) ++points;
      counted = true;
    }
  }
  if (points == 0) return std::nullopt;
  return fmt::format(
      "{} receptor point{} the front of an array farther than --max-distance {:g} m and "
      "{} not computed against it (e.g. {}): give a larger --max-distance to include {}",
      points, points == 1 ? " sees" : "s see", max_distance_m, points == 1 ? "is" : "are", example,
      points == 1 ? "it" : "them");
}

// The outputs of a whole screening (one run, or merged shards) and what the command prints.
Status writeScreen(const Scene& scene, const HazardOptions& hazard, const ScreenIdentity& identity,
                   const ScreenResult& result, const std::filesystem::path& out,
                   HazardRunSummary& summary) {
  const ScreenOutputs outputs{.scene = &scene,
                              .options = &hazard,
                              .identity = &identity,
                              .result = &result,
                              .to_lon_lat = sceneToLonLat(scene)};
  GLARECAM_CHECK(writeScreenOutputs(outputs, out));
  Result<std::string> written = readTextFile(out / "screen.json");
  if (written) summary.document = nlohmann::json::parse(*written, nullptr, false);
  summary.table = screenSummaryText(outputs);
  return {};
}

Result<HazardRunSummary> runScreen(const HazardRunOptions& options, const Scene& scene,
                                   const std::vector<const ProfileTable*>& profiles,
                                   const HazardOptions& hazard) {
  ScreenOptions screen{.hazard = hazard, .shard = options.shard};
  ScreenIdentity identity;
  GLARECAM_ASSIGN(identity, screenIdentity(options.scene, hazard, profiles));
  ScreenResult result;
  {
    const std::string label =
        options.shard ? fmt::format("screen {}/{}", options.shard->index, options.shard->count)
                      : std::string("screen");
    std::optional<Progress> progress;
    std::size_t reported = 0;
    GLARECAM_ASSIGN(result,
                    screenHazard(scene, profiles, screen, [&](std::size_t done, std::size_t total) {
                      if (!progress)
                        progress.emplace(label, static_cast<int>(total), options.show_progress);
                      for (; reported < done; ++reported) progress->advance();
                    }));
    if (progress) progress->finish();
  }
  HazardRunSummary summary;
  summary.warnings = scene.warnings;
  if (options.shard) {
    summary.document = shardJson(identity, result);
    GLARECAM_CHECK(ensureDirectory(options.out));
    GLARECAM_CHECK(writeFileAtomic(options.out / "shard.json", summary.document.dump() + "\n"));
    summary.table = fmt::format(
        "shard {}/{}: {} of {} receptor points into {}\n", result.shard.index, result.shard.count,
        result.points.size(), result.counts.receptor_points, (options.out / "shard.json").string());
    return summary;
  }
  GLARECAM_CHECK(writeScreen(scene, hazard, identity, result, options.out, summary));
  return summary;
}

}  // namespace

Result<HazardRunSummary> runHazard(const HazardRunOptions& options) {
  GLARECAM_CHECK(options.validate());
  Scene scene;
  GLARECAM_ASSIGN(scene, readScene(options.scene));
  SceneProfiles read;
  GLARECAM_CHECK(readProfiles(scene, options.scene, options.profile, read));
  const std::vector<const ProfileTable*>& profiles = read.profiles;

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
  if (options.screen) return runScreen(options, scene, profiles, hazard);
  if (std::optional<std::string> beyond = beyondDistanceWarning(scene, hazard.max_distance_m))
    scene.warnings.push_back(std::move(*beyond));
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

Result<HazardRunSummary> runHazardMerge(const HazardMergeOptions& options) {
  GLARECAM_CHECK(options.validate());
  std::vector<ShardFile> shards;
  for (const std::filesystem::path& given : options.shards) {
    std::error_code error;
    const std::filesystem::path path =
        std::filesystem::is_directory(given, error) ? given / "shard.json" : given;
    if (!std::filesystem::exists(path, error))
      return badInput(given.string() +
                      ": no shard.json (a directory written by "
                      "`glarecam hazard --screen --shard I/N`)");
    ShardFile shard;
    GLARECAM_ASSIGN(shard, readShard(path));
    shards.push_back(std::move(shard));
  }
  ScreenResult result;
  GLARECAM_ASSIGN(result, mergeShardResults(shards));
  ScreenIdentity identity = shards.front().identity;
  const std::filesystem::path scene_path = options.scene.value_or(identity.scene);
  std::error_code missing;
  if (!options.scene && !std::filesystem::exists(scene_path, missing))
    return badInput(scene_path.string() +
                    ": the shards' scene is not there (moved? give it with --scene)");
  std::string sha256;
  GLARECAM_ASSIGN(sha256, sha256OfFile(scene_path));
  if (sha256 != identity.scene_sha256)
    return badInput(scene_path.string() +
                    ": not the scene the shards were computed from (its "
                    "SHA-256 differs; give the original with --scene)");
  Scene scene;
  GLARECAM_ASSIGN(scene, readScene(scene_path));
  if (scene.observers.size() != result.counts.receptor_points ||
      scene.arrays.size() != result.counts.arrays)
    return badInput(scene_path.string() +
                    ": the scene's receptor points or arrays differ from "
                    "the shards'");
  HazardOptions hazard;
  const nlohmann::json& o = identity.options;
  try {
    hazard.year = o.at("year").get<int>();
    hazard.step_s = o.at("step_s").get<int>();
    std::string models, criteria;
    for (const auto& m : o.at("models"))
      models += (models.empty() ? "" : ",") + m.get<std::string>();
    for (const auto& c : o.at("criteria"))
      criteria += (criteria.empty() ? "" : ",") + c.get<std::string>();
    GLARECAM_ASSIGN(hazard.models, parseModels(models, "shard models"));
    GLARECAM_ASSIGN(hazard.criteria, parseCriteria(criteria, "shard criteria"));
    if (!o.at("max_distance_m").is_null())
      hazard.max_distance_m = o.at("max_distance_m").get<double>();
  } catch (const nlohmann::json::exception& e) {
    return badInput(shards.front().path.string() + ": unreadable options: " + e.what());
  }
  HazardRunSummary summary;
  GLARECAM_CHECK(writeScreen(scene, hazard, identity, result, options.out, summary));
  return summary;
}

}  // namespace glarecam::hazard
