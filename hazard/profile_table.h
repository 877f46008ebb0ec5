// A module's glare profile (pipeline/glare_profile.h, read by its one reader) as the hazard
// calculation asks it: whether the module glares at an α, and the beam spread and luminances
// there, interpolated between the profile's whole-degree rows (../shared/docs/hazard.md,
// "Inputs"):
//   - glare is possible at α iff α lies in one of glare_ranges_deg (ends included) and
//     α ≤ kProfileAlphaMaxDeg (80°); above it the method defines no limit ("beyond the method");
//   - an axis (and the circular cone's β) at a fractional α is linear between the two rows around
//     it; where one of them is null, the other's value; where both are null but α glares, the
//     spread is unknown (reported, never taken as "no glare");
//   - Lmax and the glare limit are linear in ln L.
// Profiles written by earlier versions stay readable (the reader's rules): a row's lmax_cd_m2,
// limit_cd_m2, axes and circular_beam may be null or absent. An axis below kMinAxisDeg counts as
// absent (no region, and no ellipse so thin that the test would crawl along it).
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/error.h"
#include "pipeline/glare_profile.h"

namespace glarecam::hazard {

inline constexpr double kMinAxisDeg = 0.001;

enum class SpreadStatus {
  kNoGlare,       // α outside the glare ranges
  kGlare,         // glares, with the spread below where the profile gives it
  kBeyondMethod,  // α > 80°: the method defines no limit
};

struct SpreadAt {
  SpreadStatus status = SpreadStatus::kNoGlare;
  // Full angles in degrees when status is kGlare and the profile's rows around α give them;
  // absent there, a model that needs them has an unknown spread.
  std::optional<double> vertical_deg, horizontal_deg, circle_deg;
};

struct LuminancesAt {
  std::optional<double> lmax_cd_m2, limit_cd_m2;  // linear in ln L between the rows
};

// The glare region at one α for a referred luminance level, from the profile's contour ladder
// (ProfileTable::regionAtLevel).
struct LadderRegion {
  enum class Status {
    kNoGlare,  // the level lies above the referred peak Lmax(α)
    kRegion,   // the contour at the level: full axes and solid angle
    kUnknown,  // no Lmax at α, or the level below the ladder's lowest rung: no spread is claimed
  };
  Status status = Status::kUnknown;
  double vertical_deg = 0, horizontal_deg = 0, solid_angle_sr = 0;
  bool beyond_ladder = false;  // α outside the ladder's measured degrees: its nearest degree's
  bool above_rungs = false;    // between the highest rung and the peak: shrunk toward the peak
};

class ProfileTable {
 public:
  explicit ProfileTable(const pipeline::GlareProfile& profile);
  // Reads and validates a profile file (pipeline::readGlareProfile); errors name the file and the
  // field (kBadInput).
  static Result<ProfileTable> read(const std::filesystem::path& path);
  // The same for a document read already (`file` names it in errors).
  static Result<ProfileTable> fromJson(const nlohmann::json& document, const std::string& file);

  SpreadAt at(double alpha_deg) const;
  // The spread the rows give at α whether or not the module glares there (status kGlare).
  SpreadAt spreadAt(double alpha_deg) const;
  // Whether some α in [from, to] lies in a glare range.
  bool glaresWithin(double from_deg, double to_deg) const;
  // Lmax and the glare limit at α (0–80°; beyond, the 80° row's), for the luminance seen.
  LuminancesAt luminancesAt(double alpha_deg) const;
  // The reference illuminance the profile's luminances are referred to, when it is referred and
  // carries a contour ladder: what a sun of another brightness needs (--sun clear-sky, weather).
  std::optional<double> ladderReferenceLx() const { return ladder_reference_lx_; }
  // The region where the referred luminance reaches `level_cd_m2` at α (docs/hazard.md, "The
  // sun's brightness"): none above the fitted Lmax(α); else the ladder's contour at the level
  // (pipeline::contourAt: linear in ln level between rungs, linear in α between degrees); between
  // the highest rung and the peak, the highest rung shrunk toward the peak as a log-quadratic
  // peak does, axes ∝ √ln(Lmax / level); at an α outside the ladder's degrees, its nearest degree's
  // ladder. Only for a profile with ladderReferenceLx().
  LadderRegion regionAtLevel(double alpha_deg, double level_cd_m2) const;
  // The largest full axis of any contour of the ladder (its lowest rung's, usually), degrees.
  double maxLadderAxisDeg() const { return max_ladder_axis_deg_; }
  // The spread the method's last α gives (80°, or the largest α below it with axes): the region
  // used to count "beyond the method" steps. nullopt when the profile has no axes at all.
  const std::optional<SpreadAt>& lastDefined() const { return last_defined_; }
  // The largest full axis (ellipse or circle) anywhere in the profile, in degrees: bounds every
  // region this profile makes (a cheap rejection test).
  double maxFullAxisDeg() const { return max_full_axis_deg_; }

  const std::filesystem::path& path() const { return path_; }
  const std::string& module() const { return module_; }
  // Made from stacks of the simulated camera: not a measurement (pipeline/sweep_table.h).
  bool simulated() const { return simulated_; }
  // Identity for the report: module, simulated and calibrations, date and source when the file
  // has them, and the path it was read from.
  const nlohmann::json& identity() const { return identity_; }
  const std::vector<pipeline::AlphaRange>& glareRanges() const { return ranges_; }

 private:
  struct Row {
    std::optional<double> vertical_deg, horizontal_deg, circle_deg;
    std::optional<double> lmax_cd_m2, limit_cd_m2;
  };

  std::filesystem::path path_;
  std::string module_;
  bool simulated_ = false;
  nlohmann::json identity_;
  std::vector<pipeline::AlphaRange> ranges_;
  std::array<Row, pipeline::kProfileAlphaMaxDeg + 1> rows_{};
  std::optional<SpreadAt> last_defined_;
  double max_full_axis_deg_ = 0;
  std::shared_ptr<const pipeline::GlareProfile> profile_;
  std::optional<double> ladder_reference_lx_;
  double max_ladder_axis_deg_ = 0;
};

}  // namespace glarecam::hazard
