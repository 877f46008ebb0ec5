// Screening a district (docs/hazard.md, "Screening a district" and "Running on a cluster"):
// many arrays against many receptors, reduced to candidate pairs by distance and by the side of
// the array's plane (candidate_pairs.h), each pair rejected per day by the bound on where the
// sun's mirror image can be before any step of the day is computed, and the receptor points
// computed in batches that keep none of a year's steps: memory stays bounded by the batch, not
// the district. Each point's result is a pure function of the scene and the options, so a
// point gives the same numbers in any batch and in any shard.
//
// Sharding: `--shard I/N` computes a deterministic 1/N of the candidate pairs, whole receptor
// points at a time (a point's minutes are the union over its arrays, so its pairs stay
// together): the points in a Z-order over the ground (neighbours together, so that they share
// their arrays' steps within a batch) cut into N runs of about equal estimated cost (pair-days
// the bound lets through, from an hourly sun). A shard writes shard.json;
// mergeShards() combines shards into exactly the outputs one run writes (writeScreenOutputs), in
// any order, and refuses shards of another scene, other options, a missing or repeated shard.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "core/error.h"
#include "hazard/hazard_calculation.h"
#include "hazard/profile_table.h"
#include "hazard/scene.h"

namespace glarecam::hazard {

inline constexpr const char* kShardSchema = "glarecam.hazard-shard/1";
inline constexpr const char* kScreenSchema = "glarecam.hazard-screen/1";
// More shards than this is a typing error: a district has at most tens of thousands of points.
inline constexpr unsigned kMaxShards = 100000;
// Receptor points computed together: their tallies for the year (days × models each) are the
// batch's memory, about 130 MB at 1024 points and 6 models.
inline constexpr std::size_t kDefaultBatchPoints = 1024;

struct ShardSpec {
  unsigned index = 0, count = 1;  // index in [0, count): a job array's task index
};
// "I/N" (I from 0, as Slurm's SLURM_ARRAY_TASK_ID and Kubernetes' JOB_COMPLETION_INDEX count);
// kBadInput naming `option` otherwise.
Result<ShardSpec> parseShard(std::string_view text, std::string_view option);

struct ScreenOptions {
  HazardOptions hazard;  // max_distance_m bounds the pairs; steps are never kept
  std::optional<ShardSpec> shard;
  std::size_t batch_points = kDefaultBatchPoints;
  Status validate() const;
};

// One receptor point under one model.
struct ScreenedModel {
  double minutes_per_year = 0;
  int days_with_glare = 0;
  double max_minutes_per_day = 0;
  int worst_day = -1;  // day of the year (0 = 1 January) with the most minutes; −1: none
  std::int64_t steps_beyond_method = 0, steps_unknown_spread = 0;
  std::array<double, 3> ocular_minutes{};  // green, yellow, red
  double unclassified_minutes = 0;
  std::optional<double> peak_luminance_cd_m2;
  std::vector<std::size_t> arrays;  // indices into scene.arrays of those that glare here, sorted
};

struct ScreenedPoint {
  std::size_t observer = 0;           // index into scene.observers
  std::size_t candidates = 0;         // arrays within the distance whose front it sees
  std::int64_t pair_days = 0;         // (candidate, day) pairs the day-level bound let through
  std::vector<ScreenedModel> models;  // per options.models
};

// Over the whole scene, whatever the shard.
struct ScreenCounts {
  std::size_t receptor_points = 0, arrays = 0;
  std::size_t pairs_within_distance = 0;
  std::size_t pairs_behind = 0;  // within the distance, but the point sees the array's back
  std::size_t candidate_pairs = 0;
};

struct ScreenResult {
  ShardSpec shard;
  ScreenCounts counts;
  std::vector<ScreenedPoint> points;  // this shard's, by observer index
};

using ScreenProgress = std::function<void(std::size_t points_done, std::size_t points)>;

// Screens the scene (or the options' shard of it). kBadInput for invalid options or profiles as
// computeHazard.
Result<ScreenResult> screenHazard(const Scene& scene,
                                  const std::vector<const ProfileTable*>& profiles,
                                  const ScreenOptions& options,
                                  const ScreenProgress& progress = {});

// What identifies a screening: the scene file's SHA-256, every option that changes a number, and
// the contents of the profiles and the weather file (their SHA-256).
// Shards merge only when this is equal in all of them.
struct ScreenIdentity {
  std::filesystem::path scene;  // absolute
  std::string scene_sha256;
  nlohmann::json options;  // year, step_s, models, criteria, sun, max_distance_m
};
Result<ScreenIdentity> screenIdentity(const std::filesystem::path& scene,
                                      const HazardOptions& options,
                                      const std::vector<const ProfileTable*>& profiles);

// shard.json: the identity, the counts and the shard's points.
nlohmann::json shardJson(const ScreenIdentity& identity, const ScreenResult& result);
// Reads shard.json back (kBadInput naming the file for anything malformed).
struct ShardFile {
  std::filesystem::path path;
  ScreenIdentity identity;
  ScreenResult result;
};
Result<ShardFile> readShard(const std::filesystem::path& path);
// The shards of one screening combined: the whole result, exactly as one run makes it. kBadInput
// for shards of different screenings, a shard missing or given twice.
Result<ScreenResult> mergeShardResults(const std::vector<ShardFile>& shards);

// Turns a local east–north–up position into [longitude, latitude, height] for GeoJSON.
using ToLonLat = std::function<std::array<double, 3>(Vec3)>;

// The outputs of a whole screening into `out`: screen.json (the identity, the counts, per
// receptor as written its worst point, per array the receptors it glares), receptors.csv (a row
// per receptor point) and hazard.geojson (hazard_geojson.h, the map an ordinary run writes too).
struct ScreenOutputs {
  const Scene* scene = nullptr;
  const HazardOptions* options = nullptr;
  const ScreenIdentity* identity = nullptr;
  const ScreenResult* result = nullptr;
  ToLonLat to_lon_lat;
};
Status writeScreenOutputs(const ScreenOutputs& outputs, const std::filesystem::path& out);
// The short summary for stdout.
std::string screenSummaryText(const ScreenOutputs& outputs);

}  // namespace glarecam::hazard
