// The ocular hazard plot of one observer (docs/ocular-hazard.md), as reviewers know it from
// Ho et al. 2011 and SGHAT: the subtended source angle ω across (mrad, log), the retinal
// irradiance E_r up (W/cm², log), the three zones of ocular_hazard.h shaded (green: low potential
// for after-image; yellow: potential for after-image; red: potential for permanent eye damage)
// with their two boundaries drawn as lines, and each glaring event a point.
//
// The axes are fixed, so that plots compare at a glance: ω from 0.1 to 1000 mrad (the sun is
// 9.3 mrad; a module's spread glare spot spans tens to hundreds), E_r from 10⁻⁶ to 10³ W/cm² (the
// sun seen directly is about 9 W/cm²). A point outside them is drawn at the nearest edge as a
// hollow marker (a bound, not a value) and counted in the legend; none is dropped. Up to four
// series (e.g. one per array, or per glare model), each its own marker, labelled with its events
// per class. The zones are pale so that the points stand out; the boundaries are drawn over them;
// grid lines at the decades.
//
// Two ways out: drawn into a box of a canvas (a report page embeds it: the box holds the data
// area, tick labels and axis titles, nothing is drawn outside it), or as a page of its own (A4
// landscape: title and subtitle on top, the version stamp, a translucent mark such as SIMULATED
// over everything when the content has one) written as PNG and SVG, each atomically
// (render/page_output.h).
//
// Errors: kBadInput, with nothing drawn or written, for more than four series, a series without
// a label beside others, or a point whose ω or E_r is not positive and finite; kIo when a file
// cannot be written.
#pragma once

#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "core/error.h"
#include "render/page_geometry.h"

namespace glarecam::render {
class Canvas;
}

namespace glarecam::hazard {

// The axes' ranges.
inline constexpr double kOcularPlotMinAngleMrad = 0.1;
inline constexpr double kOcularPlotMaxAngleMrad = 1000;
inline constexpr double kOcularPlotMinIrradianceWCm2 = 1e-6;
inline constexpr double kOcularPlotMaxIrradianceWCm2 = 1e3;

inline constexpr int kOcularPlotMaxSeries = 4;

// The zones' fills as 8-bit sRGB, for a reader of the picture (and its tests).
inline constexpr std::array<std::uint8_t, 3> kOcularGreenFill = {0xD2, 0xEC, 0xCB};
inline constexpr std::array<std::uint8_t, 3> kOcularYellowFill = {0xFF, 0xF1, 0xB3};
inline constexpr std::array<std::uint8_t, 3> kOcularRedFill = {0xF8, 0xC4, 0xBF};

struct OcularPlotPoint {
  double subtended_angle_mrad = 0;
  double retinal_irradiance_w_cm2 = 0;
};

struct OcularPlotSeries {
  std::string label;  // e.g. "array-1"; may be empty when it is the only series
  std::vector<OcularPlotPoint> points{};
};

struct OcularPlotContent {
  std::string title;                       // e.g. "Ocular hazard at window-3, 2027"
  std::string subtitle;                    // e.g. scene and profile files, the eye's parameters
  std::vector<OcularPlotSeries> series{};  // none, or series without points: "no glare"
  // When not empty, across the page's face over everything (render::drawPageMark): "SIMULATED"
  // and its note. Only the page draws it; an embedding page draws its own.
  std::string mark{}, mark_note{};
};

// The plot filling `frame` (points, the canvas's user units).
Status drawOcularHazardPlot(render::Canvas& canvas, const render::Box& frame,
                            const OcularPlotContent& content);

// The plot as a page of its own, PNG and SVG.
Status writeOcularHazardPlot(const OcularPlotContent& content,
                             const std::filesystem::path& png_path,
                             const std::filesystem::path& svg_path);

}  // namespace glarecam::hazard
