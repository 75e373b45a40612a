// CatadioptricAR Core: how much the mirror bends a straight 3D edge in the image.
//
// The compositor draws the image of a 3D edge as the straight segment between the images of its
// ends; the exact image of the edge is a curve. The bend of the edge is the largest distance, in
// pixels, from the exact images of points along the edge to that segment. It is the error of the
// straight-edge approximation that remeshing to a pixel tolerance bounds.
#ifndef catarEdgeBend_h
#define catarEdgeBend_h

#include "Projector.h"

#include <vector>

namespace catar
{

/// Bend in pixels of the straight edge a-b (world coordinates): the largest distance from the
/// exact images of a + t (b - a), t = k / (samples + 1), k = 1..samples, to the segment between
/// the images of a and b. Returns -1 when the edge is not seen: an end or a sample has no
/// projection (see HasProjection), or neither end lies inside the image. Never NaN.
double EdgeBendPixels(const Projector& projector, const Vec3& aWorld, const Vec3& bWorld,
  int samples = 1, SolverType solver = SolverType::Automatic);

/// Image scale at a world point, in pixels per world unit: the largest image displacement of
/// the point moved by `step` along each world axis, divided by `step`. Returns -1 when the point
/// is not seen (no valid projection, or a moved point has none). Never NaN.
double ImageScale(const Projector& projector, const Vec3& pointWorld, double step,
  SolverType solver = SolverType::Automatic);

/// The bound on the geometric error that keeps coarsening a mesh within `tolerance` pixels in the
/// image: the distance that moves the image by the tolerance where the object (its points) is
/// magnified most (its largest ImageScale over up to 4096 of its points). Kept between 1e-4 and
/// 2e-2 of the bounding-box diagonal; 0 when no point is seen or the points span nothing.
double GeometricErrorForTolerance(
  const Projector& projector, const std::vector<Vec3>& points, double tolerance);

/// Distance from point p to the segment a-b (2D).
double DistanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b);

} // namespace catar

#endif
