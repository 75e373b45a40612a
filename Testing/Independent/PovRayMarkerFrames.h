// Frames of marker boards seen in a mirror sphere, rendered by POV-Ray: an independent ray
// tracer, with its own anti-aliasing and texture filtering, for checks of what reads images
// (marker detection, pose) against a renderer the project did not write.
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

#include <opencv2/imgcodecs.hpp>

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

/// Renders the board seen through `camera` (a sphere mirror, no distortion, the principal point
/// at the image centre) into dir/NAME.png: anti-aliased (POV-Ray's adaptive sampling, 3 levels)
/// or, with idMask, the id mask. False with a sentence in `error`.
inline bool RenderMarkerFrame(const std::string& dir, const std::string& name,
  const catar::CameraModel& camera, const catar::MarkerBoard& board, bool idMask, std::string& png,
  std::string& error)
{
  const catar::Intrinsics& k = camera.intrinsics;
  // The sphere's description: centre x, y, z and radius, camera frame.
  const std::vector<double>& mirror = camera.mirror.parameters;
  if (camera.mirror.type != "sphere" || mirror.size() != 4 ||
    std::abs(k.cx - 0.5 * (k.width - 1)) > 1e-9 || std::abs(k.cy - 0.5 * (k.height - 1)) > 1e-9 ||
    k.skew != 0.0 || !camera.distortion.IsZero())
  {
    error = "POV-Ray frames need a sphere mirror, a centred principal point and no distortion";
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
  s << "sphere { <" << mirror[0] << ", " << -mirror[1] << ", " << mirror[2] << ">, " << mirror[3]
    << " pigment { rgb 0 } finish { ambient 0 diffuse 0 reflection 1 } }\n";
  // The floor, world z = 0, seen from above.
  const catar::Vec3 up = R * catar::Vec3(0, 0, 1);
  const catar::Vec3 floorPoint = R * catar::Vec3(0, 0, 0) + t;
  const double d = up.x() * floorPoint.x() + up.y() * floorPoint.y() + up.z() * floorPoint.z();
  s << "plane { " << povDirection(catar::Vec3(0, 0, 1)) << ", " << d << " pigment { rgb "
    << (idMask ? 0.0 : 0.45) << " } finish { ambient 1 diffuse 0 } }\n";
  const int cells = catar::MarkerCells(board.dictionary);
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
