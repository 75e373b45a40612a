// The rig's calibration on frames rendered by POV-Ray (as TestRigCalibrationPovRay): a 4 x 4
// marker board seen in a mirror sphere, an off-focus tilted hyperboloid and an off-axis
// paraboloid, 10 views each (anti-aliased; then with a blur of 1 px and noise of sigma 3 grey
// levels), calibrated from a start 3 mm, 2 degrees and 5 % off. Per rig: the views and corners
// used, the RMS, how far the calibrated mirror is from the true one, and the time of the whole
// calibration from the images (markers found, three solves with the corners put on the edges
// between them) and of one solve on its final corners. Prints a table; asserts nothing.
//   BenchmarkCalibrationPovRay [--quick] [--repeat N] [--pictures DIR]
// --pictures writes, for each rig, a view with the corners found (green) and each corner's
// residual through the calibrated rig drawn 200 times longer (red).
#include "CalibrationTestViews.h"
#include "MarkerFrameScenes.h"
#include "Mirror.h"
#include "PovRayMarkerFrames.h"
#include "Projector.h"
#include "RigCalibration.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <tuple>
#include <vector>

#include <unistd.h>

namespace
{
using namespace catar;
using namespace catar_independent;
using Clock = std::chrono::steady_clock;

double Milliseconds(Clock::time_point a, Clock::time_point b)
{
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// The used view `k` of the calibration with its corners (green) and their residuals x200 (red):
// the region around the corners, cropped.
void Picture(const std::string& file, const cv::Mat& bgr, const CalibrationResult& r, std::size_t k)
{
  cv::Mat out = bgr.clone();
  cv::Rect box;
  for (const auto& c : r.residuals[k])
  {
    const cv::Point2d at(c.first.x(), c.first.y());
    const cv::Point2d tip = at + 200.0 * cv::Point2d(c.second.x(), c.second.y());
    cv::line(out, at, tip, cv::Scalar(0, 0, 230), 2, cv::LINE_AA);
    cv::circle(out, at, 3, cv::Scalar(0, 170, 0), -1, cv::LINE_AA);
    const cv::Rect around(static_cast<int>(at.x) - 60, static_cast<int>(at.y) - 60, 120, 120);
    box = box.area() == 0 ? around : (box | around);
  }
  box &= cv::Rect(0, 0, out.cols, out.rows);
  cv::imwrite(file, box.area() > 0 ? out(box) : out);
}
} // namespace

int main(int argc, char** argv)
{
  bool quick = false;
  int repeat = 3;
  std::string pictures;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--quick")
    {
      quick = true;
      repeat = 1;
    }
    else if (a == "--repeat" && i + 1 < argc)
    {
      repeat = std::max(1, std::atoi(argv[++i]));
    }
    else if (a == "--pictures" && i + 1 < argc)
    {
      pictures = argv[++i];
    }
    else
    {
      std::fprintf(
        stderr, "usage: BenchmarkCalibrationPovRay [--quick] [--repeat N] [--pictures DIR]\n");
      return 2;
    }
  }
  if (!HavePovRay())
  {
    std::printf("povray is not installed: skipped\n");
    return 77;
  }
  char folder[] = "/tmp/catar-calibration-bench-XXXXXX";
  const std::string dir = mkdtemp(folder);
  const MarkerBoard board = catar_test::CalibrationBoard(0.05, 0.065, 4);
  std::vector<std::tuple<std::string, CameraModel, double>> rigs = {
    { "sphere", catar_test::DemoCameraModel(), 0.2 },
    { "tilted hyperboloid", catar_test::OffFocusHyperboloidCameraModel(), 0.25 },
    { "off-axis paraboloid", catar_test::OffAxisParaboloidCameraModel(), 0.25 },
  };
  if (quick)
  {
    rigs.resize(1);
  }
  std::printf("%-20s %-6s %5s %7s %8s %9s %9s %8s %10s %9s\n", "rig", "frames", "views", "corners",
    "rms px", "off mm", "off deg", "shape %", "images ms", "solve ms");
  for (const auto& rig : rigs)
  {
    const std::string& name = std::get<0>(rig);
    const CameraModel& truth = std::get<1>(rig);
    std::string error;
    const auto mirror = MakeMirror(truth.mirror, error);
    const std::vector<Mat4> poses =
      catar_test::BoardPosesAround(mirror->Viewpoint(), 10, std::get<2>(rig));
    std::vector<cv::Mat> clean, noisy;
    for (std::size_t v = 0; v < poses.size(); ++v)
    {
      CameraModel posed = truth;
      posed.worldToCamera = poses[v];
      std::string png;
      if (!RenderMarkerFrame(
            dir, "view-" + std::to_string(v), posed, board, false, png, error, false))
      {
        std::fprintf(stderr, "%s\n", error.c_str());
        return 1;
      }
      clean.push_back(cv::imread(png, cv::IMREAD_COLOR));
      noisy.push_back(LensBlurAndNoise(clean.back(), 1.0, 3.0, 11 + v));
    }
    CameraModel start = truth;
    start.mirror = catar_test::MirrorStartOff(truth.mirror, 0.003, 2.0, 0.05);
    for (const bool blurred : { false, true })
    {
      const std::vector<cv::Mat>& frames = blurred ? noisy : clean;
      std::vector<std::vector<std::uint8_t>> rgba;
      std::vector<CalibrationImage> images;
      rgba.reserve(frames.size());
      images.reserve(frames.size());
      for (const cv::Mat& f : frames)
      {
        rgba.push_back(RgbaPixels(f));
      }
      for (std::size_t i = 0; i < frames.size(); ++i)
      {
        images.push_back(
          { "view " + std::to_string(i), frames[i].cols, frames[i].rows, rgba[i].data() });
      }
      CalibrationResult r;
      std::vector<CalibrationView> views;
      double imagesMs = 1e30, solveMs = 1e30;
      for (int k = 0; k < repeat; ++k)
      {
        const auto t0 = Clock::now();
        r = CalibrateRigFromImages(start, board, images, {}, &views);
        const auto t1 = Clock::now();
        CalibrateRig(start, views);
        const auto t2 = Clock::now();
        imagesMs = std::min(imagesMs, Milliseconds(t0, t1));
        solveMs = std::min(solveMs, Milliseconds(t1, t2));
      }
      if (!r.ok)
      {
        std::printf("%-20s %-6s no calibration: %s\n", name.c_str(), blurred ? "noisy" : "clean",
          r.error.c_str());
        continue;
      }
      int corners = 0;
      for (const auto& list : r.residuals)
      {
        corners += static_cast<int>(list.size());
      }
      double metres = 0, degrees = 0, shape = 0;
      catar_test::MirrorDifference(truth.mirror, r.camera.mirror, metres, degrees, shape);
      std::printf("%-20s %-6s %5d %7d %8.3f %9.3f %9.4f %8.3f %10.0f %9.0f\n", name.c_str(),
        blurred ? "noisy" : "clean", r.imagesUsed, corners, r.rmsPixels, 1000.0 * metres, degrees,
        100.0 * shape, imagesMs, solveMs);
      if (!pictures.empty() && !blurred && !r.usedViews.empty())
      {
        std::string file = name;
        std::replace(file.begin(), file.end(), ' ', '-');
        const std::size_t k = std::min<std::size_t>(2, r.usedViews.size() - 1);
        Picture(pictures + "/calibration-" + file + ".png",
          frames[static_cast<std::size_t>(r.usedViews[k])], r, k);
      }
    }
  }
  const std::string remove = "rm -rf '" + dir + "'";
  return std::system(remove.c_str()) == 0 ? 0 : 1;
}
