#include "Projector.h"

#include <Eigen/Dense>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace catar
{
Projector::Projector(const CameraModel& model)
  : Model(model)
  , Pose(model.worldToCamera)
{
  this->Error = model.Validate();
  this->Valid = this->Error.empty();
  if (this->Valid)
  {
    std::string error;
    this->MirrorModel = MakeMirror(model.mirror, error);
    this->Valid = this->MirrorModel != nullptr;
    if (!this->Valid)
    {
      this->Error = error;
    }
  }
  if (this->Valid)
  {
    this->BatchSize = std::max(1, std::min(this->MirrorModel->BatchSize(), Mirror::kMaxBatchSize));
  }
}

ProjectedPoint Projector::ProjectCamera(const Vec3& p, SolverType solver) const
{
  return this->ProjectCameraFrom(p, solver, nullptr);
}

ProjectedPoint Projector::ProjectWorldNear(const Vec3& pWorld, const Vec3& mirrorGuess) const
{
  if (!pWorld.allFinite() || !mirrorGuess.allFinite())
  {
    return this->ProjectWorld(pWorld, SolverType::Iterative);
  }
  return this->ProjectCameraFrom(this->Pose.ToCamera(pWorld), SolverType::Iterative, &mirrorGuess);
}

bool Projector::PixelDerivative(
  const Vec3& p, const ProjectedPoint& at, Eigen::Matrix<double, 2, 3>& d) const
{
  const double h = 1e-6 * std::max(1.0, p.norm());
  bool all = true;
  for (int k = 0; k < 3; ++k)
  {
    Vec3 step = Vec3::Zero();
    step[k] = h;
    const ProjectedPoint plus =
      this->ProjectCameraFrom(p + step, SolverType::Iterative, &at.mirrorPoint);
    const ProjectedPoint minus =
      this->ProjectCameraFrom(p - step, SolverType::Iterative, &at.mirrorPoint);
    const bool hasPlus = HasProjection(plus.status);
    const bool hasMinus = HasProjection(minus.status);
    d.col(k) = hasPlus && hasMinus ? Vec2((plus.pixel - minus.pixel) / (2.0 * h))
      : hasPlus                    ? Vec2((plus.pixel - at.pixel) / h)
      : hasMinus                   ? Vec2((at.pixel - minus.pixel) / h)
                                   : Vec2::Zero();
    all = all && (hasPlus || hasMinus);
  }
  return all;
}

void Projector::ProjectWorldNear(std::size_t n, const Vec3* pWorld, const Vec3* mirrorGuess,
  ProjectedPoint* out, bool pixels) const
{
  constexpr int M = Mirror::kMaxBatchSize;
  const std::size_t W = static_cast<std::size_t>(this->BatchSize);
  for (std::size_t first = 0; first < n; first += W)
  {
    const int lanes = static_cast<int>(std::min<std::size_t>(W, n - first));
    Vec3 p[M], guess[M], r[M];
    unsigned char fast[M];
    int count = 0;
    int lane[M];
    for (int l = 0; l < lanes; ++l)
    {
      const Vec3& w = pWorld[first + l];
      const Vec3& g = mirrorGuess[first + l];
      if (this->Valid && w.allFinite() && g.allFinite())
      {
        p[count] = this->Pose.ToCamera(w);
        guess[count] = g;
        lane[count++] = l;
      }
      else
      {
        out[first + l] = this->ProjectWorldNear(w, g);
      }
    }
    if (count > 0)
    {
      this->MirrorModel->ReflectNear(count, p, guess, r, fast);
    }
    for (int k = 0; k < count; ++k)
    {
      ProjectedPoint& o = out[first + lane[k]];
      o = fast[k] ? this->Finish(p[k], r[k], pixels)
                  : this->ProjectCameraFrom(p[k], SolverType::Iterative, &guess[k]);
    }
  }
}

ProjectedPoint Projector::ProjectCameraFrom(
  const Vec3& p, SolverType solver, const Vec3* mirrorGuess) const
{
  ProjectedPoint out;
  if (!this->Valid || !p.allFinite())
  {
    out.status = ProjectionStatus::InvalidInput;
    return out;
  }
  Vec3 r;
  const ProjectionStatus s =
    this->MirrorModel->Reflect(p, this->MirrorModel->Resolve(solver), r, mirrorGuess);
  if (s != ProjectionStatus::Valid)
  {
    out.status = s;
    return out;
  }
  return this->Finish(p, r);
}

ProjectedPoint Projector::Finish(const Vec3& p, const Vec3& r, bool pixel) const
{
  ProjectedPoint out;
  // The camera images only mirror points in front of it.
  if (!this->Model.Sees(r))
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

ProjectedPoint Projector::ProjectWorld(const Vec3& pWorld, SolverType solver) const
{
  if (!pWorld.allFinite())
  {
    return ProjectedPoint();
  }
  return this->ProjectCamera(this->Pose.ToCamera(pWorld), solver);
}

bool Projector::CameraRay(const Vec2& pixel, Vec3& d, BackProjectedRay& out) const
{
  out = BackProjectedRay();
  if (!this->Valid || !pixel.allFinite())
  {
    out.status = ProjectionStatus::InvalidInput;
    return false;
  }
  if (!this->Model.PixelToDirection(pixel, d))
  {
    out.status = ProjectionStatus::NoReflection;
    return false;
  }
  return true;
}

BackProjectedRay Projector::BackProjectCamera(const Vec2& pixel) const
{
  BackProjectedRay out;
  Vec3 d;
  if (!this->CameraRay(pixel, d, out))
  {
    return out;
  }
  Vec3 r, n;
  if (!this->MirrorModel->Intersect(d, r, n))
  {
    out.status = ProjectionStatus::NoReflection;
    return out;
  }
  return this->Reflected(pixel, d, r, n);
}

BackProjectedRay Projector::Reflected(
  const Vec2& pixel, const Vec3& d, const Vec3& r, const Vec3& n) const
{
  BackProjectedRay out;
  Vec3 refl = d - 2.0 * d.dot(n) * n;
  refl.normalize();
  out.mirrorPoint = r;
  out.direction = refl;
  out.status =
    this->Model.InImage(pixel) ? ProjectionStatus::Valid : ProjectionStatus::OutsideImage;
  return out;
}

void Projector::BackProjectCamera(std::size_t n, const Vec2* pixels, BackProjectedRay* out) const
{
  constexpr int M = Mirror::kMaxBatchSize;
  for (std::size_t first = 0; first < n; first += M)
  {
    const int count = static_cast<int>(std::min<std::size_t>(M, n - first));
    Vec3 d[M], r[M], nrm[M];
    unsigned char hit[M];
    int todo = 0;
    int index[M];
    for (int i = 0; i < count; ++i)
    {
      if (this->CameraRay(pixels[first + i], d[todo], out[first + i]))
      {
        index[todo++] = i;
      }
    }
    if (todo > 0)
    {
      this->MirrorModel->Intersect(todo, d, r, nrm, hit);
    }
    for (int k = 0; k < todo; ++k)
    {
      BackProjectedRay& o = out[first + index[k]];
      if (hit[k])
      {
        o = this->Reflected(pixels[first + index[k]], d[k], r[k], nrm[k]);
      }
      else
      {
        o = BackProjectedRay();
        o.status = ProjectionStatus::NoReflection;
      }
    }
  }
}

void Projector::BackProjectWorld(std::size_t n, const Vec2* pixels, BackProjectedRay* out) const
{
  this->BackProjectCamera(n, pixels, out);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (HasProjection(out[i].status))
    {
      out[i].mirrorPoint = this->Model.CameraToWorld(out[i].mirrorPoint);
      out[i].direction = this->Model.CameraToWorldDirection(out[i].direction);
    }
  }
}

BackProjectedRay Projector::BackProjectWorld(const Vec2& pixel) const
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
