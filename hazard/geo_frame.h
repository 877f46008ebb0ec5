// The local east–north–up frame of a geographic scene (../shared/docs/hazard.md, "Geographic
// scenes"; docs/hazard.md): x east, y north, z up along the WGS84 ellipsoid's normal at the
// origin, in metres, the frame every scene is computed in. Geodetic positions (longitude and
// latitude in degrees on WGS84, height in metres above the ellipsoid) go there exactly, through
// PROJ's geocentric (`cart`) and `topocentric` conversions, and back; nothing here approximates
// the Earth as flat, so a point 10 km away lands 7.8 m below the origin's horizontal plane, where
// it is. Heights "above sea level" are taken as heights above the ellipsoid (docs/hazard.md says
// why that is exact enough within a district).
//
// A GeoFrame is a value: copying it makes its own PROJ transformation. The conversions are
// const and thread-safe (one PROJ context per frame, guarded by a mutex); convert many points
// at once with the vector overloads, which take the lock once.
#pragma once

#include <array>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "core/error.h"
#include "hazard/vec3.h"

namespace glarecam::hazard {

// Longitude, latitude (degrees, WGS84) and height above the ellipsoid (metres).
using LonLatH = std::array<double, 3>;

class GeoFrame {
 public:
  // The frame whose origin is at the given geodetic position. kBadInput when the longitude or
  // latitude is out of range or not finite, kInternal when PROJ refuses the transformation.
  static Result<GeoFrame> make(double longitude_deg, double latitude_deg, double height_m);

  GeoFrame(const GeoFrame& other);
  GeoFrame(GeoFrame&& other) noexcept;
  GeoFrame& operator=(const GeoFrame& other);
  GeoFrame& operator=(GeoFrame&& other) noexcept;
  ~GeoFrame();

  double longitudeDeg() const { return origin_[0]; }
  double latitudeDeg() const { return origin_[1]; }
  double heightM() const { return origin_[2]; }  // above the ellipsoid

  // A geodetic position in the frame (metres east, north, up of the origin).
  Vec3 toEnu(double longitude_deg, double latitude_deg, double height_m) const;
  // A point of the frame as longitude, latitude (degrees) and height above the ellipsoid.
  LonLatH toLonLatH(Vec3 enu_m) const;
  // The same for many points at once (one lock, one call into PROJ).
  std::vector<Vec3> toEnu(std::span<const LonLatH> positions) const;
  std::vector<LonLatH> toLonLatH(std::span<const Vec3> points_m) const;

  // The PROJ pipeline from longitude, latitude (degrees) and height to the frame, as PROJ's
  // command-line tools take it (`cct -d 6 PIPELINE`).
  std::string pipeline() const;

 private:
  struct Transform;
  static Result<std::unique_ptr<Transform>> makeTransform(const LonLatH& origin);
  GeoFrame(LonLatH origin, std::unique_ptr<Transform> transform);

  LonLatH origin_{};
  std::unique_ptr<Transform> transform_;
};

// The PROJ pipeline of the frame at an origin (see GeoFrame::pipeline).
std::string geoFramePipeline(double longitude_deg, double latitude_deg, double height_m);

}  // namespace glarecam::hazard
