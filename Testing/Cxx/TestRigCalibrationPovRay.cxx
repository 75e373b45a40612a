// The rig's calibration on frames an independent ray tracer made: a marker board seen in a mirror
// sphere, a tilted hyperboloid and an off-axis paraboloid, ten views each, rendered by POV-Ray
// (anti-aliased), clean and with a real lens's blur and noise; the markers found and calibrated by
// CalibrateRigFromImages from a start 3 mm, 2 degrees and 5 % off; wrong boards and empty images
// refused; and the program on the same frames. Skipped where povray is not installed.
#include "CalibrationIO.h"
#include "CalibrationTestViews.h"
#include "MarkerFrameScenes.h"
#include "Mirror.h"
#include "PovRayMarkerFrames.h"
#include "Projector.h"
#include "RigCalibration.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

using namespace catar;
using namespace catar_independent;

namespace
{
constexpr int kViews = 10;

struct RigFrames
{
  std::string name;
  CameraModel rig;
  std::vector<cv::Mat> clean; // BGR
  std::vector<cv::Mat> noisy;
  std::vector<std::string> files; // the clean frames on disk (for the program)
  double distance = 0.2;          // of the board from the mirror's viewpoint, metres
};

// The board's markers: 4 x 4 of 5 cm, 6.5 cm apart.
MarkerBoard Board()
{
  return catar_test::CalibrationBoard(0.05, 0.065, 4);
}

std::vector<CalibrationImage> Images(
  const std::vector<cv::Mat>& bgr, std::vector<std::vector<std::uint8_t>>& storage)
{
  storage.clear();
  std::vector<CalibrationImage> images;
  for (std::size_t i = 0; i < bgr.size(); ++i)
  {
    storage.push_back(RgbaPixels(bgr[i]));
  }
  for (std::size_t i = 0; i < bgr.size(); ++i)
  {
    images.push_back({ "view " + std::to_string(i), bgr[i].cols, bgr[i].rows, storage[i].data() });
  }
  return images;
}

class RigCalibrationPovRay : public ::testing::Test
{
protected:
  static void SetUpTestSuite()
  {
    if (!HavePovRay())
    {
      return;
    }
    char folder[] = "/tmp/catar-calibration-XXXXXX";
    dir = mkdtemp(folder);
    // Each rig with the board at a distance where its markers show 30-80 px across.
    const std::tuple<std::string, CameraModel, double> rigs[] = {
      { "sphere", catar_test::DemoCameraModel(), 0.2 },
      { "tilted hyperboloid", catar_test::OffFocusHyperboloidCameraModel(), 0.25 },
      { "off-axis paraboloid", catar_test::OffAxisParaboloidCameraModel(), 0.25 },
    };
    frames = std::make_unique<std::vector<RigFrames>>();
    for (const auto& r : rigs)
    {
      RigFrames f{ std::get<0>(r), std::get<1>(r), {}, {}, {}, std::get<2>(r) };
      std::string error;
      const auto mirror = MakeMirror(f.rig.mirror, error);
      const std::vector<Mat4> poses =
        catar_test::BoardPosesAround(mirror->Viewpoint(), kViews, f.distance);
      for (int v = 0; v < kViews; ++v)
      {
        CameraModel posed = f.rig;
        posed.worldToCamera = poses[static_cast<std::size_t>(v)];
        std::string name = f.name + "-" + std::to_string(v);
        for (char& c : name)
        {
          c = c == ' ' ? '-' : c;
        }
        std::string png;
        ASSERT_TRUE(RenderMarkerFrame(dir, name, posed, Board(), false, png, error, false))
          << error;
        const cv::Mat clean = cv::imread(png, cv::IMREAD_COLOR);
        f.clean.push_back(clean);
        f.noisy.push_back(LensBlurAndNoise(clean, 1.0, 3.0, 11 + v));
        f.files.push_back(png);
      }
      frames->push_back(f);
    }
  }

  static void TearDownTestSuite()
  {
    frames.reset();
    if (!dir.empty() && std::getenv("CATAR_KEEP_FRAMES") == nullptr)
    {
      const std::string remove = "rm -rf '" + dir + "'";
      EXPECT_EQ(std::system(remove.c_str()), 0);
    }
  }

  void SetUp() override
  {
    if (!HavePovRay())
    {
      GTEST_SKIP() << "povray is not installed";
    }
  }

  static std::unique_ptr<std::vector<RigFrames>> frames;
  static std::string dir;
};
std::unique_ptr<std::vector<RigFrames>> RigCalibrationPovRay::frames;
std::string RigCalibrationPovRay::dir;
} // namespace

TEST_F(RigCalibrationPovRay, FindsEachMirrorFromAStartOff)
{
  for (const RigFrames& f : *frames)
  {
    for (const bool noisy : { false, true })
    {
      SCOPED_TRACE(f.name + (noisy ? ", blur 1 px and noise 3" : ", clean"));
      std::vector<std::vector<std::uint8_t>> storage;
      const std::vector<CalibrationImage> images = Images(noisy ? f.noisy : f.clean, storage);
      CameraModel start = f.rig;
      start.worldToCamera = Mat4::Identity();
      start.mirror = catar_test::MirrorStartOff(f.rig.mirror, 0.003, 2.0, 0.05);
      const CalibrationResult r = CalibrateRigFromImages(start, Board(), images);
      ASSERT_TRUE(r.ok) << r.error;
      double metres = 0, degrees = 0, shape = 0;
      catar_test::MirrorDifference(f.rig.mirror, r.camera.mirror, metres, degrees, shape);
      std::printf("%s %s: %d views, rms %.3f px, mirror off by %.3f mm, %.4f deg, shape %.3f %%\n",
        f.name.c_str(), noisy ? "noisy" : "clean", r.imagesUsed, r.rmsPixels, 1000.0 * metres,
        degrees, 100.0 * shape);
      for (const CalibratedNumber& n : r.mirror)
      {
        std::printf("  %s %.6g +- %.2g %s\n", n.name.c_str(), n.value, n.sigma, n.unit.c_str());
      }
      EXPECT_GE(r.imagesUsed, 8);
      if (!noisy)
      {
        // Anti-aliased frames: the mirror within 0.3 mm, 0.15 degrees and 0.5 %.
        EXPECT_LE(r.rmsPixels, 0.6);
        EXPECT_LE(metres, 0.0003);
        EXPECT_LE(degrees, 0.15);
        EXPECT_LE(shape, 0.005);
        continue;
      }
      // A real lens's blur and noise: the errors within four of the reported standard deviations
      // (Documentation/calibrate-your-rig.md gives the numbers).
      EXPECT_LE(r.rmsPixels, 1.2);
      double position = 0.0, tilt = 0.0, size = 0.0;
      catar_test::MirrorSigmas(r.mirror, position, tilt, size);
      EXPECT_LE(metres, 4.0 * position);
      EXPECT_LE(degrees, std::max(0.15, 4.0 * tilt));
      EXPECT_LE(shape, 4.0 * size);
    }
  }
}

TEST_F(RigCalibrationPovRay, WrongBoardsAndEmptyImagesAreRefused)
{
  const RigFrames& f = frames->front(); // the sphere
  std::vector<std::vector<std::uint8_t>> storage;
  const std::vector<CalibrationImage> images = Images(f.clean, storage);
  CameraModel start = f.rig;
  start.worldToCamera = Mat4::Identity();
  start.mirror = catar_test::MirrorStartOff(f.rig.mirror, 0.003, 2.0, 0.05);
  // The board's file says 10 % too small or too large a marker: the mirror would scale with it.
  for (const double factor : { 0.9, 1.1 })
  {
    const CalibrationResult r =
      CalibrateRigFromImages(start, ResizedBoard(Board(), factor), images);
    EXPECT_FALSE(r.ok) << factor;
    EXPECT_NE(r.error.find("the board does not fit"), std::string::npos) << r.error;
  }
  // Another board's layout: the markers 20 % further apart.
  const CalibrationResult spread =
    CalibrateRigFromImages(start, catar_test::CalibrationBoard(0.05, 0.078, 4), images);
  EXPECT_FALSE(spread.ok);
  EXPECT_NE(spread.error.find("does not fit"), std::string::npos) << spread.error;
  // Empty images (a uniform grey, the lens cap's black): no markers, too few views.
  const cv::Mat grey(f.clean[0].size(), CV_8UC3, cv::Scalar(128, 128, 128));
  const cv::Mat black(f.clean[0].size(), CV_8UC3, cv::Scalar(0, 0, 0));
  const std::vector<cv::Mat> empty = { grey, black, grey, black };
  const CalibrationResult none = CalibrateRigFromImages(start, Board(), Images(empty, storage));
  EXPECT_FALSE(none.ok);
  EXPECT_NE(none.error.find("too few views: 0 of 4"), std::string::npos) << none.error;
  EXPECT_NE(none.error.find("no marker of the board found"), std::string::npos) << none.error;
  // An image of another size than the calibration's.
  cv::Mat small;
  cv::resize(f.clean[0], small, cv::Size(), 0.5, 0.5);
  const CalibrationResult sized =
    CalibrateRigFromImages(start, Board(), Images({ small }, storage));
  EXPECT_FALSE(sized.ok);
  EXPECT_NE(
    sized.error.find("664 x 524 pixels but the calibration is for 1328 x 1048"), std::string::npos)
    << sized.error;
}

namespace
{
std::string BoardYaml(const MarkerBoard& board)
{
  std::ostringstream s;
  s.precision(17);
  s << "dictionary: " << board.dictionary << "\nmarkers:\n";
  for (const BoardMarker& m : board.markers)
  {
    s << "  - { id: " << m.id << ", translate: [" << m.translate.x() << ", " << m.translate.y()
      << ", " << m.translate.z() << "], size: " << m.size << " }\n";
  }
  return s.str();
}

int RunProgram(const std::string& arguments, std::string& out)
{
  const std::string command = std::string(CATAR_CALIBRATE_PROGRAM) + " " + arguments;
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe)
  {
    return -1;
  }
  char buffer[4096];
  out.clear();
  while (std::fgets(buffer, sizeof buffer, pipe))
  {
    out += buffer;
  }
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
} // namespace

TEST_F(RigCalibrationPovRay, TheProgramWritesTheCalibratedRig)
{
  const RigFrames& f = frames->front(); // the sphere
  CameraModel start = f.rig;
  start.worldToCamera = Mat4::Identity();
  start.mirror = catar_test::MirrorStartOff(f.rig.mirror, 0.003, 2.0, 0.05);
  const std::string init = dir + "/init.yaml";
  const std::string board = dir + "/board.yaml";
  const std::string rig = dir + "/rig.yaml";
  std::string error;
  ASSERT_TRUE(SaveCalibration(init, start, error)) << error;
  std::ofstream(board) << BoardYaml(Board());
  std::string images;
  for (const std::string& file : f.files)
  {
    images += " '" + file + "'";
  }
  std::string out;
  ASSERT_EQ(
    RunProgram("'" + init + "' '" + board + "'" + images + " -o '" + rig + "' --json", out), 0)
    << out;
  // One JSON object with the numbers the library found.
  EXPECT_EQ(out.find('\n'), out.size() - 1) << out;
  EXPECT_NE(out.find("\"rms_px\": "), std::string::npos) << out;
  EXPECT_NE(out.find("\"images_used\": 9"), std::string::npos) << out;
  EXPECT_NE(out.find("\"mirror\": {\"type\": \"sphere\", \"center\": ["), std::string::npos) << out;
  CameraModel written;
  ASSERT_TRUE(LoadCalibration(rig, written, error)) << error;
  double metres = 0, degrees = 0, shape = 0;
  catar_test::MirrorDifference(f.rig.mirror, written.mirror, metres, degrees, shape);
  EXPECT_LE(metres, 0.0003);
  EXPECT_LE(shape, 0.005);
  std::ifstream in(rig);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("calibration:"), std::string::npos) << text;
  EXPECT_NE(text.find("images_used: 9"), std::string::npos) << text;
  EXPECT_NE(text.find("radius:"), std::string::npos) << text;
  EXPECT_NE(text.find("sigma:"), std::string::npos) << text;
  // A wrong board: exit status 1, a sentence, no rig written.
  std::remove(rig.c_str());
  std::ofstream(board) << BoardYaml(ResizedBoard(Board(), 0.9));
  EXPECT_EQ(
    RunProgram("'" + init + "' '" + board + "'" + images + " -o '" + rig + "' 2>&1", out), 1);
  EXPECT_NE(
    out.find("catadioptric-calibrate: cannot calibrate: the board does not fit"), std::string::npos)
    << out;
  EXPECT_FALSE(std::ifstream(rig).good());
}
