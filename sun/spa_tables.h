// The periodic-term tables of NREL's Solar Position Algorithm (Reda & Andreas, "Solar Position
// Algorithm for Solar Radiation Applications", NREL/TP-560-34302, 2004, revised 2008): Table A4.2
// (the Earth's heliocentric longitude L, latitude B and radius vector R, from VSOP87) and Table
// A4.3 (nutation in longitude and obliquity). Internal to sun/: only solar_position.cpp
// reads them.
#pragma once

#include <array>
#include <span>

namespace glarecam::sun::spa {

// One term A·cos(B + C·τ) of a VSOP87 series, τ in Julian ephemeris millennia from J2000.0.
struct PeriodicTerm {
  double a;
  double b_rad;
  double c_rad;
};

// One row of the nutation table: the multipliers Y0..Y4 of the Delaunay arguments X0..X4 and the
// coefficients of Δψ = (a + b·T)·sin(Σ Yi·Xi) and Δε = (c + d·T)·cos(Σ Yi·Xi), in 0.0001″.
struct NutationTerm {
  std::array<int, 5> y;
  double a, b, c, d;
};

// The series L0..L5, B0..B1 and R0..R4, each indexed by the power of τ it multiplies.
extern const std::array<std::span<const PeriodicTerm>, 6> kEarthLongitude;
extern const std::array<std::span<const PeriodicTerm>, 2> kEarthLatitude;
extern const std::array<std::span<const PeriodicTerm>, 5> kEarthRadius;
extern const std::span<const NutationTerm> kNutation;

}  // namespace glarecam::sun::spa
