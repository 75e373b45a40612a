// CatadioptricAR Core: the plain types every part shares: vectors and matrices, what became of a
// point or a pixel (ProjectionStatus), the solvers' choice, a forward projection's result (pixel,
// reflection point, path length, status), a back projection's reflected ray, a pose taken apart,
// and the rotations of scene objects and keyframes.
#ifndef catarTypes_h
#define catarTypes_h

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <cmath>
#include <cstdint>

namespace catar
{
using Vec2 = Eigen::Vector2d;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Mat4 = Eigen::Matrix4d;

/// What became of a point (forward projection) or a pixel (back projection).
/// Every result carries one; coordinates of a result that is not Valid/OutsideImage are zero,
/// never NaN.
enum class ProjectionStatus : std::uint8_t
{
  Valid = 0,          ///< reflection found, pixel inside the image
  OutsideImage = 1,   ///< reflection found, but the pixel lies outside the image
  InsideMirror = 2,   ///< the point is inside (or on) the mirror's solid
  HiddenByMirror = 3, ///< the mirror hides the point from every mirror point the camera sees
  NoReflection = 4,   ///< no usable reflection: grazing/degenerate, behind the camera, or a pixel
                      ///< whose ray misses the mirror
  InvalidInput = 5    ///< NaN/Inf input, or an invalid camera
};

/// A short English name for a status ("valid", "outside-image", ...).
const char* ToString(ProjectionStatus status);

/// True for the statuses that carry a mirror point and a pixel (Valid, OutsideImage).
inline bool HasProjection(ProjectionStatus s)
{
  return s == ProjectionStatus::Valid || s == ProjectionStatus::OutsideImage;
}

/// The matrix of the cross product with v: Skew(v) x = v.cross(x).
inline Mat3 Skew(const Vec3& v)
{
  Mat3 m;
  m << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return m;
}

/// The rotation of the angle-axis vector w (SO(3)'s exponential): |w| radians about w.
inline Mat3 RotationFromAngleAxis(const Vec3& w)
{
  const double angle = w.norm();
  return angle > 0.0 ? Eigen::AngleAxisd(angle, w / angle).toRotationMatrix() : Mat3::Identity();
}

/// The left Jacobian of SO(3)'s exponential: d exp(w) = [J_l(w) dw]x exp(w). So the derivative of
/// exp(w) X with respect to w is -[exp(w) X]x J_l(w) (the pose solvers' rotation updates).
inline Mat3 RotationLeftJacobian(const Vec3& w)
{
  const double theta = w.norm();
  const Mat3 W = Skew(w);
  if (theta < 1e-8)
  {
    return Mat3::Identity() + 0.5 * W;
  }
  const double t2 = theta * theta;
  return Mat3::Identity() + (1.0 - std::cos(theta)) / t2 * W +
    (theta - std::sin(theta)) / (t2 * theta) * W * W;
}

/// Two unit vectors perpendicular to the unit vector d and to each other (d, e1, e2
/// right-handed).
inline void PerpendicularBasis(const Vec3& d, Vec3& e1, Vec3& e2)
{
  e1 = d.unitOrthogonal();
  e2 = d.cross(e1);
}

/// Which algorithm finds the reflection point.
enum class SolverType : int
{
  Quartic = 0,   ///< closed-form quartic (Ferrari) + Newton polish
  Iterative = 1, ///< safeguarded Newton on the planar reflection law
  /// The default: the faster where it gives the same answer, which the mirror chooses
  /// (Mirror::Resolve): Iterative for the sphere and most quadrics; Quartic for a quadric with
  /// the camera on its axis, where a point may have several images (a concave part, a cone's
  /// rim) and the quartic keeps the one of shortest path.
  Automatic = 2
};

/// Result of a forward projection. Fields other than status are zero unless HasProjection(status).
struct ProjectedPoint
{
  Vec2 pixel = Vec2::Zero();       ///< pixel coordinates (OpenCV convention)
  Vec3 mirrorPoint = Vec3::Zero(); ///< reflection point on the mirror, camera frame
  double pathLength = 0.0;         ///< distance from the mirror point to the 3D point
  ProjectionStatus status = ProjectionStatus::InvalidInput;
};

/// Result of a back projection: the reflected ray leaves mirrorPoint along direction (unit).
struct BackProjectedRay
{
  Vec3 mirrorPoint = Vec3::Zero();
  Vec3 direction = Vec3::Zero();
  ProjectionStatus status = ProjectionStatus::InvalidInput;
};

/// A world-to-camera pose taken apart once for many points: world <-> camera frame without
/// re-reading the 4x4 matrix (the same arithmetic as CameraModel's WorldToCamera/CameraToWorld).
struct PoseFrames
{
  explicit PoseFrames(const Mat4& worldToCamera)
    : rotation(worldToCamera.topLeftCorner<3, 3>())
    , rotationT(rotation.transpose())
    , translation(worldToCamera.topRightCorner<3, 1>())
    , centre(-rotationT * translation)
  {
  }
  Mat3 rotation;    ///< R, world to camera
  Mat3 rotationT;   ///< R^T, camera to world
  Vec3 translation; ///< t
  Vec3 centre;      ///< -R^T t: the camera centre in world coordinates
  Vec3 ToCamera(const Vec3& pWorld) const { return this->rotation * pWorld + this->translation; }
  Vec3 ToWorld(const Vec3& pCamera) const
  {
    return this->rotationT * (pCamera - this->translation);
  }
};

/// Slerp of two unit quaternions taking the short way (q and -q are the same rotation); exact at
/// s = 0 (a) and s = 1 (b, or -b when that is nearer a); stable when they are nearly equal (falls
/// back to normalised lerp below ~1e-6 rad). The result is normalised.
Eigen::Quaterniond Slerp(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b, double s);

/// The rotation of a scene object's `rotate` (degrees about x, then y, then z, as the object's
/// transform applies them): Rz Ry Rx. Keyframes, objects and markers share it.
Eigen::Quaterniond RotationFromDegrees(const Vec3& degrees);
} // namespace catar

#endif
