#include "CameraModel.h"

#include "Mirror.h"

#include "LensModels.h"

#include <Eigen/Dense>
#include <unsupported/Eigen/AutoDiff>

#include <algorithm>

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
  else if (!std::all_of(d.Data(), d.Data() + Distortion::kCount, finite))
  {
    err << "distortion coefficients contain NaN or Inf";
  }
  else if (this->lens != LensType::Pinhole && this->lens != LensType::Fisheye)
  {
    err << "unknown lens type " << static_cast<int>(this->lens);
  }
  else if (this->lens == LensType::Fisheye &&
    (d.p1 != 0.0 || d.p2 != 0.0 ||
      std::any_of(d.Data() + 6, d.Data() + Distortion::kCount, [](double v) { return v != 0.0; })))
  {
    err << "a fisheye lens has the coefficients k1 k2 k3 k4 only";
  }
  else if (!(std::abs(d.tauX) < 0.5 * M_PI && std::abs(d.tauY) < 0.5 * M_PI))
  {
    err << "the sensor's tilt (tauX, tauY) must be within +-90 degrees (radians: " << d.tauX << ", "
        << d.tauY << ")";
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

const char* LensName(LensType lens)
{
  return lens == LensType::Fisheye ? "fisheye" : "pinhole";
}

bool LensFromName(const std::string& name, LensType& lens)
{
  if (name == "pinhole")
  {
    lens = LensType::Pinhole;
    return true;
  }
  if (name == "fisheye")
  {
    lens = LensType::Fisheye;
    return true;
  }
  return false;
}

bool Distortion::IsZero() const
{
  return std::all_of(this->Data(), this->Data() + kCount, [](double v) { return v == 0.0; });
}

bool Distortion::operator==(const Distortion& other) const
{
  return std::equal(this->Data(), this->Data() + kCount, other.Data());
}

std::vector<double> Distortion::Coefficients(LensType lens) const
{
  if (lens == LensType::Fisheye)
  {
    return { this->k1, this->k2, this->k3, this->k4 };
  }
  // The shortest of OpenCV's lengths that holds the last non-zero number.
  std::size_t last = kCount;
  while (last > 0 && this->Data()[last - 1] == 0.0)
  {
    --last;
  }
  const std::size_t n = last <= 5 ? 5 : last <= 8 ? 8 : last <= 12 ? 12 : 14;
  return std::vector<double>(this->Data(), this->Data() + n);
}

bool Distortion::SetCoefficients(LensType lens, const std::vector<double>& c)
{
  Distortion d;
  if (lens == LensType::Fisheye)
  {
    if (c.size() != 4)
    {
      return false;
    }
    d.k1 = c[0];
    d.k2 = c[1];
    d.k3 = c[2];
    d.k4 = c[3];
  }
  else
  {
    const std::size_t n = c.size();
    if (n != 4 && n != 5 && n != 8 && n != 12 && n != 14)
    {
      return false;
    }
    std::copy(c.begin(), c.end(), d.Data());
  }
  *this = d;
  return true;
}

Vec2 Distort(const Distortion& d, const Vec2& xy)
{
  Vec2 out;
  lens::PinholeDistort(d.Data(), d.Tilted(), xy.x(), xy.y(), out.x(), out.y());
  return out;
}

Vec2 CameraModel::DirectionToPixel(const Vec3& direction) const
{
  Vec2 xd;
  if (this->lens == LensType::Fisheye)
  {
    const double k[4] = { distortion.k1, distortion.k2, distortion.k3, distortion.k4 };
    lens::FisheyeDistort(k, direction.x(), direction.y(), direction.z(), xd.x(), xd.y());
  }
  else
  {
    const Vec2 xy(direction.x() / direction.z(), direction.y() / direction.z());
    xd = this->distortion.IsZero() ? xy : Distort(this->distortion, xy);
  }
  return Vec2(intrinsics.fx * xd.x() + intrinsics.skew * xd.y() + intrinsics.cx,
    intrinsics.fy * xd.y() + intrinsics.cy);
}

bool CameraModel::Sees(const Vec3& d) const
{
  if (!d.allFinite())
  {
    return false;
  }
  if (this->lens == LensType::Fisheye)
  {
    return d.z() > 0.0 || d.x() * d.x() + d.y() * d.y() > 1e-24 * d.squaredNorm();
  }
  return d.z() > 0.0 && d.z() * d.z() > 1e-24 * d.squaredNorm();
}

namespace
{
// Newton on the pinhole distortion: the undistorted (x, y) whose distortion is target, from the
// target itself, each step halved until the residual falls (strong or tilted lenses). Derivatives
// by forward-mode automatic differentiation of the one formula (LensModels.h).
bool UndistortPinhole(const Distortion& d, const Vec2& target, Vec2& x)
{
  using AD = Eigen::AutoDiffScalar<Eigen::Vector2d>;
  AD k[Distortion::kCount];
  for (int i = 0; i < Distortion::kCount; ++i)
  {
    k[i] = AD(d.Data()[i], Eigen::Vector2d::Zero());
  }
  const bool tilted = d.Tilted();
  auto residual = [&](const Vec2& at, Eigen::Matrix2d* J) {
    const AD u(at.x(), 2, 0);
    const AD v(at.y(), 2, 1);
    AD xd, yd;
    lens::PinholeDistort(k, tilted, u, v, xd, yd);
    if (J)
    {
      J->row(0) = xd.derivatives().transpose();
      J->row(1) = yd.derivatives().transpose();
    }
    return Vec2(xd.value() - target.x(), yd.value() - target.y());
  };
  x = target;
  Eigen::Matrix2d J;
  Vec2 f = residual(x, &J);
  const double converged = 1e-15 * (1.0 + target.norm());
  for (int it = 0; it < 60 && f.allFinite() && f.norm() > converged; ++it)
  {
    const double det = J.determinant();
    if (!std::isfinite(det) || std::abs(det) < 1e-14)
    {
      return false;
    }
    const Vec2 step = J.inverse() * f;
    double fraction = 1.0;
    Vec2 next = x - step;
    Eigen::Matrix2d Jn;
    Vec2 fn = residual(next, &Jn);
    for (int half = 0; half < 30 && !(fn.allFinite() && fn.norm() < f.norm()); ++half)
    {
      fraction *= 0.5;
      next = x - fraction * step;
      fn = residual(next, &Jn);
    }
    if (!(fn.allFinite() && fn.norm() < f.norm()))
    {
      break; // at rounding: no step lowers the residual
    }
    x = next;
    f = fn;
    J = Jn;
  }
  return x.allFinite() && f.norm() <= 1e-12 * (1.0 + target.norm());
}

// The fisheye's theta of theta_d: Newton from theta_d, each step halved until the residual falls.
bool FisheyeTheta(const Distortion& d, double thetaD, double& theta)
{
  const double k[4] = { d.k1, d.k2, d.k3, d.k4 };
  auto f = [&](double t) { return lens::FisheyeThetaD(k, t) - thetaD; };
  theta = std::min(thetaD, 3.0);
  double value = f(theta);
  const double converged = 1e-15 * (1.0 + thetaD);
  for (int it = 0; it < 60 && std::isfinite(value) && std::abs(value) > converged; ++it)
  {
    const double t2 = theta * theta;
    const double slope =
      1.0 + t2 * (3.0 * k[0] + t2 * (5.0 * k[1] + t2 * (7.0 * k[2] + t2 * 9.0 * k[3])));
    if (!(std::abs(slope) > 1e-14))
    {
      return false;
    }
    const double step = value / slope;
    double fraction = 1.0;
    double next = theta - step;
    double nextValue = f(next);
    auto better = [&](double t, double v) {
      return std::isfinite(v) && std::abs(v) < std::abs(value) && t >= 0.0;
    };
    for (int half = 0; half < 30 && !better(next, nextValue); ++half)
    {
      fraction *= 0.5;
      next = theta - fraction * step;
      nextValue = f(next);
    }
    if (!better(next, nextValue))
    {
      break; // at rounding
    }
    theta = next;
    value = nextValue;
  }
  return std::isfinite(theta) && theta >= 0.0 && theta < M_PI &&
    std::abs(value) <= 1e-12 * (1.0 + thetaD);
}
} // namespace

bool CameraModel::PixelToDirection(const Vec2& pixel, Vec3& direction) const
{
  // Invert K (upper triangular).
  const double yd = (pixel.y() - intrinsics.cy) / intrinsics.fy;
  const double xd = (pixel.x() - intrinsics.cx - intrinsics.skew * yd) / intrinsics.fx;
  const Vec2 target(xd, yd);
  if (!target.allFinite())
  {
    return false;
  }
  if (this->lens == LensType::Fisheye)
  {
    const double thetaD = target.norm();
    if (thetaD == 0.0)
    {
      direction = Vec3(0.0, 0.0, 1.0);
      return true;
    }
    double theta = 0.0;
    if (!FisheyeTheta(this->distortion, thetaD, theta))
    {
      return false;
    }
    const double s = std::sin(theta) / thetaD;
    direction = Vec3(s * xd, s * yd, std::cos(theta));
    return true;
  }
  Vec2 x = target;
  if (!this->distortion.IsZero() && !UndistortPinhole(this->distortion, target, x))
  {
    return false;
  }
  direction = Vec3(x.x(), x.y(), 1.0).normalized();
  return direction.allFinite();
}

bool CameraModel::PixelToNormalized(const Vec2& pixel, Vec2& normalized) const
{
  if (this->lens == LensType::Pinhole)
  {
    // x/z directly, not through the unit direction: exact for the common case.
    const double yd = (pixel.y() - intrinsics.cy) / intrinsics.fy;
    const double xd = (pixel.x() - intrinsics.cx - intrinsics.skew * yd) / intrinsics.fx;
    const Vec2 target(xd, yd);
    if (!target.allFinite())
    {
      return false;
    }
    if (this->distortion.IsZero())
    {
      normalized = target;
      return true;
    }
    return UndistortPinhole(this->distortion, target, normalized);
  }
  Vec3 d;
  if (!this->PixelToDirection(pixel, d) || !(d.z() > 0.0))
  {
    return false;
  }
  normalized = Vec2(d.x() / d.z(), d.y() / d.z());
  return normalized.allFinite();
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
