// The illuminance of the source that lit a stack (docs/method.md "Reference illuminance and the
// contour ladder", docs/stack-format.md `source`): the direct normal illuminance E at the module
// during the bracket, its standard uncertainty, and where it came from. Every luminance glarecam
// publishes is referred to a reference illuminance E_ref through it: L_ref = L · E_ref / E.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <string_view>

#include "core/error.h"
#include "core/json.h"

namespace glarecam {

// Where E came from, in the order of trust: a rig instrument sampled during the bracket, a value
// the operator gave (a lab lamp measured once with an illuminance meter), a clear-sky estimate.
enum class IlluminanceOrigin { kSensor, kGiven, kClearSky };

// "sensor", "given", "clear_sky": the words of the manifest's `origin`.
std::string_view originWord(IlluminanceOrigin origin);
std::optional<IlluminanceOrigin> originFromWord(std::string_view word);

// The reference E_ref results are referred to unless told otherwise: about a clear midday sun in
// Central Europe (docs/method.md "Reference illuminance").
inline constexpr double kDefaultReferenceIlluminanceLx = 100'000.0;
// No sun gives more: the solar illuminance outside the atmosphere is 133.8 klx at the mean
// Earth–Sun distance and 138 klx at perihelion (Darula, Kittler & Gueymard 2005, "Reference
// luminous solar constant and solar luminance for illuminance calculations", J. Illum. Eng. Soc.
// 34(1)). A larger value is a unit mistake (W/m² read as lx, or klx as lx), refused.
inline constexpr double kMaxSourceIlluminanceLx = 150'000.0;

struct SourceIlluminance {
  double illuminance_lx = 0;    // E, direct normal, > 0
  double illuminance_u_lx = 0;  // its standard uncertainty u(E), >= 0
  IlluminanceOrigin origin = IlluminanceOrigin::kGiven;
  // A sensor reading's description: "pyrheliometer modbus:/dev/ttyUSB0@1 (W/m², 93 lm/W)".
  std::optional<std::string> instrument = std::nullopt;
  std::optional<int> samples = std::nullopt;       // readings averaged during the bracket
  std::optional<double> spread_lx = std::nullopt;  // their standard deviation

  double relativeUncertainty() const { return illuminance_u_lx / illuminance_lx; }
  bool operator==(const SourceIlluminance&) const = default;
};

// The manifest's `source` block (a reader at it): refuses an illuminance that is not finite and
// positive or above kMaxSourceIlluminanceLx, a negative uncertainty, an unknown origin, naming
// the field.
Result<SourceIlluminance> parseSourceIlluminance(const JsonReader& block);
nlohmann::json toJson(const SourceIlluminance& source);

// An illuminance the operator types: "92500", "92500±2800", "92500+-2800" or "92500+/-2800"
// (lx; no uncertainty given means 0). `where` names the option or config key in the message
// ("--source-illuminance"). Origin kGiven.
Result<SourceIlluminance> parseGivenIlluminance(std::string_view text, const std::string& where);

// A reference illuminance E_ref: finite, > 0 and at most kMaxSourceIlluminanceLx.
Status checkReferenceIlluminance(double reference_lx, const std::string& where);

// E and its uncertainty as people read them: "92.5 ± 2.8 klx (sensor)".
std::string describe(const SourceIlluminance& source);

}  // namespace glarecam
