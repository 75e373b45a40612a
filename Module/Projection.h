// CatadioptricAR Core: what a projection through a mirror gives, whatever the mirror: the
// solvers' choice, a forward projection's result (pixel, reflection point, path length, status)
// and a back projection's reflected ray.
#ifndef catarProjection_h
#define catarProjection_h

#include "CameraModel.h"

namespace catar
{
/// Which algorithm finds the reflection point.
enum class SolverType : int
{
  Quartic = 0,  ///< closed-form quartic (Ferrari) + Newton polish
  Iterative = 1 ///< safeguarded Newton on the planar reflection law
};

/// Result of a forward projection. Fields other than status are zero unless HasProjection(status).
struct ProjectedPoint
{
  Vec2 pixel = Vec2::Zero();       ///< pixel coordinates (OpenCV convention)
  Vec3 mirrorPoint = Vec3::Zero(); ///< reflection point on the mirror, camera frame
  double pathLength = 0.0;         ///< distance from the mirror point to the 3D point
  ProjectionStatus status = ProjectionStatus::InvalidInput;
};

/// Result of a back projection: the reflected ray leaves mirrorPoint along direction (unit).
struct BackProjectedRay
{
  Vec3 mirrorPoint = Vec3::Zero();
  Vec3 direction = Vec3::Zero();
  ProjectionStatus status = ProjectionStatus::InvalidInput;
};
} // namespace catar

#endif
