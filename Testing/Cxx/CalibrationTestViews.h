// Views of a calibration board around a rig's mirror, for the calibration's tests and benchmark:
// the board's poses (facing the mirror, at several distances, angles and turns), and how far a
// calibrated mirror is from the true one.
#ifndef catarCalibrationTestViews_h
#define catarCalibrationTestViews_h

#include "CameraModel.h"
#include "Markers.h"
#include "Mirror.h"
#include "QuadricMirror.h"
#include "RigCalibration.h"
#include "SphereMirror.h"
#include "TestCameras.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <vector>

namespace catar_test
{
/// A board of n x n markers (DICT_4X4_50, ids 0 to n^2 - 1) of `size` metres, `pitch` apart,
/// centred on the board's origin, printed in its x-y plane facing +z.
inline catar::MarkerBoard CalibrationBoard(double size = 0.06, double pitch = 0.09, int n = 3)
{
  catar::MarkerBoard board;
  for (int k = 0; k < n * n; ++k)
  {
    catar::BoardMarker m;
    m.id = k;
    m.translate =
      catar::Vec3((k % n - 0.5 * (n - 1)) * pitch, (0.5 * (n - 1) - k / n) * pitch, 0.0);
    m.size = size;
    board.markers.push_back(m);
  }
  return board;
}

/// `count` board-to-camera poses around the mirror of `camera` (its viewpoint: the sphere's
/// centre, a quadric's effective viewpoint): the board's centre `distance` metres (varied by up
/// to +-25 %) from it along directions spread around the camera's axis and behind the mirror's
/// equator (the directions a convex mirror shows), its face turned towards the mirror, tilted by
/// up to 25 degrees and turned in its plane.
inline std::vector<catar::Mat4> BoardPosesAround(
  const catar::Vec3& viewpoint, int count, double distance = 0.4)
{
  std::vector<catar::Mat4> poses;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < count; ++i)
  {
    const double phi = 2.0 * pi * (i + 0.3) / count;
    const double alpha = (100.0 + 25.0 * ((i * 7) % 3)) * pi / 180.0; // from the camera's axis
    const catar::Vec3 u(
      std::cos(phi) * std::sin(alpha), std::sin(phi) * std::sin(alpha), std::cos(alpha));
    const double d = distance * (0.75 + 0.5 * ((i * 5) % 4) / 3.0);
    const catar::Vec3 centre = viewpoint + d * u;
    // The board's +z towards the mirror, tilted about a direction across it.
    const catar::Vec3 across = u.unitOrthogonal();
    const double tilt = (25.0 * (((i * 3) % 5) - 2) / 2.0) * pi / 180.0;
    const catar::Vec3 normal = Eigen::AngleAxisd(tilt, across) * (-u);
    const catar::Vec3 x0 = normal.unitOrthogonal();
    const catar::Vec3 x = Eigen::AngleAxisd(0.7 * i, normal) * x0;
    catar::Mat4 pose = catar::Mat4::Identity();
    pose.block<3, 1>(0, 0) = x;
    pose.block<3, 1>(0, 1) = normal.cross(x);
    pose.block<3, 1>(0, 2) = normal;
    pose.topRightCorner<3, 1>() = centre;
    poses.push_back(pose);
  }
  return poses;
}

/// A hyperbolic mirror (a = 3 cm, b = 4 cm) tilted 4 degrees about the camera's x axis, its
/// centre 7.5 cm ahead: the camera 2.5 cm from its outer focus, clearly non-central (the demo's
/// tilted hyperboloid has the camera 3.5 mm from the focus: so nearly central that its shape and
/// distance trade for one another in the image). The sheet from its vertex to z = 7 cm.
inline catar::CameraModel OffFocusHyperboloidCameraModel()
{
  catar::CameraModel m = catar_test::TiltedHyperboloidCameraModel();
  m.mirror.parameters[2 + 11] = 0.075; // mirror_to_camera's z translation
  return m;
}

/// An off-axis paraboloid: focal 1.5 cm, its axis turned 6 degrees about the camera's y axis and
/// its focus 2 mm off the camera's axis, 12 cm ahead; the bowl from its vertex to z = 3 cm.
inline catar::CameraModel OffAxisParaboloidCameraModel()
{
  catar::CameraModel m = DemoCameraModel();
  const double f = 0.015, tilt = 6.0 * 3.14159265358979323846 / 180.0;
  const double h[16] = { std::cos(tilt), 0, std::sin(tilt), 0.002, 0, 1, 0, 0, -std::sin(tilt), 0,
    std::cos(tilt), 0.12, 0, 0, 0, 1 };
  std::vector<double> p = { f };
  p.insert(p.end(), h, h + 16);
  p.push_back(-f);
  p.push_back(0.03);
  m.mirror = catar::MirrorDescription("paraboloid", p);
  return m;
}

/// The mirror moved by `metres` (along (1, -1, 1) / sqrt 3), turned by `degrees` (a quadric's,
/// about its frame's x axis) and its shape numbers scaled by 1 + fraction: a start that is off.
inline catar::MirrorDescription MirrorStartOff(
  const catar::MirrorDescription& d, double metres, double degrees, double fraction)
{
  catar::MirrorDescription p = d;
  const catar::Vec3 move = metres * catar::Vec3(1, -1, 1).normalized();
  catar::SphereMirror s;
  if (catar::SphereMirror::From(d, s))
  {
    s.center += move;
    s.radius *= 1.0 + fraction;
    return s;
  }
  const catar::MirrorType* type = catar::FindMirrorType(d.type, d.parameters.size());
  const int offset = type->ParameterOffset("mirror_to_camera");
  Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>> H(p.parameters.data() + offset);
  H.topLeftCorner<3, 3>() = catar::Mat3(H.topLeftCorner<3, 3>()) *
    Eigen::AngleAxisd(degrees * 3.14159265358979323846 / 180.0, catar::Vec3::UnitX())
      .toRotationMatrix();
  H.topRightCorner<3, 1>() += move;
  for (int i = 0; i < offset; ++i)
  {
    p.parameters[static_cast<std::size_t>(i)] *= 1.0 + fraction;
  }
  return p;
}

/// The one-sigma bounds a calibration reports for the mirror: of its position (the centre's or
/// mirror_to_camera's translation, metres: the root of the sum of the components' variances), its
/// tilt (degrees, likewise) and its shape (the largest relative sigma of its size numbers).
inline void MirrorSigmas(const std::vector<catar::CalibratedNumber>& mirror, double& metres,
  double& degrees, double& shape)
{
  double position = 0.0, tilt = 0.0;
  shape = 0.0;
  for (const catar::CalibratedNumber& n : mirror)
  {
    if (n.name.find("tilt") == 0)
    {
      tilt += n.sigma * n.sigma;
    }
    else if (n.name.find("center") == 0 || n.name.find("translation") == 0)
    {
      position += n.sigma * n.sigma;
    }
    else
    {
      shape = std::max(shape, n.sigma / n.value);
    }
  }
  metres = std::sqrt(position);
  degrees = std::sqrt(tilt);
}

/// How far mirror `b` is from mirror `a` (same type): the largest distance between their
/// positions (a sphere's centre, a quadric's mirror_to_camera translation), metres; the angle
/// between their orientations (quadrics), degrees; and the largest relative difference of their
/// shape numbers (radius; a, b; focal; semi-axes; half angle).
inline void MirrorDifference(const catar::MirrorDescription& a, const catar::MirrorDescription& b,
  double& metres, double& degrees, double& shape)
{
  catar::SphereMirror sa, sb;
  if (catar::SphereMirror::From(a, sa) && catar::SphereMirror::From(b, sb))
  {
    metres = (sa.center - sb.center).norm();
    degrees = 0.0;
    shape = std::abs(sb.radius / sa.radius - 1.0);
    return;
  }
  catar::QuadricGeometry ga, gb;
  catar::QuadricFromDescription(a, ga);
  catar::QuadricFromDescription(b, gb);
  metres =
    (ga.mirrorToCamera.topRightCorner<3, 1>() - gb.mirrorToCamera.topRightCorner<3, 1>()).norm();
  // The angle between the mirrors' axes (a turn about a surface of revolution's own axis shows
  // nothing).
  const catar::Vec3 za = ga.mirrorToCamera.block<3, 1>(0, 2);
  const catar::Vec3 zb = gb.mirrorToCamera.block<3, 1>(0, 2);
  degrees = std::atan2(za.cross(zb).norm(), za.dot(zb)) * 180.0 / 3.14159265358979323846;
  shape = 0.0;
  const std::size_t n = a.parameters.size() - 18; // the numbers before mirror_to_camera
  for (std::size_t i = 0; i < n; ++i)
  {
    shape = std::max(shape, std::abs(b.parameters[i] / a.parameters[i] - 1.0));
  }
}
} // namespace catar_test

#endif
