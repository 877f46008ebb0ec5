#include "calibration/angular_plane.h"

#include <cmath>
#include <numbers>

#include "core/angles.h"

namespace glarecam::calibration {
namespace {

Ray normalised(double x, double y, double z) {
  const double n = std::sqrt(x * x + y * y + z * z);
  return {x / n, y / n, z / n};
}

double dot(const Ray& a, const Ray& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

}  // namespace

AngularPlane::AngularPlane(const Ray& centre) : centre_(normalised(centre.x, centre.y, centre.z)) {
  // Image horizontal (+x) made perpendicular to the centre, then vertical = centre x horizontal,
  // which points toward +y (down) for a centre in front of the camera.
  const Ray& c = centre_;
  horizontal_ = normalised(1.0 - c.x * c.x, -c.x * c.y, -c.x * c.z);
  const Ray& h = horizontal_;
  vertical_ = {c.y * h.z - c.z * h.y, c.z * h.x - c.x * h.z, c.x * h.y - c.y * h.x};
}

PlanePointDeg AngularPlane::toPlane(const Ray& ray) const {
  const double p = dot(ray, horizontal_), q = dot(ray, vertical_);
  const double sideways = std::hypot(p, q);
  if (!(sideways > 0)) return {};
  const double rho_deg = degrees(std::atan2(sideways, dot(ray, centre_)));
  return {rho_deg * p / sideways, rho_deg * q / sideways};
}

Ray AngularPlane::toRay(const PlanePointDeg& point) const {
  const double rho = radians(std::hypot(point.x_deg, point.y_deg));
  if (!(rho > 0)) return centre_;
  const double cos_psi = radians(point.x_deg) / rho, sin_psi = radians(point.y_deg) / rho;
  const double along = std::cos(rho), across = std::sin(rho);
  const double h = across * cos_psi, v = across * sin_psi;
  return normalised(along * centre_.x + h * horizontal_.x + v * vertical_.x,
                    along * centre_.y + h * horizontal_.y + v * vertical_.y,
                    along * centre_.z + h * horizontal_.z + v * vertical_.z);
}

DirectionDeg directionFromAxis(const Ray& ray) {
  return {degrees(std::atan2(ray.x, ray.z)), degrees(std::atan2(ray.y, ray.z))};
}

Ray rayFromDirection(const DirectionDeg& direction) {
  return normalised(std::tan(radians(direction.horizontal_deg)),
                    std::tan(radians(direction.vertical_deg)), 1.0);
}

}  // namespace glarecam::calibration
