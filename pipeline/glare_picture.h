// The paper's Figure 9 drawn over the false-colour luminance picture (false_colour.h): the limit
// contour as traced, the fitted limit ellipse with both axes drawn and labelled in degrees, the
// FWHM ellipse, the contour ladder's fixed rungs (thin, each labelled with its level: the method's
// Figure 14), and circles of 1°, 5°, 10° and 20° around the luminance maximum. Ellipses,
// axes and circles are angular shapes mapped through the camera model, so they bend with the
// lens distortion exactly as the glare spot does.
#pragma once

#include "calibration/camera_model.h"
#include "pipeline/false_colour_picture.h"
#include "pipeline/glare_analysis.h"

namespace glarecam::pipeline {

// Angular radii of the reference circles around the maximum (docs/process.md).
inline constexpr double kReferenceCirclesDeg[] = {1.0, 5.0, 10.0, 20.0};

// The overlay for renderFalseColour; it keeps its own copy of what it draws.
PictureOverlay glareOverlay(const GlareAnalysis& analysis, const calibration::CameraModel& camera,
                            const LuminancePeak& peak);

}  // namespace glarecam::pipeline
