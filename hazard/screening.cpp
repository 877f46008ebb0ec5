#include "hazard/screening.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <map>
#include <numeric>
#include <set>

#include "core/angles.h"
#include "core/atomic_file.h"
#include "core/csv.h"
#include "core/sha256.h"
#include "core/text_file.h"
#include "core/time.h"
#include "hazard/candidate_pairs.h"
#include "hazard/criteria.h"
#include "hazard/hazard_geojson.h"
#include "hazard/obstruction.h"
#include "sun/solar_track.h"

namespace glarecam::hazard {
namespace {

using nlohmann::json;

// The cost estimate's sun: hourly, each day's polar-angle range widened by this much for what
// the hours between miss (the sun's polar angle moves at most ~0.25° an hour, refraction near
// the horizon adds ~0.6°). An estimate only: the calculation applies the exact bound.
constexpr int kEstimateStepS = 3600;
constexpr double kEstimateMarginRad = 0.02;  // 1.15°
constexpr int kSecondsPerDayScreen = 86400;

// A shard naming more receptor points or arrays than this is damaged: a scene holds at most
// kMaxReceptorPoints per receptor, and a district far fewer than this.
constexpr std::size_t kMaxShardPoints = 100'000'000;

// Per day of the run, the sun's polar-angle range from hourly samples (the estimate's).
Result<std::vector<PoleAngleRange>> estimatePoleRanges(const Scene& scene,
                                                       const HazardOptions& options, int days) {
  const auto local_midnight = std::chrono::sys_days{std::chrono::year{options.year} / 1 / 1};
  const auto year_start = std::chrono::time_point_cast<std::chrono::microseconds>(local_midnight) -
                          std::chrono::microseconds(std::llround(scene.site.utc_offset_h * 3600e6));
  const Vec3 pole = celestialPole(scene.site.location.latitude_deg);
  const auto step = std::chrono::microseconds(std::int64_t{kEstimateStepS} * 1'000'000);
  const std::size_t per_day = kSecondsPerDayScreen / kEstimateStepS;
  std::vector<sun::SunDirection> track;
  GLARECAM_ASSIGN(
      track, sun::solarTrack(year_start + std::chrono::days(options.first_day) + step / 2, step,
                             per_day * static_cast<std::size_t>(days), scene.site.location));
  std::vector<PoleAngleRange> ranges(static_cast<std::size_t>(days),
                                     PoleAngleRange{.min_rad = std::numbers::pi, .max_rad = -1});
  for (std::size_t k = 0; k < track.size(); ++k) {
    const Vec3 sun{track[k].east, track[k].north, track[k].up};
    if (sun.z <= 0) continue;
    PoleAngleRange& range = ranges[k / per_day];
    const double theta = angleBetweenRad(sun, pole);
    range.min_rad = std::min(range.min_rad, theta - kEstimateMarginRad);
    range.max_rad = std::max(range.max_rad, theta + kEstimateMarginRad);
  }
  return ranges;
}

// A point's estimated cost: one for the point, and per candidate the days the bound is
// expected to let through (every day for a pair the bound cannot reject).
double estimatedCost(const Scene& scene, const std::vector<const ProfileTable*>& profiles,
                     std::size_t o, const std::vector<std::size_t>& candidates,
                     const std::vector<PoleAngleRange>& days, Vec3 pole) {
  double cost = 1;
  const Vec3 point = scene.observers[o].position_m;
  for (const std::size_t a : candidates) {
    const ArrayPolygon& array = scene.arrays[a];
    const Vec3 to_centre = array.centroid_m - point;
    const double distance_m = norm(to_centre);
    const double angular_radius =
        distance_m > array.radius_m ? std::asin(array.radius_m / distance_m) : std::numbers::pi;
    const double axis_deg =
        std::max(profiles[a]->maxFullAxisDeg(), profiles[a]->maxLadderAxisDeg());
    const double reach = radians(axis_deg / 2) + angular_radius;
    const double phi = mirroredPoleAngleRad(array, pole, normalised(to_centre));
    for (const PoleAngleRange& day : days) cost += dayMayReach(phi, reach, day) ? 1 : 0;
  }
  return cost;
}

// Receptor points in the order of a Z-order (Morton) curve over cells of kOrderCellM (half the
// default distance: a cell's points share most of their arrays), ties by index: neighbours
// follow each other, so that a batch's points share their arrays (an array's step and region
// are made once per step for every point of the batch that needs them). On make-city's district
// of 1000 roofs this costs the same as its own building-by-building order (78 s against 77 s of
// CPU); 10-m cells cost 10 % more.
constexpr double kOrderCellM = 50;
std::vector<std::size_t> spatialOrder(const Scene& scene) {
  double min_x = 0, min_y = 0;
  for (std::size_t o = 0; o < scene.observers.size(); ++o) {
    const Vec3& p = scene.observers[o].position_m;
    min_x = o == 0 ? p.x : std::min(min_x, p.x);
    min_y = o == 0 ? p.y : std::min(min_y, p.y);
  }
  const auto spread = [](std::uint32_t v) {  // the bits of v at the even positions of 64
    std::uint64_t x = v;
    x = (x | (x << 16)) & 0x0000FFFF0000FFFFull;
    x = (x | (x << 8)) & 0x00FF00FF00FF00FFull;
    x = (x | (x << 4)) & 0x0F0F0F0F0F0F0F0Full;
    x = (x | (x << 2)) & 0x3333333333333333ull;
    x = (x | (x << 1)) & 0x5555555555555555ull;
    return x;
  };
  std::vector<std::pair<std::uint64_t, std::size_t>> keyed;
  for (std::size_t o = 0; o < scene.observers.size(); ++o) {
    const Vec3& p = scene.observers[o].position_m;
    // Coordinates are within kMaxCoordinateM: 2e6 m / 10 m cells fit in 32 bits.
    const auto cell = [](double offset_m) {
      return static_cast<std::uint32_t>(std::max(0.0, std::floor(offset_m / kOrderCellM)));
    };
    keyed.emplace_back(spread(cell(p.x - min_x)) | (spread(cell(p.y - min_y)) << 1), o);
  }
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::size_t> order;
  order.reserve(keyed.size());
  for (const auto& [key, o] : keyed) order.push_back(o);
  return order;
}

// The points of shard `index`: the spatial order cut into `count` runs of about equal estimated
// cost (a point goes to the run its cost's middle falls in), so that each shard keeps its
// points' neighbours (and their arrays) together.
std::vector<std::size_t> shardPoints(const std::vector<std::size_t>& order,
                                     const std::vector<double>& costs, ShardSpec shard) {
  double total = 0;
  for (const std::size_t o : order) total += costs[o];
  std::vector<std::size_t> mine;
  double before = 0;
  for (const std::size_t o : order) {
    const double middle = before + costs[o] / 2;
    before += costs[o];
    const auto run = static_cast<unsigned>(
        std::min<double>(shard.count - 1, std::floor(middle / total * shard.count)));
    if (run == shard.index) mine.push_back(o);
  }
  return mine;
}

ScreenedPoint zeroPoint(std::size_t o, std::size_t models) {
  ScreenedPoint point;
  point.observer = o;
  point.models.resize(models);
  return point;
}

// The batch's scene: the site, the batch's points, the arrays any of them may see glare from
// (in scene order) and every obstruction. `arrays` receives the batch's arrays' scene indices.
Scene batchScene(const Scene& scene, const std::vector<std::size_t>& points,
                 const std::vector<std::vector<std::size_t>>& candidates,
                 std::vector<std::size_t>& arrays) {
  std::set<std::size_t> used;
  for (const std::size_t o : points) used.insert(candidates[o].begin(), candidates[o].end());
  arrays.assign(used.begin(), used.end());
  Scene batch;
  batch.path = scene.path;
  batch.site = scene.site;
  batch.version = scene.version;
  batch.obstructions = scene.obstructions;
  for (const std::size_t a : arrays) batch.arrays.push_back(scene.arrays[a]);
  for (const std::size_t o : points) batch.observers.push_back(scene.observers[o]);
  return batch;
}

json modelJson(const ScreenedModel& model) {
  json j = {{"minutes_per_year", model.minutes_per_year},
            {"days_with_glare", model.days_with_glare},
            {"max_minutes_per_day", model.max_minutes_per_day},
            {"worst_day", model.worst_day},
            {"steps_beyond_method", model.steps_beyond_method},
            {"steps_unknown_spread", model.steps_unknown_spread},
            {"ocular_minutes", model.ocular_minutes},
            {"unclassified_minutes", model.unclassified_minutes},
            {"peak_luminance_cd_m2", nullptr},
            {"arrays", model.arrays}};
  if (model.peak_luminance_cd_m2) j["peak_luminance_cd_m2"] = *model.peak_luminance_cd_m2;
  return j;
}

ScreenedModel modelFromJson(const json& j) {
  ScreenedModel model;
  model.minutes_per_year = j.at("minutes_per_year").get<double>();
  model.days_with_glare = j.at("days_with_glare").get<int>();
  model.max_minutes_per_day = j.at("max_minutes_per_day").get<double>();
  model.worst_day = j.at("worst_day").get<int>();
  model.steps_beyond_method = j.at("steps_beyond_method").get<std::int64_t>();
  model.steps_unknown_spread = j.at("steps_unknown_spread").get<std::int64_t>();
  model.ocular_minutes = j.at("ocular_minutes").get<std::array<double, 3>>();
  model.unclassified_minutes = j.at("unclassified_minutes").get<double>();
  if (!j.at("peak_luminance_cd_m2").is_null())
    model.peak_luminance_cd_m2 = j.at("peak_luminance_cd_m2").get<double>();
  model.arrays = j.at("arrays").get<std::vector<std::size_t>>();
  return model;
}

json countsJson(const ScreenCounts& counts) {
  return {{"receptor_points", counts.receptor_points},
          {"arrays", counts.arrays},
          {"pairs_within_distance", counts.pairs_within_distance},
          {"pairs_behind", counts.pairs_behind},
          {"candidate_pairs", counts.candidate_pairs}};
}

ScreenCounts countsFromJson(const json& j) {
  return {.receptor_points = j.at("receptor_points").get<std::size_t>(),
          .arrays = j.at("arrays").get<std::size_t>(),
          .pairs_within_distance = j.at("pairs_within_distance").get<std::size_t>(),
          .pairs_behind = j.at("pairs_behind").get<std::size_t>(),
          .candidate_pairs = j.at("candidate_pairs").get<std::size_t>()};
}

// Numbers as the shortest text that reads back to the same double (nlohmann's), so that the
// outputs of a merge equal those of one run byte for byte.
std::string number(double value) { return json(value).dump(); }

// Whether a point's model result is worse than another's: more minutes per year, then more on
// its worst day.
bool worse(const ScreenedModel& x, const ScreenedModel& y) {
  return std::tie(x.minutes_per_year, x.max_minutes_per_day) >
         std::tie(y.minutes_per_year, y.max_minutes_per_day);
}

}  // namespace

Result<ShardSpec> parseShard(std::string_view text, std::string_view option) {
  const std::string bad = std::string(option) + " " + std::string(text) +
                          ": expected I/N, the shard I of N (I from 0 to N - 1)";
  const std::size_t slash = text.find('/');
  if (slash == std::string_view::npos) return badInput(bad);
  ShardSpec shard;
  const std::string_view index = text.substr(0, slash), count = text.substr(slash + 1);
  const auto [index_end, index_error] =
      std::from_chars(index.data(), index.data() + index.size(), shard.index);
  const auto [count_end, count_error] =
      std::from_chars(count.data(), count.data() + count.size(), shard.count);
  if (index.empty() || count.empty() || index_error != std::errc() || count_error != std::errc() ||
      index_end != index.data() + index.size() || count_end != count.data() + count.size())
    return badInput(bad);
  if (shard.count == 0 || shard.count > kMaxShards)
    return badInput(std::string(option) + " " + std::string(text) + ": N must be in [1, " +
                    std::to_string(kMaxShards) + "]");
  if (shard.index >= shard.count)
    return badInput(std::string(option) + " " + std::string(text) +
                    ": I counts from 0 and must be below N (a job array's task index)");
  return shard;
}

Status ScreenOptions::validate() const {
  GLARECAM_CHECK(hazard.validate());
  if (batch_points == 0) return badInput("screening: batch_points must be positive");
  if (hazard.first_day != 0 || hazard.day_count != 0)
    return badInput("screening: a screening covers the whole year");
  return {};
}

Result<ScreenResult> screenHazard(const Scene& scene,
                                  const std::vector<const ProfileTable*>& profiles,
                                  const ScreenOptions& options, const ScreenProgress& progress) {
  GLARECAM_CHECK(options.validate());
  if (profiles.size() != scene.arrays.size() ||
      std::any_of(profiles.begin(), profiles.end(), [](const ProfileTable* p) { return !p; }))
    return badInput("hazard: every array needs a glare profile");
  ScreenResult result;
  result.shard = options.shard.value_or(ShardSpec{});
  CandidateCounts candidate_counts;
  const std::vector<std::vector<std::size_t>> candidates =
      candidateArrays(scene, options.hazard.max_distance_m, candidate_counts);
  result.counts = {.receptor_points = scene.observers.size(),
                   .arrays = scene.arrays.size(),
                   .pairs_within_distance = candidate_counts.within_distance,
                   .pairs_behind = candidate_counts.behind,
                   .candidate_pairs = 0};
  for (const auto& row : candidates) result.counts.candidate_pairs += row.size();

  // Batches and shards follow the spatial order; each point's numbers do not depend on them.
  const std::vector<std::size_t> order = spatialOrder(scene);
  std::vector<std::size_t> mine;
  if (result.shard.count == 1) {
    mine = order;
  } else {
    std::vector<PoleAngleRange> days;
    GLARECAM_ASSIGN(days,
                    estimatePoleRanges(scene, options.hazard, daysInYear(options.hazard.year)));
    const Vec3 pole = celestialPole(scene.site.location.latitude_deg);
    std::vector<double> costs(scene.observers.size());
    for (std::size_t o = 0; o < costs.size(); ++o)
      costs[o] = estimatedCost(scene, profiles, o, candidates[o], days, pole);
    mine = shardPoints(order, costs, result.shard);
  }

  const std::size_t models = options.hazard.models.size();
  HazardOptions hazard = options.hazard;
  hazard.keep_steps = false;
  // Points with no candidate never glare: no batch needed.
  std::vector<std::size_t> computed;
  for (const std::size_t o : mine)
    if (!candidates[o].empty()) computed.push_back(o);
  std::map<std::size_t, ScreenedPoint> points;
  for (const std::size_t o : mine)
    if (candidates[o].empty()) points.emplace(o, zeroPoint(o, models));
  std::size_t done = mine.size() - computed.size();
  if (progress) progress(done, mine.size());
  for (std::size_t first = 0; first < computed.size(); first += options.batch_points) {
    const std::vector<std::size_t> batch_points(
        computed.begin() + static_cast<std::ptrdiff_t>(first),
        computed.begin() +
            static_cast<std::ptrdiff_t>(std::min(computed.size(), first + options.batch_points)));
    std::vector<std::size_t> arrays;
    const Scene batch = batchScene(scene, batch_points, candidates, arrays);
    std::vector<const ProfileTable*> batch_profiles;
    for (const std::size_t a : arrays) batch_profiles.push_back(profiles[a]);
    HazardResult computed_batch;
    GLARECAM_ASSIGN(computed_batch, computeHazard(batch, batch_profiles, hazard));
    for (ScreenedPoint& point : screenedPoints(computed_batch, batch_points, arrays))
      points.emplace(point.observer, std::move(point));
    done += batch_points.size();
    if (progress) progress(done, mine.size());
  }
  for (auto& [o, point] : points) result.points.push_back(std::move(point));
  return result;
}

Result<ScreenIdentity> screenIdentity(const std::filesystem::path& scene,
                                      const HazardOptions& options,
                                      const std::vector<const ProfileTable*>& profiles) {
  ScreenIdentity identity;
  std::error_code error;
  identity.scene = std::filesystem::absolute(scene, error).lexically_normal();
  if (error) identity.scene = scene;
  GLARECAM_ASSIGN(identity.scene_sha256, sha256OfFile(scene));
  json models = json::array(), criteria = json::array();
  for (const GlareModel& model : options.models) models.push_back(model.name());
  for (const Criterion& criterion : options.criteria) criteria.push_back(criterion.id);
  identity.options = {{"year", options.year},      {"step_s", options.step_s},
                      {"models", models},          {"criteria", criteria},
                      {"sun", options.sun.name()}, {"max_distance_m", maxDistanceJson(options)}};
  // What the numbers also depend on, by content: every array's profile in order (one hash of
  // their hashes) and the weather file, so that shards of refitted profiles or another weather
  // file never merge.
  std::map<std::filesystem::path, std::string> profile_hashes;
  std::string hashes;
  for (const ProfileTable* profile : profiles) {
    std::string& hash = profile_hashes[profile->path()];
    if (hash.empty()) {
      if (profile->path().empty()) {
        hash = sha256Hex(profile->module());
      } else {
        GLARECAM_ASSIGN(hash, sha256OfFile(profile->path()));
      }
    }
    hashes += hash;
  }
  identity.options["profiles_sha256"] = sha256Hex(hashes);
  identity.options["weather_sha256"] = nullptr;
  if (options.sun.weather && !options.sun.weather->path.empty()) {
    std::string weather;
    GLARECAM_ASSIGN(weather, sha256OfFile(options.sun.weather->path));
    identity.options["weather_sha256"] = weather;
  }
  return identity;
}

json shardJson(const ScreenIdentity& identity, const ScreenResult& result) {
  json points = json::array();
  for (const ScreenedPoint& point : result.points) {
    json models = json::array();
    for (const ScreenedModel& model : point.models) models.push_back(modelJson(model));
    points.push_back({{"observer", point.observer},
                      {"candidates", point.candidates},
                      {"pair_days", point.pair_days},
                      {"models", models}});
  }
  return {{"schema", kShardSchema},
          {"scene", identity.scene.string()},
          {"scene_sha256", identity.scene_sha256},
          {"options", identity.options},
          {"shard", {{"index", result.shard.index}, {"count", result.shard.count}}},
          {"counts", countsJson(result.counts)},
          {"points", points}};
}

Result<ShardFile> readShard(const std::filesystem::path& path) {
  std::string text;
  GLARECAM_ASSIGN(text, readTextFile(path));
  ShardFile shard;
  shard.path = path;
  try {
    const json j = json::parse(text);
    if (!j.is_object() || j.value("schema", std::string()) != kShardSchema)
      return badInput(path.string() + ": not a shard (schema " + std::string(kShardSchema) + ")");
    shard.identity.scene = j.at("scene").get<std::string>();
    shard.identity.scene_sha256 = j.at("scene_sha256").get<std::string>();
    shard.identity.options = j.at("options");
    shard.result.shard = {.index = j.at("shard").at("index").get<unsigned>(),
                          .count = j.at("shard").at("count").get<unsigned>()};
    if (shard.result.shard.count == 0 || shard.result.shard.count > kMaxShards ||
        shard.result.shard.index >= shard.result.shard.count)
      return badInput(path.string() + ": shard index or count out of range");
    shard.result.counts = countsFromJson(j.at("counts"));
    for (const json& p : j.at("points")) {
      ScreenedPoint point;
      point.observer = p.at("observer").get<std::size_t>();
      point.candidates = p.at("candidates").get<std::size_t>();
      point.pair_days = p.at("pair_days").get<std::int64_t>();
      for (const json& m : p.at("models")) point.models.push_back(modelFromJson(m));
      shard.result.points.push_back(std::move(point));
    }
    // What the writer indexes with must be inside the scene the counts describe.
    const ScreenCounts& counts = shard.result.counts;
    const std::size_t models = shard.identity.options.at("models").size();
    if (counts.receptor_points > kMaxShardPoints || counts.arrays > kMaxShardPoints)
      return badInput(path.string() + ": receptor points or arrays out of range");
    for (const ScreenedPoint& point : shard.result.points) {
      bool inside = point.observer < counts.receptor_points && point.models.size() == models;
      for (const ScreenedModel& model : point.models)
        for (const std::size_t a : model.arrays) inside = inside && a < counts.arrays;
      if (!inside)
        return badInput(path.string() + ": receptor point " + std::to_string(point.observer) +
                        " names a point, an array or a number of models the shard's scene and "
                        "options do not have");
    }
  } catch (const json::exception& e) {
    return badInput(path.string() + ": not a readable shard: " + e.what());
  }
  return shard;
}

Result<ScreenResult> mergeShardResults(const std::vector<ShardFile>& shards) {
  if (shards.empty()) return badInput("hazard merge: no shard given");
  const ShardFile& first = shards.front();
  const unsigned count = first.result.shard.count;
  std::vector<const ShardFile*> by_index(count, nullptr);
  for (const ShardFile& shard : shards) {
    const auto differs = [&](const std::string& what) {
      return badInput(shard.path.string() + ": " + what + " differ from " + first.path.string() +
                      "'s: shards of another screening");
    };
    if (shard.identity.scene_sha256 != first.identity.scene_sha256)
      return differs("the scene's bytes (SHA-256)");
    if (shard.identity.options != first.identity.options) {
      std::string which = "the options";
      for (const auto& [key, value] : first.identity.options.items()) {
        if (!shard.identity.options.contains(key) || shard.identity.options[key] != value) {
          which = "the options (" + key + ": " +
                  (shard.identity.options.contains(key) ? shard.identity.options[key].dump()
                                                        : std::string("none")) +
                  " against " + value.dump() + ")";
          break;
        }
      }
      return differs(which);
    }
    if (shard.result.shard.count != count) return differs("the shard counts");
    if (!(countsJson(shard.result.counts) == countsJson(first.result.counts)))
      return differs("the scene's counts");
    const unsigned index = shard.result.shard.index;
    if (by_index[index])
      return badInput(shard.path.string() + ": shard " + std::to_string(index) + "/" +
                      std::to_string(count) + " is given twice (also " +
                      by_index[index]->path.string() + ")");
    by_index[index] = &shard;
  }
  for (unsigned i = 0; i < count; ++i) {
    if (!by_index[i])
      return badInput("hazard merge: shard " + std::to_string(i) + "/" + std::to_string(count) +
                      " is missing");
  }
  ScreenResult merged;
  merged.counts = first.result.counts;
  std::vector<const ScreenedPoint*> points(merged.counts.receptor_points, nullptr);
  for (const ShardFile& shard : shards) {
    for (const ScreenedPoint& point : shard.result.points) {
      if (point.observer >= points.size() || points[point.observer])
        return badInput(shard.path.string() + ": receptor point " + std::to_string(point.observer) +
                        " is out of range or in two shards");
      points[point.observer] = &point;
    }
  }
  for (std::size_t o = 0; o < points.size(); ++o) {
    if (!points[o])
      return badInput("hazard merge: receptor point " + std::to_string(o) + " is in no shard");
    merged.points.push_back(*points[o]);
  }
  return merged;
}

Status writeScreenOutputs(const ScreenOutputs& outputs, const std::filesystem::path& out) {
  const Scene& scene = *outputs.scene;
  const HazardOptions& options = *outputs.options;
  const ScreenResult& result = *outputs.result;
  if (result.points.size() != scene.observers.size())
    return badInput("screening: the result does not cover the scene's receptor points");
  GLARECAM_CHECK(ensureDirectory(out));
  const std::size_t models = options.models.size();

  // receptors.csv
  std::string csv =
      "point,receptor,kind,east_m,north_m,up_m,longitude_deg,latitude_deg,height_m,"
      "candidates";
  for (const GlareModel& model : options.models) {
    const std::string m = model.name();
    csv += fmt::format(",{0}_minutes_per_year,{0}_days,{0}_max_minutes_per_day,{0}_worst_day", m);
    for (const Criterion& criterion : options.criteria) csv += "," + m + "_" + criterion.id;
    csv += fmt::format(",{0}_ocular_class,{0}_arrays", m);
  }
  csv += "\n";
  // Per array and model, how many receptor points it glares.
  std::vector<std::vector<std::size_t>> glared(scene.arrays.size(),
                                               std::vector<std::size_t>(models, 0));
  std::size_t glaring_points = 0, glaring_pairs = 0;
  std::int64_t pair_days = 0;
  for (const ScreenedPoint& point : result.points) {
    const Observer& observer = scene.observers[point.observer];
    const Receptor& receptor = scene.receptors[observer.receptor];
    const std::array<double, 3> lon_lat = outputs.to_lon_lat(observer.position_m);
    pair_days += point.pair_days;
    csv += fmt::format("{},{},{},{},{},{},{},{},{},{}", quoteCsvField(observer.name),
                       quoteCsvField(receptor.name), receptorKindName(receptor.kind),
                       number(observer.position_m.x), number(observer.position_m.y),
                       number(observer.position_m.z), number(lon_lat[0]), number(lon_lat[1]),
                       number(lon_lat[2]), point.candidates);
    for (std::size_t m = 0; m < models; ++m) {
      const ScreenedModel& model = point.models[m];
      std::string arrays;
      for (const std::size_t a : model.arrays) {
        if (!arrays.empty()) arrays += ';';
        arrays += scene.arrays[a].name;
        ++glared[a][m];
      }
      if (m == 0) {
        glaring_points += model.minutes_per_year > 0 ? 1 : 0;
        glaring_pairs += model.arrays.size();
      }
      const std::string worst_day =
          model.worst_day >= 0 ? isoDate(options.year, model.worst_day) : std::string();
      csv += fmt::format(",{},{},{},{}", number(model.minutes_per_year), model.days_with_glare,
                         number(model.max_minutes_per_day), worst_day);
      for (const Criterion& criterion : options.criteria) {
        const Verdict verdict =
            assess(criterion, model.max_minutes_per_day, model.minutes_per_year / 60.0);
        csv += fmt::format(",{}", quoteCsvField(verdict.text));
      }
      csv += fmt::format(",{},{}", worstOcularClass(model), quoteCsvField(arrays));
    }
    csv += "\n";
  }
  json arrays_summary = json::array();
  for (std::size_t a = 0; a < scene.arrays.size(); ++a) {
    json summary = {{"name", scene.arrays[a].name}};
    for (std::size_t m = 0; m < models; ++m) summary[options.models[m].name()] = glared[a][m];
    arrays_summary.push_back(summary);
  }
  json geojson;
  GLARECAM_ASSIGN(geojson, hazardGeoJson({.scene = &scene,
                                          .options = &options,
                                          .points = &result.points,
                                          .to_lon_lat = outputs.to_lon_lat,
                                          .results = "screen.json"}));

  // screen.json: per receptor as written, its worst point under each model.
  json receptors = json::array();
  for (const Receptor& receptor : scene.receptors) {
    json entry = {{"name", receptor.name},
                  {"kind", receptorKindName(receptor.kind)},
                  {"points", receptor.count}};
    for (std::size_t m = 0; m < models; ++m) {
      const ScreenedPoint* worst = nullptr;
      for (std::size_t o = receptor.first; o < receptor.first + receptor.count; ++o) {
        const ScreenedPoint& point = result.points[o];
        if (!worst || worse(point.models[m], worst->models[m])) worst = &point;
      }
      if (!worst) continue;
      const ScreenedModel& model = worst->models[m];
      json verdicts = json::object();
      for (const Criterion& criterion : options.criteria)
        verdicts[criterion.id] =
            assess(criterion, model.max_minutes_per_day, model.minutes_per_year / 60.0).text;
      entry[options.models[m].name()] = {
          {"worst_point", scene.observers[worst->observer].name},
          {"minutes_per_year", model.minutes_per_year},
          {"days_with_glare", model.days_with_glare},
          {"max_minutes_per_day", model.max_minutes_per_day},
          {"worst_day",
           model.worst_day >= 0 ? json(isoDate(options.year, model.worst_day)) : json(nullptr)},
          {"verdicts", verdicts},
          {"ocular_class", worstOcularClass(model)}};
    }
    receptors.push_back(entry);
  }
  json criteria = json::array();
  for (const Criterion& criterion : options.criteria) criteria.push_back(criterionJson(criterion));
  json counts = countsJson(result.counts);
  counts["pair_days_computed"] = pair_days;
  counts["glaring_pairs"] = glaring_pairs;
  counts["glaring_receptor_points"] = glaring_points;
  const json screen = {{"schema", kScreenSchema},
                       {"scene", outputs.identity->scene.string()},
                       {"scene_sha256", outputs.identity->scene_sha256},
                       {"options", outputs.identity->options},
                       {"criteria", criteria},
                       {"counts", counts},
                       {"receptors", receptors},
                       {"arrays", arrays_summary}};

  GLARECAM_CHECK(writeFileAtomic(out / "receptors.csv", csv));
  GLARECAM_CHECK(writeFileAtomic(out / kHazardGeoJson, geojson.dump() + "\n"));
  GLARECAM_CHECK(writeFileAtomic(out / "screen.json", screen.dump(2) + "\n"));
  return {};
}

std::string screenSummaryText(const ScreenOutputs& outputs) {
  const ScreenResult& result = *outputs.result;
  const HazardOptions& options = *outputs.options;
  std::size_t glaring = 0;
  std::int64_t pair_days = 0;
  for (const ScreenedPoint& point : result.points) {
    glaring += point.models.front().minutes_per_year > 0 ? 1 : 0;
    pair_days += point.pair_days;
  }
  std::string text = fmt::format(
      "{} receptor points, {} arrays; within {} m: {} pairs, {} seeing an array's back, {} "
      "candidates; {} pair-days computed\n",
      result.counts.receptor_points, result.counts.arrays,
      std::isfinite(options.max_distance_m) ? number(options.max_distance_m) : "any",
      result.counts.pairs_within_distance, result.counts.pairs_behind,
      result.counts.candidate_pairs, pair_days);
  text +=
      fmt::format("{} receptor points see glare ({})\n", glaring, options.models.front().name());
  return text;
}

}  // namespace glarecam::hazard
