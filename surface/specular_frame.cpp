#include "surface/specular_frame.h"

#include <algorithm>
#include <cmath>

#include "core/angles.h"

namespace glarecam::surface {

using calibration::PlanePointDeg;
using calibration::Ray;

namespace {
double dot(const double a[3], const Ray& b) { return a[0] * b.x + a[1] * b.y + a[2] * b.z; }
}  // namespace

Ray sampleDirection(double theta_deg, double phi_deg) {
  const double t = radians(theta_deg), p = radians(phi_deg);
  return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

std::pair<double, double> sampleAngles(const Ray& w) {
  const double n = std::sqrt(w.x * w.x + w.y * w.y + w.z * w.z);
  const double theta = degrees(std::acos(std::clamp(w.z / n, -1.0, 1.0)));
  double phi = degrees(std::atan2(w.y, w.x));
  if (phi < 0) phi += 360;
  if (phi >= 360) phi -= 360;
  return {theta, phi};
}

SpecularFrame::SpecularFrame(double incident_theta_deg, double incident_phi_deg)
    : plane_(Ray{0, 0, 1}) {
  const double t = radians(incident_theta_deg), p = radians(incident_phi_deg);
  // The specular direction (θ_i, φ_i + 180°), its derivative in θ (toward grazing, in the plane
  // of incidence) and the axis across the plane that makes (h, v, r) right-handed.
  r_[0] = -std::sin(t) * std::cos(p);
  r_[1] = -std::sin(t) * std::sin(p);
  r_[2] = std::cos(t);
  v_[0] = -std::cos(t) * std::cos(p);
  v_[1] = -std::cos(t) * std::sin(p);
  v_[2] = -std::sin(t);
  h_[0] = v_[1] * r_[2] - v_[2] * r_[1];
  h_[1] = v_[2] * r_[0] - v_[0] * r_[2];
  h_[2] = v_[0] * r_[1] - v_[1] * r_[0];
}

Ray SpecularFrame::toFrame(const Ray& w) const { return {dot(h_, w), dot(v_, w), dot(r_, w)}; }

Ray SpecularFrame::toFrame(double theta_deg, double phi_deg) const {
  return toFrame(sampleDirection(theta_deg, phi_deg));
}

Ray SpecularFrame::sampleRay(const Ray& ray) const {
  const double n = std::sqrt(ray.x * ray.x + ray.y * ray.y + ray.z * ray.z);
  Ray w;
  w.x = (h_[0] * ray.x + v_[0] * ray.y + r_[0] * ray.z) / n;
  w.y = (h_[1] * ray.x + v_[1] * ray.y + r_[1] * ray.z) / n;
  w.z = (h_[2] * ray.x + v_[2] * ray.y + r_[2] * ray.z) / n;
  return w;
}

std::pair<double, double> SpecularFrame::fromFrame(const Ray& ray) const {
  return sampleAngles(sampleRay(ray));
}

PlanePointDeg SpecularFrame::toPlane(double theta_deg, double phi_deg) const {
  return plane_.toPlane(toFrame(theta_deg, phi_deg));
}

std::pair<double, double> SpecularFrame::fromPlane(const PlanePointDeg& point) const {
  return fromFrame(plane_.toRay(point));
}

Ray SpecularFrame::sampleRayAt(const PlanePointDeg& point) const {
  return sampleRay(plane_.toRay(point));
}

}  // namespace glarecam::surface
