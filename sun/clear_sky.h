// The direct normal illuminance of a clear sky: the estimate of the source illuminance E used
// only when a stack has nothing better (docs/method.md "Reference illuminance", origin
// `clear_sky`), and the sun's brightness the simulated rig lights its scene with.
//
// Model: the IES clear-sky direct normal illuminance (IES RP-21, "Calculation of Daylight
// Availability", 1984; IES Lighting Handbook, 9th ed. 2000, ch. 8 "Daylighting"),
//   E_dn = E_xt · exp(−c · m),
// with the solar illuminance outside the atmosphere E_xt = 127.5 klx · (1 + 0.034 cos(2π (J − 2)
// / 365)) on day of year J, the clear-sky extinction coefficient c = 0.21, and the relative
// optical air mass m. Where the Handbook takes m = 1 / sin(elevation), we use Kasten & Young's
// (1989, "Revised optical air mass tables and approximation formula", Appl. Opt. 28(22)) formula,
// which stays finite at the horizon, scaled by the site's pressure ratio exp(−z / 8434.5 m)
// (Kasten's isothermal atmosphere), so a mountain site sees the thinner air above it.
//
// Uncertainty: the model is for one typical clear sky; real clear skies differ by their turbidity
// (aerosol and water vapour). The spread of measured clear-sky direct normal illuminance around
// such a model is about 10–15 % at high sun and more at low sun (Darula & Kittler, and the IES
// handbook's own "clear" range of c, 0.18–0.24). We state one standard deviation of 15 % above 10°
// elevation, growing to 30 % at the horizon, since m, and with it the effect of c's spread, grows.
#pragma once

#include <chrono>
#include <optional>

#include "core/error.h"
#include "core/source_illuminance.h"
#include "core/stack_manifest.h"
#include "core/time.h"
#include "sun/solar_position.h"

namespace glarecam::sun {

// IES RP-21's constants (see above).
inline constexpr double kIesExtraterrestrialIlluminanceLx = 127'500.0;
inline constexpr double kIesClearSkyExtinction = 0.21;
// Kasten's scale height of the isothermal atmosphere for the pressure ratio, m.
inline constexpr double kAirMassScaleHeightM = 8434.5;
// One standard deviation of the estimate, relative: high sun, and at the horizon.
inline constexpr double kClearSkyRelativeUncertainty = 0.15;
inline constexpr double kClearSkyRelativeUncertaintyHorizon = 0.30;

struct ClearSkyIlluminance {
  double illuminance_lx = 0;    // direct normal
  double illuminance_u_lx = 0;  // one standard deviation
  double air_mass = 0;          // relative optical air mass, pressure-corrected
};

// Kasten & Young's relative optical air mass at an apparent elevation (°, > −6.07995), at sea
// level.
double relativeAirMass(double elevation_deg);

// The clear-sky direct normal illuminance for the sun at `elevation_deg` (apparent) on day of
// year `day_of_year` (1..366) at a site `altitude_m` above sea level. None when the sun is not
// above the horizon (elevation <= 0).
std::optional<ClearSkyIlluminance> clearSkyIlluminance(double elevation_deg, int day_of_year,
                                                       double altitude_m = 0);

// The clear-sky estimate as a stack's source for an instant at a site (origin clear_sky, its
// instrument "clear sky (IES RP-21, c = 0.21)"). kBadInput when the sun is not up there then (no
// direct light to refer to) or the site or instant is invalid.
Result<SourceIlluminance> clearSkySource(std::chrono::sys_time<std::chrono::microseconds> utc,
                                         const SiteLocation& site);

// The clear-sky estimate for a recorded stack, from the sun its rig measured: the manifest's
// geometry block (`time`, `sun_elevation_deg`, docs/stack-format.md), at sea level (the geometry
// does not record the site's altitude: at 1000 m the estimate would be 2.5 % higher at a high
// sun, far inside its 15 %). kBadInput naming the stack when the geometry records no sun (a lab
// lamp, a stack of another tool, a rig without a [site]) or a sun below the horizon.
Result<SourceIlluminance> clearSkySourceOfStack(const StackManifest& manifest);

}  // namespace glarecam::sun
