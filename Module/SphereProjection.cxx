#include "SphereProjection.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace catar
{
SphereProjector::SphereProjector(const CameraModel& model)
  : Model(model)
  , Frame(model.mirror.center, model.mirror.radius)
{
  this->Error = model.Validate();
  this->Valid = this->Error.empty();
  this->R = model.worldToCamera.topLeftCorner<3, 3>();
  this->T = model.worldToCamera.topRightCorner<3, 1>();
}

ProjectedPoint SphereProjector::ProjectCamera(const Vec3& p, SolverType solver) const
{
  return this->ProjectCameraFrom(p, solver, nullptr);
}

ProjectedPoint SphereProjector::ProjectWorldNear(const Vec3& pWorld, const Vec3& mirrorGuess) const
{
  if (!pWorld.allFinite() || !mirrorGuess.allFinite())
  {
    return this->ProjectWorld(pWorld, SolverType::Iterative);
  }
  return this->ProjectCameraFrom(this->R * pWorld + this->T, SolverType::Iterative, &mirrorGuess);
}

void SphereProjector::ProjectWorldNear(std::size_t n, const Vec3* pWorld, const Vec3* mirrorGuess,
  ProjectedPoint* out, bool pixels) const
{
  constexpr int W = detail::MirrorFrame::kLanes;
  for (std::size_t first = 0; first < n; first += W)
  {
    const int lanes = static_cast<int>(std::min<std::size_t>(W, n - first));
    Vec3 p[W], guess[W], r[W];
    unsigned char fast[W];
    int count = 0;
    int lane[W];
    for (int l = 0; l < lanes; ++l)
    {
      const Vec3& w = pWorld[first + l];
      const Vec3& g = mirrorGuess[first + l];
      if (this->Valid && w.allFinite() && g.allFinite())
      {
        p[count] = this->R * w + this->T;
        guess[count] = g;
        lane[count++] = l;
      }
      else
      {
        out[first + l] = this->ProjectWorldNear(w, g);
      }
    }
    this->Frame.ReflectNear(count, p, guess, r, fast);
    for (int k = 0; k < count; ++k)
    {
      ProjectedPoint& o = out[first + lane[k]];
      o = fast[k] ? this->Finish(p[k], r[k], pixels)
                  : this->ProjectCameraFrom(p[k], SolverType::Iterative, &guess[k]);
    }
  }
}

ProjectedPoint SphereProjector::ProjectCameraFrom(
  const Vec3& p, SolverType solver, const Vec3* mirrorGuess) const
{
  ProjectedPoint out;
  if (!this->Valid || !p.allFinite())
  {
    out.status = ProjectionStatus::InvalidInput;
    return out;
  }
  Vec3 r;
  const ProjectionStatus s = this->Frame.Reflect(p, solver, r, mirrorGuess);
  if (s != ProjectionStatus::Valid)
  {
    out.status = s;
    return out;
  }
  return this->Finish(p, r);
}

ProjectedPoint SphereProjector::Finish(const Vec3& p, const Vec3& r, bool pixel) const
{
  ProjectedPoint out;
  // The camera images only mirror points in front of it.
  if (!(r.z() > 0.0 && r.z() * r.z() > 1e-24 * r.squaredNorm()))
  {
    out.status = ProjectionStatus::NoReflection;
    return out;
  }
  if (!pixel)
  {
    out.mirrorPoint = r;
    out.pathLength = (p - r).norm();
    out.status = ProjectionStatus::Valid;
    return out;
  }
  const Vec2 px = this->Model.DirectionToPixel(r);
  if (!px.allFinite())
  {
    out.status = ProjectionStatus::NoReflection;
    return out;
  }
  out.pixel = px;
  out.mirrorPoint = r;
  out.pathLength = (p - r).norm();
  out.status = this->Model.InImage(px) ? ProjectionStatus::Valid : ProjectionStatus::OutsideImage;
  return out;
}

ProjectedPoint SphereProjector::ProjectWorld(const Vec3& pWorld, SolverType solver) const
{
  if (!pWorld.allFinite())
  {
    return ProjectedPoint();
  }
  return this->ProjectCamera(this->R * pWorld + this->T, solver);
}

BackProjectedRay SphereProjector::BackProjectCamera(const Vec2& pixel) const
{
  BackProjectedRay out;
  if (!this->Valid || !pixel.allFinite())
  {
    out.status = ProjectionStatus::InvalidInput;
    return out;
  }
  Vec2 xy;
  if (!this->Model.PixelToNormalized(pixel, xy))
  {
    out.status = ProjectionStatus::NoReflection;
    return out;
  }
  const Vec3 d = Vec3(xy.x(), xy.y(), 1.0).normalized();
  const Vec3& c = this->Model.mirror.center;
  const double radius = this->Model.mirror.radius;
  const double dc = d.dot(c);
  const double c2r2 = c.squaredNorm() - radius * radius;
  // disc = R^2 - (distance from the centre to the ray)^2, without the cancellation of
  // (d.c)^2 - |c|^2 + R^2, which would cost digits at every pixel.
  const double lateral = c.cross(d).norm();
  const double disc = (radius - lateral) * (radius + lateral);
  if (!(dc > 0.0) || !(disc >= 0.0))
  {
    out.status = ProjectionStatus::NoReflection;
    return out;
  }
  // Nearer intersection, in the cancellation-free form s = (|c|^2 - R^2) / (d.c + sqrt(disc)).
  const double s = c2r2 / (dc + std::sqrt(disc));
  const Vec3 r = s * d;
  const Vec3 n = (r - c) / radius;
  Vec3 refl = d - 2.0 * d.dot(n) * n;
  refl.normalize();
  out.mirrorPoint = r;
  out.direction = refl;
  out.status =
    this->Model.InImage(pixel) ? ProjectionStatus::Valid : ProjectionStatus::OutsideImage;
  return out;
}

BackProjectedRay SphereProjector::BackProjectWorld(const Vec2& pixel) const
{
  BackProjectedRay out = this->BackProjectCamera(pixel);
  if (HasProjection(out.status))
  {
    out.mirrorPoint = this->Model.CameraToWorld(out.mirrorPoint);
    out.direction = this->Model.CameraToWorldDirection(out.direction);
  }
  return out;
}
} // namespace catar
