// CatadioptricAR Core (private): conics fitted to points, and the lens check and the number
// formatting of the messages. Not installed; shared by the two halves of MirrorOutline.h: the
// outline's detection in an image (MirrorOutlineDetection.cxx) and the sphere from an outline
// (MirrorOutline.cxx).
#ifndef catarConicFit_h
#define catarConicFit_h

#include "CameraModel.h"

#include <cmath>
#include <cstddef>
#include <string>

namespace catar
{
namespace detail
{
// ---- Conics ---------------------------------------------------------------------------------

/// The algebraic least-squares conic (x^T Q x = 0 for x = (u, v, 1)) through n points, fitted after
/// Hartley's normalisation (centroid at the origin, mean distance sqrt(2)) and returned in the
/// points' own coordinates with unit Frobenius norm. False when the points fix no single conic
/// (fewer than 5 distinct points, collinear points, NaN).
bool FitConic(const Vec2* points, std::size_t n, Mat3& conic);

/// A real ellipse x^T Q x = 0, Q scaled so that its 2x2 block is positive definite.
struct Ellipse
{
  Mat3 Q = Mat3::Identity();
  Vec2 centre = Vec2::Zero();
  Vec2 major = Vec2::UnitX(); // unit direction of the semi-axis a
  Vec2 minor = Vec2::UnitY(); // unit direction of the semi-axis b
  double a = 0.0;             // semi-major axis
  double b = 0.0;             // semi-minor axis

  Vec2 At(double phi) const
  {
    return centre + a * std::cos(phi) * major + b * std::sin(phi) * minor;
  }
  double AngleOf(const Vec2& p) const // the parameter phi of At nearest p's direction
  {
    const Vec2 r = p - centre;
    return std::atan2(r.dot(minor) / b, r.dot(major) / a);
  }
};

/// What a conic is: an ellipse, or why not.
enum class ConicKind
{
  Ellipse,
  NotElliptic, // a hyperbola, a parabola or a pair of lines
  Imaginary    // no real point (or a single one)
};

/// The ellipse that the conic is, or why it is none.
ConicKind EllipseOf(const Mat3& conic, Ellipse& e);

/// Sampson's first-order distance of p from the conic, and the conic's unit normal there.
double SampsonDistance(const Mat3& q, const Vec2& p, Vec2* normal = nullptr);

// ---- The lens -------------------------------------------------------------------------------

/// Empty when the camera's intrinsics and distortion are usable (its mirror and pose are not
/// looked at).
std::string ValidateLens(const CameraModel& camera);

// ---- Messages -------------------------------------------------------------------------------

/// The value with `precision` significant digits, for an error message.
std::string Describe(double value, int precision = 3);
} // namespace detail
} // namespace catar

#endif
