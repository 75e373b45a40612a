// Frames of marker boards seen in a mirror (a sphere or a quadric), rendered by POV-Ray: an
// independent ray tracer, with its own anti-aliasing and texture filtering, for checks of what
// reads images (marker detection, pose, calibration) against a renderer the project did not
// write.
//
// The scene is written in the camera's frame (OpenCV's: x right, y down, z ahead) with y negated
// for POV-Ray (a reflection of the whole scene, camera included, leaves the image as it is): a
// pinhole camera of the calibration's focal lengths with its principal point at the image centre
// (POV-Ray has no offset; RenderMarkerFrame refuses another), a perfect mirror sphere, a grey
// floor at world z = 0, a light-grey background, and each marker as a square textured with its
// image (white margin of one bit cell) through uv mapping. Every surface is self-lit (ambient 1,
// no light sources), so the marker's black and white are the image's. An id mask (no
// anti-aliasing, marker k drawn in red k + 1, the rest black) gives which markers are visible
// and how large, independently of the project's projection.
#ifndef catarPovRayMarkerFrames_h
#define catarPovRayMarkerFrames_h

#include "CameraModel.h"
#include "Markers.h"
#include "QuadricMirror.h"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace catar_independent
{
/// True when `povray` runs on this machine.
inline bool HavePovRay()
{
  return std::system("povray --version > /dev/null 2>&1") == 0;
}

/// Writes the scene text to dir/NAME.pov and renders it into dir/NAME.png (`png`) at width x
/// height: anti-aliased (POV-Ray's adaptive sampling, 3 levels) unless `antialias` is false. False
/// with a sentence in `error` (POV-Ray's log: dir/NAME.log).
inline bool RunPovRay(const std::string& dir, const std::string& name, const std::string& scene,
  int width, int height, bool antialias, std::string& png, std::string& error)
{
  const std::string sceneFile = dir + "/" + name + ".pov";
  png = dir + "/" + name + ".png";
  std::ofstream(sceneFile) << scene;
  std::ostringstream command;
  command << "povray +I" << sceneFile << " +O" << png << " +W" << width << " +H" << height
          << " +FN File_Gamma=1.0 -D -V -GA +Q9 " << (antialias ? "+A0.05 +AM2 +R3" : "-A") << " > "
          << dir << "/" << name << ".log 2>&1";
  if (std::system(command.str().c_str()) != 0)
  {
    error = "povray failed: see " + dir + "/" + name + ".log";
    return false;
  }
  return true;
}

/// The mirror of a description as a POV-Ray object in POV-Ray's frame (the camera frame, y
/// negated): the sphere (centre and radius) as a sphere; a quadric type as POV-Ray's quadric of
/// its Omega (mirror frame), clipped to its z_range and placed by mirror_to_camera. A perfect
/// mirror. "" for a description it cannot write.
inline std::string PovRayMirror(const catar::MirrorDescription& description)
{
  std::ostringstream s;
  s.precision(17);
  const std::vector<double>& p = description.parameters;
  const std::string finish = " pigment { rgb 0 } finish { ambient 0 diffuse 0 reflection 1 }";
  if (description.type == "sphere" && p.size() == 4)
  {
    s << "sphere { <" << p[0] << ", " << -p[1] << ", " << p[2] << ">, " << p[3] << finish << " }\n";
    return s.str();
  }
  catar::QuadricGeometry g;
  if (!catar::QuadricFromDescription(description, g) || g.omega.isZero())
  {
    return "";
  }
  const catar::Mat4& W = g.omega;
  // A x^2 + B y^2 + C z^2 + D xy + E xz + F yz + G x + H y + I z + J = 0, mirror frame.
  s << "quadric { <" << W(0, 0) << ", " << W(1, 1) << ", " << W(2, 2) << ">, <" << 2 * W(0, 1)
    << ", " << 2 * W(0, 2) << ", " << 2 * W(1, 2) << ">, <" << 2 * W(0, 3) << ", " << 2 * W(1, 3)
    << ", " << 2 * W(2, 3) << ">, " << W(3, 3) << "\n  clipped_by { box { <-10, -10, " << g.zmin
    << ">, <10, 10, " << g.zmax << "> } }\n";
  // POV-Ray's matrix <a..l>: x' = a x + d y + g z + j, ...: the columns of M = diag(1, -1, 1) H.
  catar::Mat4 M = g.mirrorToCamera;
  M.row(1) *= -1.0;
  s << "  matrix <" << M(0, 0) << ", " << M(1, 0) << ", " << M(2, 0) << ", " << M(0, 1) << ", "
    << M(1, 1) << ", " << M(2, 1) << ", " << M(0, 2) << ", " << M(1, 2) << ", " << M(2, 2) << ", "
    << M(0, 3) << ", " << M(1, 3) << ", " << M(2, 3) << ">\n " << finish << " }\n";
  return s.str();
}

/// Renders the board seen through `camera` (a sphere or quadric mirror, no distortion, the
/// principal point at the image centre) into dir/NAME.png: anti-aliased (POV-Ray's adaptive
/// sampling, 3 levels) or, with idMask, the id mask. `floor`: the grey floor at world z = 0 (else
/// a light-grey plate under the board's markers, as a printed board has). False with a sentence in
/// `error`.
inline bool RenderMarkerFrame(const std::string& dir, const std::string& name,
  const catar::CameraModel& camera, const catar::MarkerBoard& board, bool idMask, std::string& png,
  std::string& error, bool floor = true)
{
  const catar::Intrinsics& k = camera.intrinsics;
  const std::string mirror = PovRayMirror(camera.mirror);
  if (mirror.empty() || std::abs(k.cx - 0.5 * (k.width - 1)) > 1e-9 ||
    std::abs(k.cy - 0.5 * (k.height - 1)) > 1e-9 || k.skew != 0.0 || !camera.distortion.IsZero() ||
    camera.lens != catar::LensType::Pinhole)
  {
    error = "POV-Ray frames need a sphere or quadric mirror, a centred principal point and a "
            "pinhole lens without distortion";
    return false;
  }
  const catar::Mat3 R = camera.worldToCamera.topLeftCorner<3, 3>();
  const catar::Vec3 t = camera.worldToCamera.topRightCorner<3, 1>();
  // A world point in POV-Ray's coordinates: the camera frame, y negated.
  auto pov = [&](const catar::Vec3& w) {
    const catar::Vec3 c = R * w + t;
    std::ostringstream s;
    s.precision(17);
    s << "<" << c.x() << ", " << -c.y() << ", " << c.z() << ">";
    return s.str();
  };
  auto povDirection = [&](const catar::Vec3& w) {
    const catar::Vec3 c = R * w;
    std::ostringstream s;
    s.precision(17);
    s << "<" << c.x() << ", " << -c.y() << ", " << c.z() << ">";
    return s.str();
  };
  std::ostringstream s;
  s.precision(17);
  s << "global_settings { assumed_gamma 1.0 max_trace_level 8 }\n";
  // POV-Ray puts pixel (i, j)'s centre where OpenCV does: small bright spheres seen directly and
  // in the mirror have their centroids within 0.08 px of the project's projection (0.01 px on
  // average). OpenCV's marker corners lie 0.3-0.4 px low on these frames: the mirror bends the
  // sides, which OpenCV takes as straight (RefineMarkerCorners).
  s << "camera { perspective location <0, 0, 0> direction <0, 0, 1> right <" << k.width / k.fx
    << ", 0, 0> up <0, " << k.height / k.fy << ", 0> }\n";
  s << "background { rgb " << (idMask ? 0.0 : 0.75) << " }\n";
  s << mirror;
  const int cells = catar::MarkerCells(board.dictionary);
  if (floor)
  {
    // The floor, world z = 0, seen from above.
    const catar::Vec3 up = R * catar::Vec3(0, 0, 1);
    const catar::Vec3 floorPoint = R * catar::Vec3(0, 0, 0) + t;
    const double d = up.x() * floorPoint.x() + up.y() * floorPoint.y() + up.z() * floorPoint.z();
    s << "plane { " << povDirection(catar::Vec3(0, 0, 1)) << ", " << d << " pigment { rgb "
      << (idMask ? 0.0 : 0.45) << " } finish { ambient 1 diffuse 0 } }\n";
  }
  else if (!board.markers.empty())
  {
    // The plate: the markers' extent (white margins included) and one marker's side more, 1 mm
    // under them (the board's z = 0 plane).
    double lo[2] = { 1e30, 1e30 }, hi[2] = { -1e30, -1e30 };
    for (const catar::BoardMarker& m : board.markers)
    {
      for (const catar::Vec3& c : m.Corners())
      {
        for (int a = 0; a < 2; ++a)
        {
          lo[a] = std::min(lo[a], c[a] - 0.5 * m.size);
          hi[a] = std::max(hi[a], c[a] + 0.5 * m.size);
        }
      }
    }
    s << "mesh2 { vertex_vectors { 4, " << pov(catar::Vec3(lo[0], lo[1], -0.001)) << ", "
      << pov(catar::Vec3(hi[0], lo[1], -0.001)) << ", " << pov(catar::Vec3(hi[0], hi[1], -0.001))
      << ", " << pov(catar::Vec3(lo[0], hi[1], -0.001))
      << " } face_indices { 2, <0, 1, 2>, <0, 2, 3> } pigment { rgb " << (idMask ? 0.0 : 0.8)
      << " } finish { ambient 1 diffuse 0 } }\n";
  }
  for (const catar::BoardMarker& m : board.markers)
  {
    // The printed square with its white margin of one cell: the black square's corners pushed
    // out by (cells + 2) / cells about the centre.
    const auto corners = m.Corners();
    const double grow = (cells + 2.0) / cells;
    std::string v[4];
    for (int i = 0; i < 4; ++i)
    {
      v[i] = pov(m.translate + grow * (corners[i] - m.translate));
    }
    std::string texture;
    if (idMask)
    {
      texture = "pigment { rgb <" + std::to_string((m.id + 1) / 255.0) + ", 0, 0> }";
    }
    else
    {
      std::vector<std::uint8_t> grey;
      const int side = 40 * (cells + 2);
      if (!catar::MarkerImage(board.dictionary, m.id, side, 1, grey, error))
      {
        return false;
      }
      const std::string file = dir + "/marker-" + std::to_string(m.id) + ".png";
      cv::imwrite(file, cv::Mat(side, side, CV_8UC1, grey.data()));
      texture = "uv_mapping pigment { image_map { png \"" + file + "\" interpolate 2 } }";
    }
    // Corners TL, TR, BR, BL of the printed marker; the image's (0, 0) is its bottom left.
    s << "mesh2 { vertex_vectors { 4, " << v[0] << ", " << v[1] << ", " << v[2] << ", " << v[3]
      << " } uv_vectors { 4, <0, 1>, <1, 1>, <1, 0>, <0, 0> } face_indices { 2, <0, 1, 2>, "
         "<0, 2, 3> } uv_indices { 2, <0, 1, 2>, <0, 2, 3> } texture { "
      << texture << " finish { ambient 1 diffuse 0 } } }\n";
  }
  return RunPovRay(dir, name, s.str(), k.width, k.height, !idMask, png, error);
}
} // namespace catar_independent

#endif
