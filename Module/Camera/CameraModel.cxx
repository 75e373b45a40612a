#include "CameraModel.h"

#include "Mirror.h"

#include <Eigen/Dense>

#include <cmath>
#include <sstream>

namespace catar
{
std::string CameraModel::Validate() const
{
  std::ostringstream err;
  const Intrinsics& in = this->intrinsics;
  const Distortion& d = this->distortion;
  auto finite = [](double v) { return std::isfinite(v); };
  if (!(finite(in.fx) && finite(in.fy) && finite(in.cx) && finite(in.cy) && finite(in.skew)))
  {
    err << "intrinsics contain NaN or Inf";
  }
  else if (!(in.fx > 0.0 && in.fy > 0.0))
  {
    err << "focal lengths must be positive (fx=" << in.fx << ", fy=" << in.fy << ")";
  }
  else if (in.width <= 0 || in.height <= 0)
  {
    err << "image size must be positive (" << in.width << "x" << in.height << ")";
  }
  else if (in.width > kMaxImageSide || in.height > kMaxImageSide ||
    static_cast<long long>(in.width) * in.height > kMaxImagePixels)
  {
    err << "image size " << in.width << "x" << in.height << " is over the limit (at most "
        << kMaxImageSide << " pixels a side and " << kMaxImagePixels << " pixels)";
  }
  else if (!(finite(d.k1) && finite(d.k2) && finite(d.p1) && finite(d.p2) && finite(d.k3)))
  {
    err << "distortion coefficients contain NaN or Inf";
  }
  else if (const std::string mirrorError = ValidateMirror(this->mirror); !mirrorError.empty())
  {
    err << mirrorError;
  }
  else if (!this->worldToCamera.allFinite())
  {
    err << "pose contains NaN or Inf";
  }
  else
  {
    const Mat3 R = this->worldToCamera.topLeftCorner<3, 3>();
    const double orth = (R.transpose() * R - Mat3::Identity()).cwiseAbs().maxCoeff();
    const Eigen::RowVector4d last = this->worldToCamera.row(3);
    if (orth > 1e-6 || R.determinant() < 0.0)
    {
      err << "pose rotation is not a rotation (|R^T R - I| = " << orth
          << ", det = " << R.determinant() << ")";
    }
    else if ((last - Eigen::RowVector4d(0, 0, 0, 1)).cwiseAbs().maxCoeff() > 1e-12)
    {
      err << "pose last row must be (0, 0, 0, 1)";
    }
  }
  return err.str();
}

Mat3 CameraModel::K() const
{
  Mat3 k;
  k << intrinsics.fx, intrinsics.skew, intrinsics.cx, 0.0, intrinsics.fy, intrinsics.cy, 0.0, 0.0,
    1.0;
  return k;
}

Vec2 Distort(const Distortion& d, const Vec2& xy)
{
  const double x = xy.x();
  const double y = xy.y();
  const double r2 = x * x + y * y;
  const double radial = 1.0 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3));
  const double xd = x * radial + 2.0 * d.p1 * x * y + d.p2 * (r2 + 2.0 * x * x);
  const double yd = y * radial + d.p1 * (r2 + 2.0 * y * y) + 2.0 * d.p2 * x * y;
  return Vec2(xd, yd);
}

Vec2 CameraModel::DirectionToPixel(const Vec3& direction) const
{
  const Vec2 xy(direction.x() / direction.z(), direction.y() / direction.z());
  const Vec2 xd = this->distortion.IsZero() ? xy : Distort(this->distortion, xy);
  return Vec2(intrinsics.fx * xd.x() + intrinsics.skew * xd.y() + intrinsics.cx,
    intrinsics.fy * xd.y() + intrinsics.cy);
}

bool CameraModel::PixelToNormalized(const Vec2& pixel, Vec2& normalized) const
{
  // Invert K (upper triangular).
  const double yd = (pixel.y() - intrinsics.cy) / intrinsics.fy;
  const double xd = (pixel.x() - intrinsics.cx - intrinsics.skew * yd) / intrinsics.fx;
  const Vec2 target(xd, yd);
  if (this->distortion.IsZero())
  {
    normalized = target;
    return target.allFinite();
  }
  const Distortion& d = this->distortion;
  // Newton on Distort(x) = target, starting from the target itself.
  Vec2 x = target;
  for (int it = 0; it < 50; ++it)
  {
    const double u = x.x();
    const double v = x.y();
    const double r2 = u * u + v * v;
    const double radial = 1.0 + r2 * (d.k1 + r2 * (d.k2 + r2 * d.k3));
    const double dradial = d.k1 + r2 * (2.0 * d.k2 + 3.0 * r2 * d.k3); // d radial / d r2
    const Vec2 f = Distort(d, x) - target;
    Eigen::Matrix2d J;
    J(0, 0) = radial + u * dradial * 2.0 * u + 2.0 * d.p1 * v + d.p2 * 6.0 * u;
    J(0, 1) = u * dradial * 2.0 * v + 2.0 * d.p1 * u + d.p2 * 2.0 * v;
    J(1, 0) = v * dradial * 2.0 * u + d.p1 * 2.0 * u + 2.0 * d.p2 * v;
    J(1, 1) = radial + v * dradial * 2.0 * v + d.p1 * 6.0 * v + 2.0 * d.p2 * u;
    const double det = J.determinant();
    if (!std::isfinite(det) || std::abs(det) < 1e-14)
    {
      return false;
    }
    const Vec2 step = J.inverse() * f;
    x -= step;
    if (!x.allFinite())
    {
      return false;
    }
    if (step.norm() <= 1e-16 * (1.0 + x.norm()))
    {
      break;
    }
  }
  normalized = x;
  // Accept only a true inverse.
  return (Distort(d, x) - target).norm() <= 1e-12 * (1.0 + target.norm());
}

bool CameraModel::InImage(const Vec2& pixel) const
{
  return pixel.x() >= -0.5 && pixel.y() >= -0.5 && pixel.x() < intrinsics.width - 0.5 &&
    pixel.y() < intrinsics.height - 0.5;
}

Vec3 CameraModel::WorldToCamera(const Vec3& p) const
{
  return this->worldToCamera.topLeftCorner<3, 3>() * p + this->worldToCamera.topRightCorner<3, 1>();
}

Vec3 CameraModel::CameraToWorld(const Vec3& p) const
{
  const Mat3 R = this->worldToCamera.topLeftCorner<3, 3>();
  return R.transpose() * (p - this->worldToCamera.topRightCorner<3, 1>());
}

Vec3 CameraModel::CameraToWorldDirection(const Vec3& d) const
{
  return this->worldToCamera.topLeftCorner<3, 3>().transpose() * d;
}

CameraModel CameraModel::Resized(int width, int height) const
{
  CameraModel m = *this;
  const double sx = static_cast<double>(width) / intrinsics.width;
  const double sy = static_cast<double>(height) / intrinsics.height;
  // Pixel centres: u' + 0.5 = s (u + 0.5).
  m.intrinsics.fx *= sx;
  m.intrinsics.skew *= sx;
  m.intrinsics.cx = (intrinsics.cx + 0.5) * sx - 0.5;
  m.intrinsics.fy *= sy;
  m.intrinsics.cy = (intrinsics.cy + 0.5) * sy - 0.5;
  m.intrinsics.width = width;
  m.intrinsics.height = height;
  return m;
}
} // namespace catar
