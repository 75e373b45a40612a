// CatadioptricAR Core: a quadric mirror's pose from its rim's outline (QuadricFromRim,
// MirrorOutline.h).
#include "MirrorOutline.h"

#include "ConicFit.h"
#include "QuadricMirror.h"

#include <Eigen/Dense>
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
using detail::Describe;
using detail::ValidateLens;

constexpr double kPi = 3.14159265358979323846;
// Two fits are alike when their costs differ by less than this many times the residuals'
// variance: three sigmas (9) for points that count as a fifth as many (a detected outline is
// smoothed along the rim over about five of its points).
constexpr double kAlike = 45.0;

// The rim: a circle of radius rho about the mirror frame's z axis at height z, placed in the
// camera frame by its centre c and unit normal n (the mirror's axis).
struct Rim
{
  Vec3 centre = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
};

// The residuals of the rays against the rim (radius rho): where each ray meets the rim's plane,
// its distance from the rim circle, scaled to about a pixel (focal / depth). False when a ray
// misses the plane in front of the camera.
bool Residuals(const std::vector<Vec3>& rays, const Rim& rim, double rho, double focal,
  Eigen::VectorXd& residuals)
{
  residuals.resize(static_cast<Eigen::Index>(rays.size()));
  for (std::size_t i = 0; i < rays.size(); ++i)
  {
    const double denominator = rim.normal.dot(rays[i]);
    const double t = rim.normal.dot(rim.centre) / denominator;
    if (!(std::abs(denominator) > 1e-12) || !(t > 0.0) || !std::isfinite(t))
    {
      return false;
    }
    const Vec3 p = t * rays[i];
    residuals(static_cast<Eigen::Index>(i)) = ((p - rim.centre).norm() - rho) * focal / p.z();
  }
  return residuals.allFinite();
}

// The rim moved by the five numbers x: the centre by x(0..2), the normal turned towards e1, e2 by
// x(3), x(4).
Rim Moved(const Rim& rim, const Vec3& e1, const Vec3& e2, const Eigen::Matrix<double, 5, 1>& x)
{
  Rim moved;
  moved.centre = rim.centre + x.head<3>();
  moved.normal = (rim.normal + x(3) * e1 + x(4) * e2).normalized();
  return moved;
}

// Distance from p to the polyline through `line` (closed).
double ToPolyline(const std::vector<Vec2>& line, const Vec2& p)
{
  double nearest = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k < line.size(); ++k)
  {
    const Vec2& a = line[k];
    const Vec2& b = line[(k + 1) % line.size()];
    const double length = (b - a).squaredNorm();
    const double t = length > 0.0 ? std::clamp((p - a).dot(b - a) / length, 0.0, 1.0) : 0.0;
    nearest = std::min(nearest, (a + t * (b - a) - p).norm());
  }
  return nearest;
}
// Levenberg-Marquardt on the rim's centre and (when `unknowns` is 5) normal, from `rim`: the rim
// that fits the rays, its residuals, iterations, and one sigma of its centre (worst direction)
// and normal (radians) from s^2 (J^T J)^-1. False when the rays miss the start's rim plane.
struct RimFit
{
  Rim rim;
  double cost = 0.0; // sum of squared residuals (pixels^2)
  int iterations = 0;
  double centreSigma = 0.0;
  double axisSigma = 0.0;
};

bool FitRim(const std::vector<Vec3>& rays, const Rim& start, double rho, double focal, int unknowns,
  RimFit& fit)
{
  fit = RimFit();
  fit.rim = start;
  Rim& rim = fit.rim;
  Eigen::VectorXd r;
  if (!Residuals(rays, rim, rho, focal, r))
  {
    return false;
  }
  const auto n = static_cast<Eigen::Index>(rays.size());
  const double distance = rim.centre.norm();
  const auto jacobian = [&](const Vec3& e1, const Vec3& e2, Eigen::MatrixXd& J) {
    J.resize(n, unknowns);
    for (int k = 0; k < unknowns; ++k)
    {
      Eigen::Matrix<double, 5, 1> step = Eigen::Matrix<double, 5, 1>::Zero();
      const double h = k < 3 ? 1e-7 * distance : 1e-7;
      step(k) = h;
      Eigen::VectorXd plus, minus;
      if (!Residuals(rays, Moved(rim, e1, e2, step), rho, focal, plus) ||
        !Residuals(rays, Moved(rim, e1, e2, -step), rho, focal, minus))
      {
        return false;
      }
      J.col(k) = (plus - minus) / (2.0 * h);
    }
    return true;
  };
  double cost = r.squaredNorm();
  double lambda = 1e-3;
  for (int iteration = 0; iteration < 200; ++iteration)
  {
    fit.iterations = iteration + 1;
    Vec3 e1, e2;
    PerpendicularBasis(rim.normal, e1, e2);
    Eigen::MatrixXd J;
    if (!jacobian(e1, e2, J))
    {
      break;
    }
    const Eigen::MatrixXd JtJ = J.transpose() * J;
    const Eigen::VectorXd Jtr = J.transpose() * r;
    bool improved = false;
    double gain = 0.0;
    for (int attempt = 0; attempt < 30 && !improved; ++attempt)
    {
      Eigen::MatrixXd A = JtJ;
      A.diagonal() *= 1.0 + lambda;
      Eigen::Matrix<double, 5, 1> delta = Eigen::Matrix<double, 5, 1>::Zero();
      delta.head(unknowns) = A.ldlt().solve(-Jtr);
      const Rim trial = Moved(rim, e1, e2, delta);
      Eigen::VectorXd trialResiduals;
      if (delta.allFinite() && Residuals(rays, trial, rho, focal, trialResiduals) &&
        trialResiduals.squaredNorm() < cost)
      {
        gain = cost - trialResiduals.squaredNorm();
        rim = trial;
        r = trialResiduals;
        cost = r.squaredNorm();
        lambda = std::max(lambda / 10.0, 1e-12);
        improved = true;
      }
      else
      {
        lambda *= 10.0;
      }
    }
    if (!improved || gain < 1e-15 * (1.0 + cost))
    {
      break;
    }
  }
  fit.cost = cost;
  Vec3 e1, e2;
  PerpendicularBasis(rim.normal, e1, e2);
  Eigen::MatrixXd J;
  if (jacobian(e1, e2, J) && n > unknowns)
  {
    const double variance = cost / static_cast<double>(n - unknowns);
    const Eigen::MatrixXd covariance =
      variance * (J.transpose() * J).ldlt().solve(Eigen::MatrixXd::Identity(unknowns, unknowns));
    const Eigen::SelfAdjointEigenSolver<Mat3> position(covariance.topLeftCorner<3, 3>());
    fit.centreSigma = std::sqrt(std::max(position.eigenvalues().maxCoeff(), 0.0));
    if (unknowns == 5)
    {
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> axis(
        covariance.bottomRightCorner<2, 2>());
      fit.axisSigma = std::sqrt(std::max(axis.eigenvalues().maxCoeff(), 0.0));
    }
  }
  return true;
}
} // namespace

bool QuadricFromRim(const CameraModel& camera, const std::vector<Vec2>& outlinePixels,
  MirrorDescription& mirror, RimOutlineReport& report, std::string& error)
{
  return QuadricFromRim(camera, outlinePixels, RimFitOptions(), mirror, report, error);
}

bool QuadricFromRim(const CameraModel& camera, const std::vector<Vec2>& outlinePixels,
  const RimFitOptions& options, MirrorDescription& mirror, RimOutlineReport& report,
  std::string& error)
{
  report = RimOutlineReport();
  if (const std::string lens = ValidateLens(camera); !lens.empty())
  {
    error = "the camera is not usable: " + lens;
    return false;
  }
  QuadricGeometry g;
  std::string shapeError;
  if (!QuadricFromDescription(mirror, g, &shapeError))
  {
    error = "the mirror (" + mirror.type +
      ") is not a quadric mirror with mirror_to_camera and z_range: a rim needs one";
    return false;
  }
  if (!shapeError.empty())
  {
    error = "the mirror's shape is not usable: " + shapeError;
    return false;
  }
  const Mat4& o = g.omega;
  const double scale = o.cwiseAbs().maxCoeff();
  const double tolerance = 1e-9 * scale;
  if (!(scale > 0.0) || std::abs(o(0, 0) - o(1, 1)) > tolerance || std::abs(o(0, 1)) > tolerance ||
    std::abs(o(0, 2)) > tolerance || std::abs(o(1, 2)) > tolerance ||
    std::abs(o(0, 3)) > tolerance || std::abs(o(1, 3)) > tolerance || !(o(0, 0) != 0.0))
  {
    error = "the mirror is not a surface of revolution about its z axis: its rim is no circle";
    return false;
  }
  // The rim: the end of z_range where the mirror is widest (x^2 + y^2 = rho^2 there).
  const auto rho2 = [&](double z) {
    return -(o(2, 2) * z * z + 2.0 * o(2, 3) * z + o(3, 3)) / o(0, 0);
  };
  const double z = rho2(g.zmax) >= rho2(g.zmin) ? g.zmax : g.zmin;
  if (!(rho2(z) > 0.0))
  {
    error = "the mirror has no rim at either end of z_range (" + Describe(g.zmin) + ", " +
      Describe(g.zmax) + "): the surface does not reach there";
    return false;
  }
  const double rho = std::sqrt(rho2(z));
  const std::size_t n = outlinePixels.size();
  if (n < 5)
  {
    error = "a rim needs at least 5 outline points (got " + std::to_string(n) + ")";
    return false;
  }
  std::vector<Vec3> rays(n);
  for (std::size_t i = 0; i < n; ++i)
  {
    Vec2 xy;
    if (!outlinePixels[i].allFinite() || !camera.PixelToNormalized(outlinePixels[i], xy))
    {
      error = "outline point " + std::to_string(i) +
        " is not finite or lies beyond the range of the camera's distortion model";
      return false;
    }
    rays[i] = Vec3(xy.x(), xy.y(), 1.0).normalized();
  }

  // The rim from the description's pose; with the axis fitted, also from the other tilt that a
  // circle's image allows (the normal mirrored about the line of sight to the rim's centre): the
  // better fit is taken; when the two fit alike (their costs differ by less than kAlike s^2;
  // through a pinhole both fit exactly) the tilt is ambiguous and the one nearer the guess is
  // taken.
  const Mat3 R0 = g.mirrorToCamera.topLeftCorner<3, 3>();
  const Vec3 t0 = g.mirrorToCamera.topRightCorner<3, 1>();
  Rim first;
  first.normal = R0.col(2);
  first.centre = R0 * Vec3(0.0, 0.0, z) + t0;
  const double focal = std::max(camera.intrinsics.fx, camera.intrinsics.fy);
  const int unknowns = options.fitAxis ? 5 : 3;
  RimFit fit;
  if (!FitRim(rays, first, rho, focal, unknowns, fit))
  {
    error = "the outline's rays miss the first guess's rim plane: mirror_to_camera is too far off "
            "(or the outline is not the rim)";
    return false;
  }
  if (options.fitAxis)
  {
    // The rays' cone x^T Q x = 0 (x = (u, v, 1), normalised coordinates), whose eigenvalues are
    // two of one sign and one of the other: a circle's two planes have normals +-a v1 + b v3 (v3
    // the lone eigenvalue's eigenvector, v1 that of the larger of the other two), mirror images
    // across the plane of v2 and v3.
    std::vector<Vec2> normalised(n);
    for (std::size_t i = 0; i < n; ++i)
    {
      normalised[i] = Vec2(rays[i].x() / rays[i].z(), rays[i].y() / rays[i].z());
    }
    Mat3 Q;
    Vec3 v1 = Vec3::Zero();
    if (detail::FitConic(normalised.data(), n, Q))
    {
      Mat3 q = Q;
      if (q.determinant() > 0.0)
      {
        q = -q; // two positive eigenvalues and one negative
      }
      const Eigen::SelfAdjointEigenSolver<Mat3> es(q);
      v1 = es.eigenvectors().col(2); // the largest
    }
    // Fits from the other tilt of the first fit and of the guess.
    std::vector<RimFit> fits = { fit };
    const auto mirrored = [&](const Vec3& normal) {
      const Vec3 m = (normal - 2.0 * normal.dot(v1) * v1).normalized();
      return m.dot(first.normal) < 0.0 ? Vec3(-m) : m;
    };
    for (const Vec3& normal : { mirrored(fit.rim.normal), mirrored(first.normal) })
    {
      Rim start = fit.rim;
      start.normal = normal;
      RimFit other;
      if (v1.norm() > 0.5 && FitRim(rays, start, rho, focal, unknowns, other))
      {
        fits.push_back(other);
      }
    }
    const auto angle = [](const Vec3& p, const Vec3& q) {
      return std::atan2(p.cross(q).norm(), p.dot(q));
    };
    std::size_t best = 0;
    for (std::size_t k = 1; k < fits.size(); ++k)
    {
      best = fits[k].cost < fits[best].cost ? k : best;
    }
    const double variance = fits[best].cost / static_cast<double>(static_cast<int>(n) - unknowns);
    const double limit = kAlike * variance + 1e-12 * (1.0 + static_cast<double>(n));
    // The fits alike to the best but with another axis: the tilt is ambiguous. The one nearer
    // the guess is taken, the farthest from it reported.
    std::size_t chosen = best;
    std::size_t farthest = best;
    for (std::size_t k = 0; k < fits.size(); ++k)
    {
      const bool alike = fits[k].cost - fits[best].cost <= limit;
      if (!alike)
      {
        continue;
      }
      if (angle(fits[k].rim.normal, first.normal) < angle(fits[chosen].rim.normal, first.normal))
      {
        chosen = k;
      }
    }
    for (std::size_t k = 0; k < fits.size(); ++k)
    {
      const bool alike = fits[k].cost - fits[best].cost <= limit;
      if (alike &&
        angle(fits[k].rim.normal, fits[chosen].rim.normal) >
          angle(fits[farthest].rim.normal, fits[chosen].rim.normal))
      {
        farthest = k;
      }
    }
    // Where noise merges the two minima into one flat valley, the cost's profile along the tilt
    // (the axis turned towards its mirror image, the centre refitted at each) shows it: the
    // farthest tilt, either side, that fits alike.
    {
      const Vec3 from = fits[chosen].rim.normal;
      const Vec3 towards = mirrored(from);
      const double span = std::max(angle(from, towards), 6.0 * fits[chosen].axisSigma);
      const Vec3 side = (towards - from.dot(towards) * from).normalized();
      for (int k = -12; k <= 12 && side.allFinite(); ++k)
      {
        const double tilt = 1.5 * span * k / 12.0;
        Rim start = fits[chosen].rim;
        start.normal = (std::cos(tilt) * from + std::sin(tilt) * side).normalized();
        RimFit profile;
        if (k != 0 && FitRim(rays, start, rho, focal, 3, profile) &&
          profile.cost - fits[best].cost <= limit &&
          angle(profile.rim.normal, from) > angle(fits[farthest].rim.normal, from))
        {
          fits.push_back(profile);
          farthest = fits.size() - 1;
        }
      }
    }
    const double turn = angle(fits[farthest].rim.normal, fits[chosen].rim.normal);
    if (turn > 3.0 * fits[chosen].axisSigma)
    {
      report.ambiguousTilt = turn;
      report.otherAxis = fits[farthest].rim.normal;
    }
    fit = fits[chosen];
  }
  const Rim& rim = fit.rim;
  report.iterations = fit.iterations;
  report.centreSigma = fit.centreSigma;
  report.axisSigma = fit.axisSigma;

  // The mirror placed: turned as little as takes its axis to the rim's normal.
  const Mat3 turn = Eigen::Quaterniond::FromTwoVectors(first.normal, rim.normal).toRotationMatrix();
  const Mat3 R = turn * R0;
  const Vec3 t = rim.centre - R * Vec3(0.0, 0.0, z);
  if (!R.allFinite() || !t.allFinite())
  {
    error = "the rim's fit failed (no finite pose)";
    return false;
  }
  // mirror_to_camera, row-major, before the two numbers of z_range.
  double* h = mirror.parameters.data() + (mirror.parameters.size() - 18);
  for (int row = 0; row < 3; ++row)
  {
    for (int col = 0; col < 3; ++col)
    {
      *h++ = R(row, col);
    }
    *h++ = t(row);
  }
  report.pointCount = static_cast<int>(n);
  report.rimRadius = rho;
  report.rimZ = z;
  report.rimCentre = rim.centre;
  report.axis = rim.normal;
  report.axisTurn = std::acos(std::clamp(first.normal.dot(rim.normal), -1.0, 1.0));
  report.shift = (rim.centre - first.centre).norm();
  // The RMS distance of the points from the rim's image (2880 points round it).
  const std::vector<Vec2> line = RimOutline(camera, report, 2880);
  double sum = 0.0;
  for (const Vec2& p : outlinePixels)
  {
    const double d = ToPolyline(line, p);
    sum += d * d;
  }
  report.rmsPixels = std::sqrt(sum / static_cast<double>(n));
  if (!std::isfinite(report.rmsPixels))
  {
    error = "the rim's fit failed (its outline leaves the camera's view)";
    return false;
  }
  return true;
}

std::vector<Vec2> RimOutline(const CameraModel& camera, const RimOutlineReport& rim, int count)
{
  std::vector<Vec2> line;
  Vec3 e1, e2;
  PerpendicularBasis(rim.axis, e1, e2);
  for (int k = 0; k < count; ++k)
  {
    const double angle = 2.0 * kPi * k / count;
    const Vec3 p = rim.rimCentre + rim.rimRadius * (std::cos(angle) * e1 + std::sin(angle) * e2);
    if (p.z() > 0.0)
    {
      line.push_back(camera.DirectionToPixel(p));
    }
  }
  return line;
}
} // namespace catar
