#include "EdgeBend.h"

#include <algorithm>
#include <cmath>

namespace catar
{

double DistanceToSegment(const Vec2& p, const Vec2& a, const Vec2& b)
{
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  double t = len2 > 0.0 ? (p - a).dot(ab) / len2 : 0.0;
  t = std::clamp(t, 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

double EdgeBendPixels(const Projector& projector, const Vec3& aWorld, const Vec3& bWorld,
  int samples, SolverType solver)
{
  const ProjectedPoint pa = projector.ProjectWorld(aWorld, solver);
  const ProjectedPoint pb = projector.ProjectWorld(bWorld, solver);
  if (!HasProjection(pa.status) || !HasProjection(pb.status))
  {
    return -1.0;
  }
  if (pa.status != ProjectionStatus::Valid && pb.status != ProjectionStatus::Valid)
  {
    return -1.0;
  }
  samples = std::max(samples, 1);
  double bend = 0.0;
  for (int k = 1; k <= samples; ++k)
  {
    const double t = static_cast<double>(k) / (samples + 1);
    const ProjectedPoint pm = projector.ProjectWorld(aWorld + t * (bWorld - aWorld), solver);
    if (!HasProjection(pm.status))
    {
      return -1.0;
    }
    bend = std::max(bend, DistanceToSegment(pm.pixel, pa.pixel, pb.pixel));
  }
  return std::isfinite(bend) ? bend : -1.0;
}

double ImageScale(
  const Projector& projector, const Vec3& pointWorld, double step, SolverType solver)
{
  if (!(step > 0.0) || !std::isfinite(step))
  {
    return -1.0;
  }
  const ProjectedPoint p = projector.ProjectWorld(pointWorld, solver);
  if (p.status != ProjectionStatus::Valid)
  {
    return -1.0;
  }
  double scale = 0.0;
  for (int axis = 0; axis < 3; ++axis)
  {
    const ProjectedPoint q = projector.ProjectWorld(pointWorld + step * Vec3::Unit(axis), solver);
    if (!HasProjection(q.status))
    {
      return -1.0;
    }
    scale = std::max(scale, (q.pixel - p.pixel).norm() / step);
  }
  return std::isfinite(scale) ? scale : -1.0;
}

double GeometricErrorForTolerance(
  const Projector& projector, const std::vector<Vec3>& points, double tolerance)
{
  if (points.empty())
  {
    return 0.0;
  }
  Vec3 lo = points.front(), hi = lo;
  for (const Vec3& p : points)
  {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diagonal = (hi - lo).norm();
  if (!(diagonal > 0.0) || !std::isfinite(diagonal))
  {
    return 0.0;
  }
  const std::size_t stride = std::max<std::size_t>(1, points.size() / 4096);
  double scale = 0.0;
  for (std::size_t i = 0; i < points.size(); i += stride)
  {
    scale = std::max(scale, ImageScale(projector, points[i], 1e-4 * diagonal));
  }
  if (!(scale > 0.0))
  {
    return 0.0;
  }
  return std::min(2e-2 * diagonal, std::max(1e-4 * diagonal, tolerance / scale));
}

} // namespace catar
