// Frames of a mirror sphere in a room, rendered by POV-Ray, for checks of the mirror-outline tool
// against a renderer the project did not write: a physical mirror (reflectance below 1, so it is
// darker than what it reflects) before a backdrop, which it reflects at its rim as a real mirror
// does, so the rim's contrast is the backdrop's brightness times (1 - reflectance).
//
// The scene is written in the camera's frame (OpenCV's: x right, y down, z ahead) with y negated
// for POV-Ray, as in PovRayMarkerFrames.h: a pinhole camera of the intrinsics' focal lengths with
// its principal point at the image centre; the mirror (a whole sphere, or a dome: the sphere cut
// by a plane, standing on a grey post); a square backdrop of uniform grey across the view behind
// the mirror; and a room (a large sphere with a coloured, blotchy wall and a floor) around them,
// which the mirror shows. Every surface but the mirror is self-lit (ambient 1, no light sources).
#ifndef catarPovRayOutlineFrames_h
#define catarPovRayOutlineFrames_h

#include "CameraModel.h"
#include "PovRayMarkerFrames.h" // HavePovRay

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

namespace catar_independent
{
/// A mirror before a backdrop, camera frame (metres).
struct OutlineScene
{
  catar::Intrinsics intrinsics{ 1000.0, 1000.0, 663.5, 523.5, 0.0, 1328, 1048 };
  catar::Vec3 centre{ 0.0, 0.0, 0.14 }; ///< the sphere's centre
  double radius = 0.05;
  double reflectance = 0.7;       ///< of the mirror (polished chrome reflects 0.6-0.7 of the light)
  double backdrop = 0.9;          ///< grey level (0-1) of the backdrop
  double backdropBehind = 0.3;    ///< distance of the backdrop behind the mirror's centre (along z)
  double backdropHalfSide = 0.45; ///< the backdrop square's half side
  /// A dome: the part of the sphere on the side of `domeAxis` (unit, camera frame, pointing out
  /// of the dome) beyond the plane at domeCut * radius from the centre along it; the rest is cut
  /// away and a grey post of radius 0.3 R stands below the cut. domeCut <= -1: a whole sphere.
  catar::Vec3 domeAxis{ 0.0, 0.0, -1.0 };
  double domeCut = -2.0;
  /// Instead of the sphere: a hyperboloid's upper sheet (x^2 + y^2) / b^2 - z^2 / a^2 + 1 = 0
  /// between zmin and zmax of its own frame, placed by mirrorToCamera (as the calibration's
  /// hyperboloid type). `centre` then only places the backdrop (behind it by backdropBehind).
  bool hyperboloid = false;
  double a = 0.03, b = 0.04, zmin = 0.03, zmax = 0.07;
  catar::Mat4 mirrorToCamera = catar::Mat4::Identity();
};

/// A vector in POV-Ray's coordinates (the camera frame, y negated).
inline std::string PovVector(const catar::Vec3& v)
{
  std::ostringstream s;
  s.precision(17);
  s << "<" << v.x() << ", " << -v.y() << ", " << v.z() << ">";
  return s.str();
}

/// Renders the scene into dir/NAME.png (anti-aliased: POV-Ray's adaptive sampling, 3 levels).
/// False with a sentence in `error`.
inline bool RenderOutlineFrame(const std::string& dir, const std::string& name,
  const OutlineScene& scene, std::string& png, std::string& error)
{
  const catar::Intrinsics& k = scene.intrinsics;
  if (std::abs(k.cx - 0.5 * (k.width - 1)) > 1e-9 || std::abs(k.cy - 0.5 * (k.height - 1)) > 1e-9 ||
    k.skew != 0.0)
  {
    error = "POV-Ray frames need a centred principal point and no skew";
    return false;
  }
  std::ostringstream s;
  s.precision(17);
  s << "global_settings { assumed_gamma 1.0 max_trace_level 8 }\n";
  // POV-Ray puts pixel (i, j)'s centre at ((i + 0.5) / width, (j + 0.5) / height) of `right` and
  // `up`, as OpenCV: measured with a small white sphere at (0.05, 0.03, 1) m through f = 500 px,
  // its image's centroid at (688.515, 538.517) px against (688.5, 538.5) projected. (The marker
  // frames' camera, PovRayMarkerFrames.h, is turned half a pixel, which this measurement does not
  // bear out: their corners' half-pixel offset has another cause.)
  s << "camera { perspective location <0, 0, 0> direction <0, 0, 1> right <" << k.width / k.fx
    << ", 0, 0> up <0, " << k.height / k.fy << ", 0> }\n";
  s << "background { rgb 0.5 }\n";
  // The room: a wall of coloured blotches all round, 4 m away, and a floor 1 m below the camera.
  s << "sphere { <0, 0, 0>, 4 hollow pigment { bozo scale 0.35 color_map { [0.0 rgb <0.85, 0.8, "
       "0.7>] [0.3 rgb <0.3, 0.35, 0.5>] [0.55 rgb <0.7, 0.45, 0.3>] [0.8 rgb <0.2, 0.25, 0.2>] "
       "[1.0 rgb <0.95, 0.95, 0.9>] } } finish { ambient 1 diffuse 0 } }\n";
  s << "plane { y, -1 pigment { checker rgb 0.35 rgb 0.55 scale 0.25 } finish { ambient 1 "
       "diffuse 0 } }\n";
  // The camera's body, which the mirror shows at its centre (invisible to the camera itself).
  s << "box { <-0.04, -0.03, -0.08>, <0.04, 0.03, -0.001> pigment { rgb 0.05 } finish { ambient "
       "1 diffuse 0 } no_image }\n";
  const double back = scene.centre.z() + scene.backdropBehind;
  const double h = scene.backdropHalfSide;
  s << "box { " << PovVector(catar::Vec3(scene.centre.x() - h, scene.centre.y() - h, back)) << ", "
    << PovVector(catar::Vec3(scene.centre.x() + h, scene.centre.y() + h, back + 0.01))
    << " pigment { rgb " << scene.backdrop << " } finish { ambient 1 diffuse 0 } }\n";
  const std::string mirror =
    "sphere { " + PovVector(scene.centre) + ", " + std::to_string(scene.radius) + " }";
  std::ostringstream finish;
  finish << "pigment { rgb 0 } finish { ambient 0 diffuse 0 reflection " << scene.reflectance
         << " }";
  if (scene.hyperboloid)
  {
    // POV-Ray's matrix maps a row vector p to p M + m3: M is the transpose of (S R), S the y
    // negation, and m3 is S t.
    const catar::Mat3 SR =
      catar::Vec3(1.0, -1.0, 1.0).asDiagonal() * scene.mirrorToCamera.topLeftCorner<3, 3>();
    const catar::Vec3 t = scene.mirrorToCamera.topRightCorner<3, 1>();
    s << "intersection { quadric { <" << 1.0 / (scene.b * scene.b) << ", "
      << 1.0 / (scene.b * scene.b) << ", " << -1.0 / (scene.a * scene.a)
      << ">, <0, 0, 0>, <0, 0, 0>, 1 } plane { z, " << scene.zmax << " } plane { -z, "
      << -scene.zmin << " } matrix <";
    for (int i = 0; i < 3; ++i)
    {
      for (int j = 0; j < 3; ++j)
      {
        s << SR(j, i) << ", ";
      }
    }
    s << t.x() << ", " << -t.y() << ", " << t.z() << "> " << finish.str() << " }\n";
  }
  else if (scene.domeCut <= -1.0)
  {
    s << "object { " << mirror << " " << finish.str() << " }\n";
  }
  else
  {
    // The half-space beyond the cut: POV-Ray's plane keeps what lies below it (against its
    // normal), so the plane's normal is -axis at distance -(c.axis + cut R).
    const catar::Vec3& a = scene.domeAxis;
    const double offset = scene.centre.dot(a) + scene.domeCut * scene.radius;
    s << "intersection { " << mirror << " plane { " << PovVector(-a) << ", " << -offset << " } "
      << finish.str() << " }\n";
    const catar::Vec3 base = scene.centre + scene.domeCut * scene.radius * a;
    s << "cylinder { " << PovVector(base) << ", " << PovVector(base - 0.6 * a) << ", "
      << 0.3 * scene.radius << " pigment { rgb 0.3 } finish { ambient 1 diffuse 0 } }\n";
  }
  return RunPovRay(dir, name, s.str(), k.width, k.height, true, png, error);
}
} // namespace catar_independent

#endif
