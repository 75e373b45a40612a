// The cameras of the tests and benchmarks, in one place (VTK-free; TestUtilities.h puts them in a
// vtkCatadioptricCamera).
#ifndef catarTestCameras_h
#define catarTestCameras_h

#include "CameraModel.h"
#include "SphereMirror.h"

#include <cmath>
#include <vector>

namespace catar_test
{
/// The sphere a mirror description holds (the tests' cameras are spheres).
inline catar::SphereMirror Sphere(const catar::MirrorDescription& mirror)
{
  catar::SphereMirror s;
  catar::SphereMirror::From(mirror, s);
  return s;
}

/// The demo rig (Data/calibration/demo-camera.yaml and the built-in demo scene's camera; a test
/// checks all three agree): a 5 cm mirror 14 cm in front of the camera, which sits at world
/// (0, -0.14, 1) looking along +y, image up = world +z; 1328 x 1048 pixels, f = 1000.
inline catar::CameraModel DemoCameraModel()
{
  catar::CameraModel m;
  m.intrinsics = catar::Intrinsics{ 1000.0, 1000.0, 663.5, 523.5, 0.0, 1328, 1048 };
  m.mirror = catar::SphereMirror{ catar::Vec3(0.0, 0.0, 0.14), 0.05 };
  m.worldToCamera << 1, 0, 0, 0, 0, 0, -1, 1, 0, 1, 0, 0.14, 0, 0, 0, 1;
  return m;
}

/// The demo rig with a hyperbolic mirror tilted 4 degrees off the camera's axis (a non-central
/// rig): a = 3 cm, b = 4 cm, the camera near the outer focus, the sheet from its vertex to z = 7 cm
/// (as Data/scenes/hyperbolic-tilted.yaml).
inline catar::CameraModel TiltedHyperboloidCameraModel()
{
  catar::CameraModel m = DemoCameraModel();
  const double a = 0.03, b = 0.04, c = 0.05, tilt = 4.0 * 3.14159265358979323846 / 180.0;
  // mirror_to_camera: a rotation of `tilt` about the camera's x axis, the mirror frame's origin
  // (the hyperboloid's centre) c ahead of the camera.
  const double h[16] = { 1, 0, 0, 0, 0, std::cos(tilt), -std::sin(tilt), 0, 0, std::sin(tilt),
    std::cos(tilt), c, 0, 0, 0, 1 };
  std::vector<double> p = { a, b };
  p.insert(p.end(), h, h + 16);
  p.push_back(a);
  p.push_back(0.07);
  m.mirror = catar::MirrorDescription("hyperboloid", p);
  return m;
}

/// The same rig with a smaller image: 640 x 480 pixels, f = 480 (the filter tests).
inline catar::CameraModel SmallDemoCameraModel()
{
  catar::CameraModel m = DemoCameraModel();
  m.intrinsics = catar::Intrinsics{ 480.0, 480.0, 319.5, 239.5, 0.0, 640, 480 };
  return m;
}
} // namespace catar_test

#endif
