// The mirror from its outline (DetectMirrorOutline + SphereFromOutline) on frames rendered by
// POV-Ray (Testing/Independent/PovRayOutlineFrames.h): a mirror sphere of reflectance 0.7 in a
// room before a bright (0.9) or dark (0.1) backdrop, the demo's 5 cm sphere 14 cm ahead, at
// 1328x1048, 2656x2096 and 4096x3232 pixels (the focal length scaled with the size), clean and
// with 1 px blur and noise sigma 6. Per frame: the centre's error against the one POV-Ray was
// given, the outline points and their RMS distance from the fitted outline, the detection time
// (median of three) and the process's peak memory so far (sizes run from small to large, so the
// peak is the largest frame's). With CATAR_SHARED_DATA's mirror-balls/room.jpg (4096x4096, a real
// photograph, no intrinsics known: f = 4 x width assumed), its time and peak too. Prints a table;
// asserts nothing.
//   BenchmarkOutlinePovRay [--quick] [--keep DIR]
#include "MarkerFrameScenes.h"
#include "MirrorOutline.h"
#include "PovRayOutlineFrames.h"

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

namespace
{
using namespace catar_independent;

// The process's peak resident memory (MB), from /proc/self/status.
double PeakMegabytes()
{
  std::ifstream status("/proc/self/status");
  std::string line;
  while (std::getline(status, line))
  {
    if (line.rfind("VmHWM:", 0) == 0)
    {
      return std::atof(line.c_str() + 6) / 1024.0;
    }
  }
  return 0.0;
}

struct Timed
{
  bool found = false;
  std::string error;
  catar::Vec3 centre = catar::Vec3::Zero();
  catar::SphereOutlineReport report;
  double ms = 0.0;
};

Timed Measure(const catar::CameraModel& camera, double radius, const cv::Mat& bgr)
{
  const std::vector<std::uint8_t> rgba = RgbaPixels(bgr);
  std::vector<double> times;
  Timed t;
  for (int round = 0; round < 3; ++round)
  {
    std::vector<catar::Vec2> outline;
    const auto start = std::chrono::steady_clock::now();
    t.found = catar::DetectMirrorOutline(camera, bgr.cols, bgr.rows, rgba.data(), outline, t.error);
    times.push_back(
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    t.found =
      t.found && catar::SphereFromOutline(camera, radius, outline, t.centre, t.report, t.error);
  }
  std::sort(times.begin(), times.end());
  t.ms = times[1];
  return t;
}
} // namespace

int main(int argc, char** argv)
{
  bool quick = false;
  std::string keep;
  for (int i = 1; i < argc; ++i)
  {
    const std::string a = argv[i];
    if (a == "--quick")
    {
      quick = true;
    }
    else if (a == "--keep" && i + 1 < argc)
    {
      keep = argv[++i];
    }
    else
    {
      std::fprintf(stderr, "usage: BenchmarkOutlinePovRay [--quick] [--keep DIR]\n");
      return 2;
    }
  }
  if (!HavePovRay())
  {
    std::printf("povray is not installed: skipped\n");
    return 77;
  }
  std::string dir = keep;
  if (dir.empty())
  {
    char folder[] = "/tmp/catar-outline-bench-XXXXXX";
    dir = mkdtemp(folder);
  }
  std::printf("%-11s %-7s %-6s %10s %8s %7s %9s %9s %9s\n", "size", "backdrop", "frame", "error mm",
    "error %", "points", "rms px", "ms", "peak MB");
  const std::vector<int> scales = quick ? std::vector<int>{ 1 } : std::vector<int>{ 1, 2, 3 };
  for (const int s : scales)
  {
    // 1, 2 and about 3.08 times the demo frame (4096 wide).
    const double factor = s == 3 ? 4096.0 / 1328.0 : s;
    OutlineScene scene;
    const int width = static_cast<int>(std::lround(1328 * factor));
    const int height = static_cast<int>(std::lround(1048 * factor));
    scene.intrinsics = catar::Intrinsics{ 1000.0 * factor, 1000.0 * factor, 0.5 * (width - 1),
      0.5 * (height - 1), 0.0, width, height };
    for (const double backdrop : { 0.9, 0.1 })
    {
      if (quick && backdrop < 0.5)
      {
        continue;
      }
      scene.backdrop = backdrop;
      const std::string name =
        "outline-" + std::to_string(width) + (backdrop > 0.5 ? "-bright" : "-dark");
      std::string png, error;
      if (!RenderOutlineFrame(dir, name, scene, png, error))
      {
        std::fprintf(stderr, "%s\n", error.c_str());
        return 1;
      }
      const cv::Mat clean = cv::imread(png, cv::IMREAD_COLOR);
      catar::CameraModel camera;
      camera.intrinsics = scene.intrinsics;
      for (const bool noisy : { false, true })
      {
        const cv::Mat frame = noisy ? LensBlurAndNoise(clean, 1.0, 6.0, 11) : clean;
        const Timed t = Measure(camera, scene.radius, frame);
        const std::string size = std::to_string(width) + "x" + std::to_string(height);
        if (!t.found)
        {
          std::printf("%-11s %-8s %-6s refused: %s\n", size.c_str(),
            backdrop > 0.5 ? "bright" : "dark", noisy ? "noisy" : "clean", t.error.c_str());
          continue;
        }
        const double mm = 1e3 * (t.centre - scene.centre).norm();
        std::printf("%-11s %-8s %-6s %10.4f %8.4f %7d %9.3f %9.0f %9.0f\n", size.c_str(),
          backdrop > 0.5 ? "bright" : "dark", noisy ? "noisy" : "clean", mm,
          0.1 * mm / scene.centre.norm(), t.report.pointCount, t.report.rmsPixels, t.ms,
          PeakMegabytes());
      }
    }
  }
  // A real photograph, where the shared data is.
  const char* shared = std::getenv("CATAR_SHARED_DATA");
  const std::string photo = std::string(shared ? shared : "") + "/mirror-balls/room.jpg";
  const cv::Mat room = shared && !quick ? cv::imread(photo, cv::IMREAD_COLOR) : cv::Mat();
  if (!room.empty())
  {
    catar::CameraModel camera;
    camera.intrinsics = catar::Intrinsics{ 4.0 * room.cols, 4.0 * room.cols, 0.5 * (room.cols - 1),
      0.5 * (room.rows - 1), 0.0, room.cols, room.rows };
    const Timed t = Measure(camera, 0.1, room);
    std::printf("room.jpg (%dx%d, real photograph): %s, %d points, rms %.3f px, %.0f ms, peak "
                "%.0f MB\n",
      room.cols, room.rows, t.found ? "found" : t.error.c_str(), t.report.pointCount,
      t.report.rmsPixels, t.ms, PeakMegabytes());
  }
  return 0;
}
