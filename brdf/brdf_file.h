// Goniophotometer files (docs/brdf.md, "Formats"): what `glarecam brdf` reads and the simulated
// goniophotometer writes. No vendor SDK; both formats are text.
//
//  pab-opto / Radiance (pabopto2bsdf): '#' header lines, then one "θ φ value" row per sample,
//    one file per angle of incidence. Header keys: "format: theta phi BSDF|DSF" (DSF = BSDF ·
//    cos θ), "intheta", "inphi" or "incident_angle θ φ" (the direction toward the source),
//    "upphi" (a rotation of every azimuth alike: the geometry it describes does not change),
//    "colorimetry: CIE-Y", 'sample_name "…"', and glarecam's "relative_noise" (the relative
//    standard uncertainty of one sample).
//  Zemax/OpticStudio BSDF data interchange: keywords Source, Symmetry (PlaneSymmetrical or
//    Asymmetrical), SpectralContent (Monochrome, or XYZ of which the Y blocks are read),
//    ScatterType (BRDF), SampleRotation, AngleOfIncidence, ScatterAzimuth and ScatterRadial (each
//    a count and the values, degrees), then data blocks "DataBegin … DataEnd" holding per sample
//    rotation and angle of incidence "TIS value" and one row per azimuth of one value per radial
//    angle; '#' comments. The scatter angles are around the specular direction: the radial angle
//    from it, the azimuth from the plane of incidence (0° toward grazing; docs/brdf.md), so that a
//    plane-symmetric file's 0–180° is mirrored across the plane of incidence.
//
// Every reader refuses with kBadInput and "FILE:LINE: problem": an unknown format (a window
// BSDF in the Klems basis says why it cannot serve), BTDF data, a value that is negative or not
// finite, an angle out of range, a missing header.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "brdf/brdf_measurement.h"
#include "core/error.h"

namespace glarecam::brdf {

// A file is refused beyond this size (a dense pab-opto file is a few MB).
inline constexpr std::uintmax_t kMaxBrdfFileBytes = 64u << 20;

// The measurements of one file: one for a pab-opto file, one per angle of incidence (and
// sample rotation) for a Zemax file. The format is recognised from the content.
Result<std::vector<BrdfMeasurement>> readBrdfFile(const std::filesystem::path& path);

// The same from text (`name` in messages): what the fuzz target drives.
Result<std::vector<BrdfMeasurement>> parseBrdfText(std::string_view text, const std::string& name);

// A pab-opto file of one measurement (BSDF values, CIE-Y).
std::string formatPabOpto(const BrdfMeasurement& measurement);

// A Zemax BSDF table: one grid of scatter angles around the specular direction, one block of
// values per angle of incidence (sample rotation 0).
struct ZemaxTable {
  std::string source = "Measured";
  bool plane_symmetric = true;      // azimuths 0–180° mirrored across the plane of incidence
  std::vector<double> radial_deg;   // ascending, from 0
  std::vector<double> azimuth_deg;  // ascending, from 0
  struct Block {
    double incident_theta_deg = 0;
    double tis = 0;              // total integrated scatter (written as given)
    std::vector<double> values;  // f_r in sr⁻¹, azimuth-major: [azimuth][radial]
  };
  std::vector<Block> blocks;
};
std::string formatZemaxBsdf(const ZemaxTable& table);

// The specular-frame ray of a Zemax scatter direction (radial angle from specular, azimuth from
// the plane of incidence toward grazing), shared by the reader and the simulator.
calibration::Ray zemaxScatterRay(double radial_deg, double azimuth_deg);

}  // namespace glarecam::brdf
