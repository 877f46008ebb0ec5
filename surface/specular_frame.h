// Directions at a reflecting sample (docs/brdf.md, "Angles"): in the sample's frame z is the
// surface normal, θ the polar angle from it and φ the azimuth; an incident direction (θ_i, φ_i)
// points toward the source, so the specular direction is (θ_i, φ_i + 180°). The specular frame of
// one incidence is the camera route's view of the glare spot: its z axis the specular direction,
// its y axis (the image vertical) in the plane of incidence toward grazing, its x axis across that
// plane. The glare analysis runs in the angular plane around it (calibration/angular_plane.h),
// where a full axis is an angle on the sky. Pure geometry, shared by the surface models, the
// simulated goniophotometer and the BRDF route.
#pragma once

#include <utility>

#include "calibration/angular_plane.h"
#include "calibration/camera_model.h"

namespace glarecam::surface {

// A unit direction in the sample's frame from (θ, φ) in degrees, and back (φ in [0, 360)).
calibration::Ray sampleDirection(double theta_deg, double phi_deg);
std::pair<double, double> sampleAngles(const calibration::Ray& direction);

class SpecularFrame {
 public:
  SpecularFrame(double incident_theta_deg, double incident_phi_deg);
  // A direction of the sample's frame, as a ray of the specular frame (z toward specular).
  calibration::Ray toFrame(double theta_deg, double phi_deg) const;
  calibration::Ray toFrame(const calibration::Ray& sample_direction) const;
  // The sample-frame direction (θ, φ in degrees, φ in [0, 360)) of a specular-frame ray, and the
  // unit vector.
  std::pair<double, double> fromFrame(const calibration::Ray& ray) const;
  calibration::Ray sampleRay(const calibration::Ray& ray) const;
  // The angular plane's point of a sample-frame direction (x across, y along the plane of
  // incidence toward grazing), and back.
  calibration::PlanePointDeg toPlane(double theta_deg, double phi_deg) const;
  std::pair<double, double> fromPlane(const calibration::PlanePointDeg& point) const;
  calibration::Ray sampleRayAt(const calibration::PlanePointDeg& point) const;

 private:
  double h_[3], v_[3], r_[3];  // the frame's x, y, z axes in the sample's frame
  calibration::AngularPlane plane_;
};

}  // namespace glarecam::surface
