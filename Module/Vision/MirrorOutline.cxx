// CatadioptricAR Core: a sphere's centre from its outline, and the outline of a sphere
// (MirrorOutline.h). The outline's detection in an image is in MirrorOutlineDetection.cxx.
#include "MirrorOutline.h"

#include "ConicFit.h"
#include "SphereMirror.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace catar
{
namespace
{
using detail::ConicKind;
using detail::Describe;
using detail::Ellipse;
using detail::EllipseOf;
using detail::FitConic;
using detail::ValidateLens;

constexpr double kPi = 3.14159265358979323846;
// The camera centre must lie outside the sphere by this relative margin (as ValidateSphere).
constexpr double kOutsideMargin = 1e-9;
// Covariance eigenvalue ratio below which points are taken as collinear.
constexpr double kCollinearRatio = 1e-12;

// ---- The cone -------------------------------------------------------------------------------

// The angle between unit ray r and the direction of c (accurate at small angles too).
double AngleTo(const Vec3& r, const Vec3& c)
{
  return std::atan2(r.cross(c).norm(), r.dot(c));
}

// Sum of squared angular residuals angle(r_i, c) - asin(R / |c|).
double ConeCost(const std::vector<Vec3>& rays, double radius, const Vec3& c)
{
  const double alpha = std::asin(radius / c.norm());
  double cost = 0.0;
  for (const Vec3& r : rays)
  {
    const double f = AngleTo(r, c) - alpha;
    cost += f * f;
  }
  return cost;
}

// The cone of rays tangent to the sphere of that radius centred at c: a ray's angular residual
// angle(r, c) - asin(R / |c|) and its gradient with respect to c (d angle / d c = -u / |c|, u the
// unit part of r across c; d asin(R / |c|) / d c = -tan(a) / |c| axis).
struct TangentCone
{
  TangentCone(double radius, const Vec3& centre)
    : c(centre)
    , distance(centre.norm())
    , axis(centre / distance)
  {
    const double sinAlpha = radius / this->distance;
    this->alpha = std::asin(sinAlpha);
    this->tanAlpha = sinAlpha / std::sqrt((1.0 - sinAlpha) * (1.0 + sinAlpha));
  }

  double Residual(const Vec3& r, Vec3& gradient) const
  {
    const Vec3 across = r - r.dot(this->axis) * this->axis;
    const double acrossNorm = across.norm();
    const Vec3 u = acrossNorm > 0.0 ? Vec3(across / acrossNorm) : Vec3::Zero();
    gradient = (this->tanAlpha * this->axis - u) / this->distance;
    return AngleTo(r, this->c) - this->alpha;
  }

  Vec3 c;
  double distance;
  Vec3 axis;
  double alpha = 0.0;
  double tanAlpha = 0.0;
};

// One sigma of the centre along its worst direction (metres): s^2 (J^T J)^-1 from the angular
// residuals' Jacobian, s from the residuals, times the residuals' correlation along the outline
// (neighbouring points come from profiles smoothed along the rim, so their errors are not
// independent): 1 + 2 sum of the autocorrelations at lags 1, 2, ... of the residuals in the
// outline's order, up to the first below 0.05 (the effective number of independent points).
double CentreSigma(const std::vector<Vec3>& rays, double radius, const Vec3& c)
{
  const std::size_t n = rays.size();
  const TangentCone cone(radius, c);
  Mat3 jtj = Mat3::Zero();
  std::vector<double> f(n);
  double squares = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    Vec3 j;
    f[i] = cone.Residual(rays[i], j);
    squares += f[i] * f[i];
    jtj += j * j.transpose();
  }
  if (n <= 3 || !(squares > 0.0))
  {
    return n <= 3 ? std::numeric_limits<double>::infinity() : 0.0;
  }
  double correlation = 1.0;
  for (std::size_t lag = 1; lag < n / 4; ++lag)
  {
    double sum = 0.0;
    for (std::size_t i = lag; i < n; ++i)
    {
      sum += f[i] * f[i - lag];
    }
    const double rho = sum / squares;
    if (rho < 0.05)
    {
      break;
    }
    correlation += 2.0 * rho;
  }
  const double variance = squares / static_cast<double>(n - 3) * correlation;
  const Eigen::SelfAdjointEigenSolver<Mat3> es(jtj);
  if (!(es.eigenvalues()(0) > 0.0))
  {
    return std::numeric_limits<double>::infinity();
  }
  return std::sqrt(variance / es.eigenvalues()(0));
}

// Levenberg-Marquardt on the three coordinates of c. Returns the iterations taken.
int RefineCentre(const std::vector<Vec3>& rays, double radius, Vec3& c)
{
  double cost = ConeCost(rays, radius, c);
  double lambda = -1.0;
  int iteration = 0;
  for (; iteration < 100; ++iteration)
  {
    const TangentCone cone(radius, c);
    Mat3 jtj = Mat3::Zero();
    Vec3 jtf = Vec3::Zero();
    for (const Vec3& r : rays)
    {
      Vec3 j;
      const double f = cone.Residual(r, j);
      jtj += j * j.transpose();
      jtf += j * f;
    }
    if (lambda < 0.0)
    {
      lambda = 1e-6 * jtj.diagonal().maxCoeff();
    }
    bool improved = false;
    Vec3 step = Vec3::Zero();
    for (int attempt = 0; attempt < 20 && !improved; ++attempt)
    {
      Mat3 damped = jtj;
      damped.diagonal() += lambda * (jtj.diagonal().array() + 1e-300).matrix();
      step = -damped.ldlt().solve(jtf);
      const Vec3 next = c + step;
      if (step.allFinite() && next.norm() > radius * (1.0 + kOutsideMargin))
      {
        const double nextCost = ConeCost(rays, radius, next);
        if (nextCost <= cost)
        {
          c = next;
          const bool settled = cost - nextCost <= 1e-15 * cost;
          cost = nextCost;
          lambda = std::max(lambda * 0.1, 1e-300);
          improved = true;
          if (settled && step.norm() <= 1e-12 * c.norm())
          {
            return iteration + 1;
          }
          break;
        }
      }
      lambda *= 10.0;
    }
    if (!improved || step.norm() <= 1e-15 * c.norm())
    {
      return iteration + 1;
    }
  }
  return iteration;
}

// The point of the cone's outline (through `camera`) nearest `pixel`, whose ray is `ray`:
// Gauss-Newton on the angle around the axis, from the ray's own.
double PixelDistanceToOutline(const CameraModel& camera, const Vec3& axis, const Vec3& e1,
  const Vec3& e2, double cosAlpha, double sinAlpha, const Vec3& ray, const Vec2& pixel)
{
  auto at = [&](double theta) {
    return camera.DirectionToPixel(
      cosAlpha * axis + sinAlpha * (std::cos(theta) * e1 + std::sin(theta) * e2));
  };
  double theta = std::atan2(ray.dot(e2), ray.dot(e1));
  for (int it = 0; it < 20; ++it)
  {
    const double h = 1e-6;
    const Vec2 p = at(theta);
    const Vec2 dp = (at(theta + h) - at(theta - h)) / (2.0 * h);
    const double den = dp.squaredNorm();
    if (!(den > 0.0))
    {
      break;
    }
    const double step = -(p - pixel).dot(dp) / den;
    theta += step;
    if (std::abs(step) < 1e-13)
    {
      break;
    }
  }
  return (at(theta) - pixel).norm();
}
} // namespace

std::vector<Vec2> SphereOutline(
  const CameraModel& camera, const Vec3& centre, double radius, int count)
{
  std::vector<Vec2> outline;
  const double distance = centre.norm();
  if (count < 1 || !(radius > 0.0) || !std::isfinite(radius) || !centre.allFinite() ||
    !(distance > radius * (1.0 + kOutsideMargin)))
  {
    return outline;
  }
  const Vec3 axis = centre / distance;
  const double sinAlpha = radius / distance;
  const double cosAlpha = std::sqrt((1.0 - sinAlpha) * (1.0 + sinAlpha));
  Vec3 e1, e2;
  PerpendicularBasis(axis, e1, e2);
  outline.reserve(static_cast<std::size_t>(count));
  for (int k = 0; k < count; ++k)
  {
    const double theta = 2.0 * kPi * k / count;
    const Vec3 ray = cosAlpha * axis + sinAlpha * (std::cos(theta) * e1 + std::sin(theta) * e2);
    if (ray.z() > 1e-12)
    {
      outline.push_back(camera.DirectionToPixel(ray));
    }
  }
  return outline;
}

bool SphereFromOutline(const CameraModel& camera, double radius,
  const std::vector<Vec2>& outlinePixels, Vec3& centre, SphereOutlineReport& report,
  std::string& error)
{
  report = SphereOutlineReport();
  if (const std::string lens = ValidateLens(camera); !lens.empty())
  {
    error = "the camera is not usable: " + lens;
    return false;
  }
  if (!(radius > 0.0) || !std::isfinite(radius))
  {
    error = "the sphere's radius must be positive and finite (" + Describe(radius) + ")";
    return false;
  }
  const std::size_t n = outlinePixels.size();
  if (n < 5)
  {
    error = "an outline needs at least 5 points to fix a conic (got " + std::to_string(n) + ")";
    return false;
  }
  std::vector<Vec2> normalized(n);
  std::vector<Vec3> rays(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!outlinePixels[i].allFinite())
    {
      error = "outline point " + std::to_string(i) + " is not finite (NaN or Inf)";
      return false;
    }
    if (!camera.PixelToNormalized(outlinePixels[i], normalized[i]))
    {
      error = "outline point " + std::to_string(i) + " (" + Describe(outlinePixels[i].x(), 6) +
        ", " + Describe(outlinePixels[i].y(), 6) +
        ") lies beyond the range of the camera's distortion model";
      return false;
    }
    rays[i] = Vec3(normalized[i].x(), normalized[i].y(), 1.0).normalized();
  }

  // Collinear points fix no ellipse (and make the conic fit's normalisation degenerate).
  Vec2 mean = Vec2::Zero();
  for (const Vec2& p : normalized)
  {
    mean += p;
  }
  mean /= static_cast<double>(n);
  Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  for (const Vec2& p : normalized)
  {
    covariance += (p - mean) * (p - mean).transpose();
  }
  const Vec2 spread = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(covariance).eigenvalues();
  if (!(spread(1) > 1e-24 * static_cast<double>(n) * (1.0 + mean.squaredNorm())))
  {
    error = "the outline points all coincide: they do not outline a sphere";
    return false;
  }
  if (spread(0) <= kCollinearRatio * spread(1))
  {
    error = "the outline points are collinear: they do not outline a sphere";
    return false;
  }

  Mat3 conic;
  if (!FitConic(normalized.data(), n, conic))
  {
    error = "the outline points do not fix a single conic (fewer than 5 distinct points?)";
    return false;
  }
  Ellipse ellipse;
  switch (EllipseOf(conic, ellipse))
  {
    case ConicKind::NotElliptic:
      error = "the outline points do not lie on an ellipse (the conic through them is a "
              "hyperbola, a parabola or a pair of lines): they do not outline a sphere in front "
              "of the camera";
      return false;
    case ConicKind::Imaginary:
      error = "the outline points do not lie on a real ellipse";
      return false;
    case ConicKind::Ellipse:
      break;
  }

  // -Q ~ d d^T - cos^2(a) I: after the sign fix (2x2 block positive definite) Q has one negative
  // eigenvalue (-sin^2 a, eigenvector d) and two positive ones (cos^2 a).
  const Eigen::SelfAdjointEigenSolver<Mat3> es(ellipse.Q);
  const Vec3& lambda = es.eigenvalues(); // ascending
  const double positive = 0.5 * (lambda(1) + lambda(2));
  const double tan2 = -lambda(0) / positive;
  if (!(lambda(0) < 0.0) || !(positive > 0.0) || !std::isfinite(tan2))
  {
    error = "the outline points do not lie on the image of a cone in front of the camera";
    return false;
  }
  Vec3 axis = es.eigenvectors().col(0).normalized();
  if (axis.z() < 0.0)
  {
    axis = -axis;
  }
  const double sinAlpha0 = std::sqrt(tan2 / (1.0 + tan2));
  Vec3 c = (radius / sinAlpha0) * axis;
  if (!(c.norm() > radius * (1.0 + kOutsideMargin)) || !c.allFinite())
  {
    error = "the outline spans a half-space of directions: the camera would be inside the "
            "sphere (or on it)";
    return false;
  }

  report.iterations = RefineCentre(rays, radius, c);
  const double distance = c.norm();
  if (!c.allFinite() || !(distance > radius * (1.0 + kOutsideMargin)) || !(c.z() > 0.0))
  {
    error = "the refinement of the sphere's centre failed (the camera would be inside the "
            "sphere, or the sphere behind it)";
    return false;
  }
  centre = c;
  report.pointCount = static_cast<int>(n);
  report.distance = distance;
  const double sinAlpha = radius / distance;
  const double cosAlpha = std::sqrt((1.0 - sinAlpha) * (1.0 + sinAlpha));
  report.halfAngle = std::asin(sinAlpha);
  report.rmsAngle = std::sqrt(ConeCost(rays, radius, c) / static_cast<double>(n));
  report.centreSigma = CentreSigma(rays, radius, c);
  const Vec3 d = c / distance;
  Vec3 e1, e2;
  PerpendicularBasis(d, e1, e2);
  double sum = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    const double dist =
      PixelDistanceToOutline(camera, d, e1, e2, cosAlpha, sinAlpha, rays[i], outlinePixels[i]);
    sum += dist * dist;
  }
  report.rmsPixels = std::sqrt(sum / static_cast<double>(n));
  if (!std::isfinite(report.rmsPixels) || !std::isfinite(report.rmsAngle))
  {
    // A radius far out of scale (1e200) leaves the cone's numbers without precision.
    error = "the fit of a sphere of radius " + std::to_string(radius) +
      " to the outline has no finite residual (is the radius in the calibration's length unit?)";
    return false;
  }
  return true;
}

MirrorDescription MirrorOfOutline(const Vec3& centre, double radius)
{
  return SphereMirror{ centre, radius };
}
} // namespace catar
