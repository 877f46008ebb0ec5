#include "hazard/geo_frame.h"

#include <fmt/format.h>
#include <proj.h>

#include <cmath>
#include <limits>
#include <mutex>

namespace glarecam::hazard {
namespace {

constexpr double kNotAPosition = std::numeric_limits<double>::quiet_NaN();

// PROJ marks a point it cannot convert with HUGE_VAL; we give NaN, which every check refuses.
double projValueOrNan(double value) { return std::isfinite(value) ? value : kNotAPosition; }

}  // namespace

// One PROJ context (contexts are not shared between threads) and its transformation; the mutex
// serialises the frame's users.
struct GeoFrame::Transform {
  struct ContextDeleter {
    void operator()(PJ_CONTEXT* context) const { proj_context_destroy(context); }
  };
  struct TransformationDeleter {
    void operator()(PJ* transformation) const { proj_destroy(transformation); }
  };
  std::unique_ptr<PJ_CONTEXT, ContextDeleter> context;
  std::unique_ptr<PJ, TransformationDeleter> transformation;
  std::mutex mutex;
};

std::string geoFramePipeline(double longitude_deg, double latitude_deg, double height_m) {
  // Degrees in (unitconvert), geocentric Cartesian on WGS84 (cart), then rotated and shifted to
  // the origin's east–north–up (topocentric, whose origin is given geodetically).
  return fmt::format(
      "+proj=pipeline +step +proj=unitconvert +xy_in=deg +xy_out=rad +step +proj=cart "
      "+ellps=WGS84 +step +proj=topocentric +ellps=WGS84 +lon_0={} +lat_0={} +h_0={}",
      longitude_deg, latitude_deg, height_m);
}

Result<std::unique_ptr<GeoFrame::Transform>> GeoFrame::makeTransform(const LonLatH& origin) {
  auto transform = std::make_unique<GeoFrame::Transform>();
  transform->context.reset(proj_context_create());
  if (!transform->context) return fail(ErrorCode::kInternal, "PROJ: cannot create a context");
  // The pipeline is a PROJ string of operators only: no database, no grids, no network.
  proj_context_set_enable_network(transform->context.get(), 0);
  proj_log_level(transform->context.get(), PJ_LOG_NONE);  // its errors go into ours, not stderr
  const std::string pipeline = geoFramePipeline(origin[0], origin[1], origin[2]);
  transform->transformation.reset(proj_create(transform->context.get(), pipeline.c_str()));
  if (!transform->transformation) {
    const int code = proj_context_errno(transform->context.get());
    return fail(ErrorCode::kInternal,
                fmt::format("PROJ refuses the local frame \"{}\": {}", pipeline,
                            proj_context_errno_string(transform->context.get(), code)));
  }
  return transform;
}

GeoFrame::GeoFrame(LonLatH origin, std::unique_ptr<Transform> transform)
    : origin_(origin), transform_(std::move(transform)) {}

Result<GeoFrame> GeoFrame::make(double longitude_deg, double latitude_deg, double height_m) {
  if (!(std::abs(longitude_deg) <= 180) || !(std::abs(latitude_deg) <= 90) ||
      !std::isfinite(height_m)) {
    return badInput(fmt::format("the origin ({}, {}, {}) is not a longitude, latitude and height",
                                longitude_deg, latitude_deg, height_m));
  }
  const LonLatH origin{longitude_deg, latitude_deg, height_m};
  std::unique_ptr<Transform> transform;
  GLARECAM_ASSIGN(transform, makeTransform(origin));
  return GeoFrame(origin, std::move(transform));
}

// A copy makes its own transformation; the original's was made from the same origin, so this
// one cannot fail but for memory (then the copy converts every point to NaN).
GeoFrame::GeoFrame(const GeoFrame& other) : origin_(other.origin_) {
  if (!other.transform_) return;
  Result<std::unique_ptr<Transform>> transform = makeTransform(origin_);
  if (transform) transform_ = std::move(*transform);
}
GeoFrame::GeoFrame(GeoFrame&& other) noexcept = default;
GeoFrame& GeoFrame::operator=(const GeoFrame& other) {
  if (this != &other) *this = GeoFrame(other);
  return *this;
}
GeoFrame& GeoFrame::operator=(GeoFrame&& other) noexcept = default;
GeoFrame::~GeoFrame() = default;

std::string GeoFrame::pipeline() const {
  return geoFramePipeline(origin_[0], origin_[1], origin_[2]);
}

std::vector<Vec3> GeoFrame::toEnu(std::span<const LonLatH> positions) const {
  std::vector<double> x, y, z;
  for (const LonLatH& position : positions) {
    x.push_back(position[0]), y.push_back(position[1]), z.push_back(position[2]);
  }
  std::vector<Vec3> points(positions.size(), Vec3{kNotAPosition, kNotAPosition, kNotAPosition});
  if (!transform_ || positions.empty()) return points;
  {
    const std::lock_guard lock(transform_->mutex);
    proj_trans_generic(transform_->transformation.get(), PJ_FWD, x.data(), sizeof(double), x.size(),
                       y.data(), sizeof(double), y.size(), z.data(), sizeof(double), z.size(),
                       nullptr, 0, 0);
  }
  for (std::size_t i = 0; i < points.size(); ++i)
    points[i] = {projValueOrNan(x[i]), projValueOrNan(y[i]), projValueOrNan(z[i])};
  return points;
}

std::vector<LonLatH> GeoFrame::toLonLatH(std::span<const Vec3> points_m) const {
  std::vector<double> x, y, z;
  for (const Vec3& point : points_m)
    x.push_back(point.x), y.push_back(point.y), z.push_back(point.z);
  std::vector<LonLatH> positions(points_m.size(),
                                 LonLatH{kNotAPosition, kNotAPosition, kNotAPosition});
  if (!transform_ || points_m.empty()) return positions;
  {
    const std::lock_guard lock(transform_->mutex);
    proj_trans_generic(transform_->transformation.get(), PJ_INV, x.data(), sizeof(double), x.size(),
                       y.data(), sizeof(double), y.size(), z.data(), sizeof(double), z.size(),
                       nullptr, 0, 0);
  }
  for (std::size_t i = 0; i < positions.size(); ++i)
    positions[i] = {projValueOrNan(x[i]), projValueOrNan(y[i]), projValueOrNan(z[i])};
  return positions;
}

Vec3 GeoFrame::toEnu(double longitude_deg, double latitude_deg, double height_m) const {
  const LonLatH position{longitude_deg, latitude_deg, height_m};
  return toEnu(std::span<const LonLatH>(&position, 1))[0];
}

LonLatH GeoFrame::toLonLatH(Vec3 enu_m) const {
  return toLonLatH(std::span<const Vec3>(&enu_m, 1))[0];
}

}  // namespace glarecam::hazard
