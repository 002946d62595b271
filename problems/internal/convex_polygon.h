// Convex polygons in the plane clipped by half-planes: the feasible sets of
// TOPP-RA's stages (topp_ra.h), whose extent in the first coordinate is the
// controllable set. Two dimensions only, so clipping a convex polygon
// (Sutherland-Hodgman, O(vertices) per half-plane) replaces a linear
// programme, and no LP library is needed.
//
// A polygon is its vertices in order (either orientation). Degenerate
// polygons (a segment, a point: a stage whose next set is one value) are
// valid and stay valid under clipping; the empty polygon has no vertices.
#ifndef CCMA_PROBLEMS_INTERNAL_CONVEX_POLYGON_H_
#define CCMA_PROBLEMS_INTERNAL_CONVEX_POLYGON_H_

#include <vector>

#include <Eigen/Core>

namespace ccma {
namespace internal {

using Polygon = std::vector<Eigen::Vector2d>;

// The box [x_lo, x_hi] x [y_lo, y_hi] (x_lo <= x_hi, y_lo <= y_hi), counter-
// clockwise from (x_lo, y_lo).
Polygon BoxPolygon(double x_lo, double x_hi, double y_lo, double y_hi);

// `*out` = polygon (convex) intersected with {(x, y): a x + b y <= c}. A
// vertex whose excess a x + b y - c is within rounding of its terms
// (kClipSlack (|a x| + |b y| + |c|)) counts as inside, so a polygon lying on
// the boundary line (a tight equality a x + b y = c given as two half-planes)
// is kept rather than lost to rounding. New vertices on the line are
// interpolated from the edge's end nearer the line, which keeps them accurate
// on long edges (a box of 1e9 in x with a feature at 1). `out` may not be
// `&polygon`; empty in, empty out.
constexpr double kClipSlack = 1e-13;
void ClipByHalfPlane(const Polygon& polygon, double a, double b, double c, Polygon* out);

// Signed area by the shoelace formula (> 0 counter-clockwise).
double SignedArea(const Polygon& polygon);

// Smallest and largest x over the vertices (polygon not empty).
void XRange(const Polygon& polygon, double* x_min, double* x_max);

}  // namespace internal
}  // namespace ccma

#endif  // CCMA_PROBLEMS_INTERNAL_CONVEX_POLYGON_H_
