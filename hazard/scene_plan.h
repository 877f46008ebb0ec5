// The plan view of a hazard scene, the first page of the hazard report (hazard_pdf.h,
// docs/hazard-report.md): the scene from above in its east–north metres around the site (x east,
// y north; heights are not drawn but written: an obstruction's top), one scale for both axes,
// drawn with render/ into a box of a canvas:
//   - each array as its polygon seen from above, with an arrow the way its front faces (none
//     for a level array), its name under its centre;
//   - each obstruction's footprint: an extruded one's lowest face, a planar one's outline seen
//     from above (a vertical wall is a line), grey, named with its top height;
//   - each observer as a point, with a pale wedge over the directions in which it counts
//     (Observer::view_azimuths_deg within field_of_view_deg) and an arrow along each;
//   - each route as the polyline of its points, an arrow at its middle point along each
//     direction of travel; each area as its points and their outline (convex hull);
//   - the points given as worst (a route's or an area's worst point) ringed;
//   - a north arrow (top right), a scale bar (bottom left), the axes in metres and a legend in
//     the emptiest remaining corner.
// Nothing is drawn outside the box but half a tick label at the axes' ends, as plot_axes draws
// them. Colours: Okabe–Ito, as the charts'.
#pragma once

#include <cstddef>
#include <vector>

#include "core/error.h"
#include "hazard/scene.h"
#include "render/page_geometry.h"

namespace glarecam::render {
class Canvas;
}

namespace glarecam::hazard {

// The plan filling `frame` (points, the canvas's user units); `worst_points` index
// Scene::observers (others are ignored). Returns the canvas's status.
Status drawScenePlan(render::Canvas& canvas, const render::Box& frame, const Scene& scene,
                     const std::vector<std::size_t>& worst_points);

}  // namespace glarecam::hazard
