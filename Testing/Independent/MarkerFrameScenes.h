// The marker scenes that the POV-Ray frames show (PovRayMarkerFrames.h), shared by the pose tests
// and the marker benchmark: the demo camera's rig, boards of 20 cm markers on the floor behind
// the camera, a real lens's blur and noise, and the error between two poses.
#ifndef catarMarkerFrameScenes_h
#define catarMarkerFrameScenes_h

#include "CameraModel.h"
#include "Markers.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <vector>

namespace catar_independent
{
/// The demo calibration's camera and mirror sphere (Data/calibration/demo-camera.yaml) with the
/// principal point at the image centre, which POV-Ray's camera needs.
inline catar::CameraModel DemoMarkerCamera()
{
  catar::CameraModel m;
  m.intrinsics = catar::Intrinsics{ 1000.0, 1000.0, 663.5, 523.5, 0.0, 1328, 1048 };
  m.mirror = catar::MirrorDescription("sphere", { 0.0, 0.0, 0.14, 0.05 });
  m.worldToCamera << 1, 0, 0, 0, 0, 0, -1, 1, 0, 1, 0, 0.14, 0, 0, 0, 1;
  return m;
}

/// Eight 20 cm markers (DICT_4X4_50, ids 0-7) on the floor behind the camera, 45 cm apart (as
/// TestMarkers' board), the whole board turned by `turn` degrees about the vertical through
/// (0, -0.5) and moved by (dx, dy); each marker also turned 10 degrees more than the last.
/// `count` 10 adds two more (ids 8, 9) 90 cm either side of the middle one.
inline catar::MarkerBoard EightMarkerBoard(double turn, double dx, double dy, int count = 8)
{
  catar::MarkerBoard board;
  const double xy[10][2] = { { -0.45, -0.5 }, { 0.0, -0.5 }, { 0.45, -0.5 }, { -0.45, -0.95 },
    { 0.0, -0.95 }, { 0.45, -0.95 }, { -0.45, -0.05 }, { 0.45, -0.05 }, { -0.9, -0.5 },
    { 0.9, -0.5 } };
  const double a = turn * 3.14159265358979323846 / 180.0;
  for (int k = 0; k < std::min(count, 10); ++k)
  {
    const double x = xy[k][0];
    const double y = xy[k][1] + 0.5;
    catar::BoardMarker m;
    m.id = k;
    m.translate = catar::Vec3(
      std::cos(a) * x - std::sin(a) * y + dx, std::sin(a) * x + std::cos(a) * y - 0.5 + dy, 0.002);
    m.size = 0.2;
    m.rotate = catar::Vec3(0, 0, 10.0 * k + turn);
    board.markers.push_back(m);
  }
  return board;
}

/// Two 20 cm markers side by side (centres `apart` metres apart along x) on the floor behind
/// the camera, at `y` metres.
inline catar::MarkerBoard MarkerPair(double apart, double y)
{
  catar::MarkerBoard board;
  for (int k = 0; k < 2; ++k)
  {
    catar::BoardMarker m;
    m.id = k;
    m.translate = catar::Vec3((k - 0.5) * apart, y, 0.002);
    m.size = 0.2;
    board.markers.push_back(m);
  }
  return board;
}

/// The board with every marker's size scaled (a board file whose size is wrong).
inline catar::MarkerBoard ResizedBoard(catar::MarkerBoard board, double factor)
{
  for (catar::BoardMarker& m : board.markers)
  {
    m.size *= factor;
  }
  return board;
}

/// A real lens's frame: Gaussian blur of `blur` px, then Gaussian noise of `noise` grey levels
/// (seeded).
inline cv::Mat LensBlurAndNoise(const cv::Mat& bgr, double blur, double noise, std::uint64_t seed)
{
  cv::Mat out;
  cv::GaussianBlur(bgr, out, cv::Size(0, 0), blur);
  cv::Mat grain(out.size(), CV_32FC3);
  cv::RNG rng(seed);
  rng.fill(grain, cv::RNG::NORMAL, 0.0, noise);
  out.convertTo(out, CV_32FC3);
  out += grain;
  out.convertTo(out, CV_8UC3);
  return out;
}

/// RGBA8 pixels of a BGR image (what DetectMarkers reads).
inline std::vector<std::uint8_t> RgbaPixels(const cv::Mat& bgr)
{
  cv::Mat rgba;
  cv::cvtColor(bgr, rgba, cv::COLOR_BGR2RGBA);
  return std::vector<std::uint8_t>(rgba.data, rgba.data + rgba.total() * 4);
}

/// The shorter side (pixels) of each marker's image in an id mask (PovRayMarkerFrames.h: red
/// k + 1 for marker k), from the smallest rectangle around its pixels.
inline std::map<int, double> VisibleSizes(const cv::Mat& mask)
{
  std::map<int, std::vector<cv::Point>> pixels;
  for (int y = 0; y < mask.rows; ++y)
  {
    for (int x = 0; x < mask.cols; ++x)
    {
      const int red = mask.at<cv::Vec3b>(y, x)[2];
      if (red > 0)
      {
        pixels[red - 1].emplace_back(x, y);
      }
    }
  }
  std::map<int, double> sizes;
  for (const auto& p : pixels)
  {
    if (p.second.size() >= 3)
    {
      const cv::RotatedRect box = cv::minAreaRect(p.second);
      sizes[p.first] = std::min(box.size.width, box.size.height);
    }
  }
  return sizes;
}

/// Camera centre distance (mm) and rotation angle (degrees) between two world-to-camera poses.
inline void PoseError(const catar::Mat4& a, const catar::Mat4& b, double& mm, double& degrees)
{
  const catar::Mat3 ra = a.topLeftCorner<3, 3>();
  const catar::Mat3 rb = b.topLeftCorner<3, 3>();
  const catar::Vec3 ca = -ra.transpose() * a.topRightCorner<3, 1>();
  const catar::Vec3 cb = -rb.transpose() * b.topRightCorner<3, 1>();
  mm = 1000.0 * (ca - cb).norm();
  const double c = std::max(-1.0, std::min(1.0, 0.5 * ((ra * rb.transpose()).trace() - 1.0)));
  degrees = std::acos(c) * 180.0 / 3.14159265358979323846;
}
} // namespace catar_independent

#endif
