#include "ConicFit.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SVD>

#include <limits>
#include <sstream>

namespace catar
{
namespace detail
{
namespace
{
// Singular value ratio below which the conic through the points is not unique.
constexpr double kRankRatio = 1e-10;
} // namespace

// ---- Conics ---------------------------------------------------------------------------------

bool FitConic(const Vec2* points, std::size_t n, Mat3& conic)
{
  if (n < 5)
  {
    return false;
  }
  Vec2 mean = Vec2::Zero();
  for (std::size_t i = 0; i < n; ++i)
  {
    mean += points[i];
  }
  mean /= static_cast<double>(n);
  double spread = 0.0;
  for (std::size_t i = 0; i < n; ++i)
  {
    spread += (points[i] - mean).norm();
  }
  spread /= static_cast<double>(n);
  if (!(spread > 0.0) || !std::isfinite(spread))
  {
    return false;
  }
  const double s = std::sqrt(2.0) / spread;
  Eigen::Matrix<double, Eigen::Dynamic, 6> design(static_cast<Eigen::Index>(n), 6);
  for (std::size_t i = 0; i < n; ++i)
  {
    const double x = s * (points[i].x() - mean.x());
    const double y = s * (points[i].y() - mean.y());
    design.row(static_cast<Eigen::Index>(i)) << x * x, x * y, y * y, x, y, 1.0;
  }
  const Eigen::JacobiSVD<Eigen::Matrix<double, Eigen::Dynamic, 6>> svd(design, Eigen::ComputeFullV);
  const auto& sv = svd.singularValues(); // min(n, 6) values, descending
  if (!(sv(4) > kRankRatio * sv(0)))
  {
    return false; // a second null direction: many conics fit
  }
  const Eigen::Matrix<double, 6, 1> c = svd.matrixV().col(5);
  Mat3 q;
  q << c(0), 0.5 * c(1), 0.5 * c(3), 0.5 * c(1), c(2), 0.5 * c(4), 0.5 * c(3), 0.5 * c(4), c(5);
  Mat3 t;
  t << s, 0.0, -s * mean.x(), 0.0, s, -s * mean.y(), 0.0, 0.0, 1.0;
  conic = t.transpose() * q * t;
  const double norm = conic.norm();
  if (!(norm > 0.0) || !conic.allFinite())
  {
    return false;
  }
  conic /= norm;
  return true;
}

ConicKind EllipseOf(const Mat3& conic, Ellipse& e)
{
  Mat3 q = conic;
  Eigen::Matrix2d q2 = q.topLeftCorner<2, 2>();
  if (q2.trace() < 0.0)
  {
    q = -q;
    q2 = -q2;
  }
  if (!(q2.determinant() > 1e-12 * q2.squaredNorm()))
  {
    return ConicKind::NotElliptic;
  }
  const Vec2 l = q.topRightCorner<2, 1>();
  e.centre = -q2.inverse() * l;
  const double k = q(2, 2) + l.dot(e.centre); // (x - c)^T Q2 (x - c) = -k
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> es(q2);
  const Vec2& lambda = es.eigenvalues(); // ascending, both positive
  if (!(k < 0.0) || !(lambda(0) > 0.0) || !e.centre.allFinite())
  {
    return ConicKind::Imaginary;
  }
  e.Q = q;
  e.a = std::sqrt(-k / lambda(0));
  e.b = std::sqrt(-k / lambda(1));
  e.major = es.eigenvectors().col(0);
  e.minor = Vec2(-e.major.y(), e.major.x());
  return std::isfinite(e.a) && std::isfinite(e.b) && e.b > 0.0 ? ConicKind::Ellipse
                                                               : ConicKind::Imaginary;
}

double SampsonDistance(const Mat3& q, const Vec2& p, Vec2* normal)
{
  const Vec3 h(p.x(), p.y(), 1.0);
  const Vec3 qh = q * h;
  const Vec2 g = 2.0 * qh.head<2>();
  const double gn = g.norm();
  if (!(gn > 0.0))
  {
    return std::numeric_limits<double>::infinity();
  }
  if (normal)
  {
    *normal = g / gn;
  }
  return std::abs(h.dot(qh)) / gn;
}

// ---- The lens -------------------------------------------------------------------------------

std::string ValidateLens(const CameraModel& camera)
{
  CameraModel lens;
  lens.intrinsics = camera.intrinsics;
  lens.distortion = camera.distortion;
  return lens.Validate();
}

// ---- Messages -------------------------------------------------------------------------------

std::string Describe(double value, int precision)
{
  std::ostringstream out;
  out.precision(precision);
  out << value;
  return out.str();
}
} // namespace detail
} // namespace catar
