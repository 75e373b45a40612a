#include "Types.h"

#include <cmath>

namespace catar
{
namespace
{
constexpr double kNlerpAngle = 1e-6; // below: slerp falls back to normalised lerp
}

const char* ToString(ProjectionStatus status)
{
  switch (status)
  {
    case ProjectionStatus::Valid:
      return "valid";
    case ProjectionStatus::OutsideImage:
      return "outside-image";
    case ProjectionStatus::InsideMirror:
      return "inside-mirror";
    case ProjectionStatus::HiddenByMirror:
      return "hidden-by-mirror";
    case ProjectionStatus::NoReflection:
      return "no-reflection";
    case ProjectionStatus::InvalidInput:
      return "invalid-input";
  }
  return "unknown";
}

Eigen::Quaterniond RotationFromDegrees(const Vec3& degrees)
{
  const double k = 3.14159265358979323846 / 180.0;
  return Eigen::Quaterniond(Eigen::AngleAxisd(k * degrees.z(), Vec3::UnitZ()) *
    Eigen::AngleAxisd(k * degrees.y(), Vec3::UnitY()) *
    Eigen::AngleAxisd(k * degrees.x(), Vec3::UnitX()));
}

Eigen::Quaterniond Slerp(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b, double s)
{
  // The short way: b or -b, whichever is nearer a on the unit sphere of quaternions.
  const Eigen::Vector4d& va = a.coeffs();
  const Eigen::Vector4d vb =
    a.coeffs().dot(b.coeffs()) < 0.0 ? Eigen::Vector4d(-b.coeffs()) : Eigen::Vector4d(b.coeffs());
  if (s == 0.0)
  {
    return a;
  }
  if (s == 1.0)
  {
    return Eigen::Quaterniond(vb);
  }
  // The angle between them, stable for nearly equal and nearly opposite vectors (unlike acos).
  const double angle = 2.0 * std::atan2((va - vb).norm(), (va + vb).norm());
  Eigen::Vector4d v;
  if (angle < kNlerpAngle)
  {
    v = (1.0 - s) * va + s * vb;
  }
  else
  {
    v = (std::sin((1.0 - s) * angle) * va + std::sin(s * angle) * vb) / std::sin(angle);
  }
  return Eigen::Quaterniond(v.normalized());
}

} // namespace catar
