// The cameras of the tests and benchmarks, in one place (VTK-free; TestUtilities.h puts them in a
// vtkCatadioptricCamera).
#ifndef catarTestCameras_h
#define catarTestCameras_h

#include "CameraModel.h"
#include "SphereMirror.h"

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

/// The same rig with a smaller image: 640 x 480 pixels, f = 480 (the filter tests).
inline catar::CameraModel SmallDemoCameraModel()
{
  catar::CameraModel m = DemoCameraModel();
  m.intrinsics = catar::Intrinsics{ 480.0, 480.0, 319.5, 239.5, 0.0, 640, 480 };
  return m;
}
} // namespace catar_test

#endif
