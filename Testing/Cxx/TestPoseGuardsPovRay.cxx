// The pose guards (PoseResult::reliable, PoseOptions) on frames the project did not render:
// POV-Ray's anti-aliased images of marker boards seen in the demo camera's mirror sphere
// (Testing/Independent), clean and with a real lens's blur (1 px) and noise (sigma 6). The truth
// is the pose POV-Ray was given. What must hold:
// - the whole board: found reliable, within 2 mm and 0.1 degrees clean, 4 mm and 0.2 degrees
//   noisy (the issue asks 5 mm and 0.2 degrees, 10 mm), and within three of its reported sigmas;
// - no pose reported reliable that is more than 2 cm or 1 degree off, whatever part of the
//   markers it comes from (each marker alone, every pair, two markers side by side) or whatever
//   wrong board it is given (marker sizes 0.8 to 1.25 times the true ones);
// - one marker alone is flagged, with a warning that says so; so are two markers side by side
//   and a board 10 % to 25 % off in size;
// - the corners lie on the markers' edges: no bias inwards or outwards, and within 0.2 px (clean)
//   or 0.4 px (noisy) of the exact projection of the board's corners, RMS;
// - every marker of 20 px or more on its shorter side (POV-Ray's id mask says which) is found.
// Skipped where povray is not installed.
#include "MarkerFrameScenes.h"
#include "MarkerPoseTracker.h"
#include "Markers.h"
#include "PovRayMarkerFrames.h"
#include "Projector.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

using namespace catar_independent;

namespace
{
struct Frame
{
  std::string name;
  catar::MarkerBoard board;
  std::vector<catar::MarkerDetection> found;
  cv::Mat image;                      // BGR
  std::map<int, double> visibleSizes; // from POV-Ray's id mask
};

// The frames, rendered once for all tests: two views of the eight-marker board and one of two
// markers side by side, each clean and noisy.
class PoseGuards : public ::testing::Test
{
protected:
  static void SetUpTestSuite()
  {
    if (!HavePovRay())
    {
      return;
    }
    char folder[] = "/tmp/catar-guards-XXXXXX";
    const std::string dir = mkdtemp(folder);
    const catar::CameraModel camera = DemoMarkerCamera();
    const std::pair<std::string, catar::MarkerBoard> scenes[] = {
      { "board-a", EightMarkerBoard(0.0, 0.0, 0.0) },
      { "board-b", EightMarkerBoard(39.0, 0.09, -0.06) }, { "pair", MarkerPair(0.22, -0.45) }
    };
    frames = std::make_unique<std::vector<Frame>>();
    for (const auto& scene : scenes)
    {
      std::string png;
      std::string error;
      ASSERT_TRUE(RenderMarkerFrame(dir, scene.first, camera, scene.second, false, png, error))
        << error;
      std::string mask;
      ASSERT_TRUE(
        RenderMarkerFrame(dir, scene.first + "-ids", camera, scene.second, true, mask, error))
        << error;
      const std::map<int, double> sizes = VisibleSizes(cv::imread(mask, cv::IMREAD_COLOR));
      const cv::Mat clean = cv::imread(png, cv::IMREAD_COLOR);
      const cv::Mat noisy = LensBlurAndNoise(clean, 1.0, 6.0, 7);
      for (const auto& kind : { std::make_pair("clean", clean), std::make_pair("noisy", noisy) })
      {
        // The markers as the tracker finds them (OpenCV's detection, those undecoded read again
        // where the pose puts them, the corners placed on the edges): what a user's poses
        // come from.
        Frame f{ scene.first + " " + kind.first, scene.second, {}, kind.second, sizes };
        const std::vector<std::uint8_t> rgba = RgbaPixels(kind.second);
        catar::MarkerPoseTracker tracker(scene.second);
        f.found = tracker.Track(camera, clean.cols, clean.rows, rgba.data(), 0.0).detections;
        frames->push_back(f);
      }
    }
    const std::string remove = "rm -rf '" + dir + "'";
    EXPECT_EQ(std::system(remove.c_str()), 0);
  }

  static void TearDownTestSuite() { frames.reset(); }

  void SetUp() override
  {
    if (!HavePovRay())
    {
      GTEST_SKIP() << "povray is not installed";
    }
  }

  // Checks that a pose reported reliable is within 2 cm and 1 degree; true when it is reliable.
  static bool ReliableMeansRight(const catar::PoseResult& pose, const std::string& what)
  {
    if (!pose.ok || !pose.reliable)
    {
      return false;
    }
    double mm = 0.0;
    double degrees = 0.0;
    PoseError(pose.worldToCamera, DemoMarkerCamera().worldToCamera, mm, degrees);
    EXPECT_LE(mm, 20.0) << what << ": reported reliable, " << mm << " mm off";
    EXPECT_LE(degrees, 1.0) << what << ": reported reliable, " << degrees << " degrees off";
    return true;
  }

  static std::unique_ptr<std::vector<Frame>> frames;
};

std::unique_ptr<std::vector<Frame>> PoseGuards::frames;

TEST_F(PoseGuards, TheWholeBoardIsReliableAndWithinItsSigmas)
{
  const catar::CameraModel camera = DemoMarkerCamera();
  for (const Frame& f : *frames)
  {
    if (f.board.markers.size() != 8)
    {
      continue;
    }
    const bool noisy = f.name.find("noisy") != std::string::npos;
    ASSERT_GE(f.found.size(), 6U) << f.name;
    const catar::PoseResult pose = catar::PoseFromMarkers(camera, f.board, f.found);
    ASSERT_TRUE(pose.ok) << f.name << ": " << pose.error;
    EXPECT_TRUE(pose.reliable) << f.name << ": " << pose.warning;
    double mm = 0.0;
    double degrees = 0.0;
    PoseError(pose.worldToCamera, camera.worldToCamera, mm, degrees);
    std::cout << f.name << ": " << f.found.size() << " markers, " << mm << " mm, " << degrees
              << " deg off; one sigma " << 1000.0 * pose.uncertainty.positionSigma << " mm, "
              << pose.uncertainty.angleSigmaDegrees << " deg\n";
    EXPECT_LE(mm, noisy ? 4.0 : 2.0) << f.name;
    EXPECT_LE(degrees, noisy ? 0.2 : 0.1) << f.name;
    EXPECT_LE(mm, 3.0 * 1000.0 * pose.uncertainty.positionSigma) << f.name;
    EXPECT_LE(degrees, 3.0 * pose.uncertainty.angleSigmaDegrees) << f.name;
  }
}

// Every marker whose image is 20 px or more on its shorter side is found by the tracker (OpenCV's
// detection, then the markers read again where the pose puts them), and the pose with them is
// as accurate as the issue asks. Board b is the view where OpenCV alone misses marker 7 (35 px,
// foreshortened near the mirror's rim).
TEST_F(PoseGuards, EveryMarkerOf20PixelsIsFound)
{
  const catar::CameraModel camera = DemoMarkerCamera();
  for (const Frame& f : *frames)
  {
    if (f.board.markers.size() != 8)
    {
      continue;
    }
    catar::MarkerPoseTracker tracker(f.board);
    const std::vector<std::uint8_t> rgba = RgbaPixels(f.image);
    const catar::FramePose& pose =
      tracker.Track(camera, f.image.cols, f.image.rows, rgba.data(), 0.0);
    int visible = 0;
    for (const auto& size : f.visibleSizes)
    {
      if (size.second < 20.0)
      {
        continue;
      }
      ++visible;
      const bool found = std::any_of(pose.detections.begin(), pose.detections.end(),
        [&](const catar::MarkerDetection& d) { return d.id == size.first; });
      EXPECT_TRUE(found) << f.name << ": marker " << size.first << " (" << size.second
                         << " px on its shorter side) not found";
    }
    EXPECT_GE(visible, 7) << f.name;
    ASSERT_EQ(pose.verdict, catar::PoseVerdict::Reliable) << f.name << ": " << pose.note;
    double mm = 0.0;
    double degrees = 0.0;
    PoseError(pose.result.worldToCamera, camera.worldToCamera, mm, degrees);
    std::cout << f.name << ": " << pose.markersFound << " markers (" << pose.markersRecovered
              << " read again where the pose puts them), " << mm << " mm, " << degrees
              << " deg off\n";
    const bool noisy = f.name.find("noisy") != std::string::npos;
    EXPECT_LE(mm, noisy ? 4.0 : 2.0) << f.name;
    EXPECT_LE(degrees, noisy ? 0.2 : 0.1) << f.name;
  }
}

// The corners the tracker gives against the exact projection of the board's corners (the
// project's forward projection, which independent tracers and an outside toolbox match to
// 1e-10 px): their mean offset out of the marker (OpenCV's contour corners lie 0.6 px inside on
// these frames) and their RMS distance (0.7-0.8 px from OpenCV alone, clean).
TEST_F(PoseGuards, CornersLieOnTheEdges)
{
  const catar::CameraModel camera = DemoMarkerCamera();
  const catar::Projector projector(camera);
  for (const Frame& f : *frames)
  {
    // Not the pair: its markers' white margins overlap (2 cm apart), and OpenCV puts two corners
    // of one of them on the neighbour's side, 3-3.6 px off, too far to be moved (2 px at most).
    if (f.board.markers.size() != 8)
    {
      continue;
    }
    double outward = 0.0;
    double squares = 0.0;
    int n = 0;
    for (const catar::MarkerDetection& d : f.found)
    {
      const auto marker = std::find_if(f.board.markers.begin(), f.board.markers.end(),
        [&](const catar::BoardMarker& m) { return m.id == d.id; });
      ASSERT_NE(marker, f.board.markers.end()) << f.name << ": marker " << d.id;
      const auto corners = marker->Corners();
      catar::Vec2 truth[4];
      catar::Vec2 centre = catar::Vec2::Zero();
      for (int c = 0; c < 4; ++c)
      {
        truth[c] = projector.ProjectWorld(corners[static_cast<std::size_t>(c)]).pixel;
        centre += 0.25 * truth[c];
      }
      for (int c = 0; c < 4; ++c)
      {
        const catar::Vec2 offset = d.corners[static_cast<std::size_t>(c)] - truth[c];
        outward += offset.dot((truth[c] - centre).normalized());
        squares += offset.squaredNorm();
        ++n;
      }
    }
    ASSERT_GE(n, 8) << f.name;
    const bool noisy = f.name.find("noisy") != std::string::npos;
    std::cout << f.name << ": " << n << " corners, " << outward / n << " px outwards on average, "
              << std::sqrt(squares / n) << " px RMS\n";
    EXPECT_LE(std::abs(outward / n), noisy ? 0.2 : 0.1) << f.name;
    EXPECT_LE(std::sqrt(squares / n), noisy ? 0.4 : 0.2) << f.name;
  }
}

TEST_F(PoseGuards, OneMarkerAloneIsFlagged)
{
  const catar::CameraModel camera = DemoMarkerCamera();
  catar::PoseOptions allowed;
  allowed.allowSingleMarker = true;
  int tried = 0;
  for (const Frame& f : *frames)
  {
    for (const catar::MarkerDetection& d : f.found)
    {
      const catar::PoseResult pose = catar::PoseFromMarkers(camera, f.board, { d });
      if (!pose.ok)
      {
        continue;
      }
      ++tried;
      EXPECT_FALSE(pose.reliable) << f.name << ", marker " << d.id;
      EXPECT_NE(pose.warning.find("one marker"), std::string::npos) << pose.warning;
      // Allowed, the uncertainty alone must still keep a wrong pose out.
      ReliableMeansRight(catar::PoseFromMarkers(camera, f.board, { d }, allowed),
        f.name + ", marker " + std::to_string(d.id) + " alone, allowed");
    }
  }
  EXPECT_GE(tried, 20);
}

TEST_F(PoseGuards, NoPairOfMarkersGivesAWrongReliablePose)
{
  const catar::CameraModel camera = DemoMarkerCamera();
  int pairs = 0;
  for (const Frame& f : *frames)
  {
    for (std::size_t i = 0; i < f.found.size(); ++i)
    {
      for (std::size_t j = i + 1; j < f.found.size(); ++j)
      {
        ++pairs;
        const catar::PoseResult pose =
          catar::PoseFromMarkers(camera, f.board, { f.found[i], f.found[j] });
        const bool reliable = ReliableMeansRight(pose,
          f.name + ", markers " + std::to_string(f.found[i].id) + " and " +
            std::to_string(f.found[j].id));
        if (f.board.markers.size() == 2)
        {
          EXPECT_FALSE(reliable) << f.name << ": two markers side by side";
        }
      }
    }
  }
  EXPECT_GE(pairs, 60);
}

TEST_F(PoseGuards, AWrongBoardIsNotReliable)
{
  const catar::CameraModel camera = DemoMarkerCamera();
  for (const Frame& f : *frames)
  {
    if (f.board.markers.size() != 8)
    {
      continue;
    }
    for (const double factor : { 0.8, 0.9, 1.1, 1.25 })
    {
      const catar::PoseResult pose =
        catar::PoseFromMarkers(camera, ResizedBoard(f.board, factor), f.found);
      const std::string what = f.name + ", marker sizes x" + std::to_string(factor);
      // Off by 10 % the markers' corners no longer fit within their noise (rms 1.2-1.4 px),
      // which the uncertainty shows (one sigma 10-13 mm, over the bound of 8).
      EXPECT_FALSE(ReliableMeansRight(pose, what)) << what;
    }
  }
}
} // namespace
// Tracking: 10 cm markers (15-20 px with their margins) in frames with blur and noise, where
// OpenCV's search of the whole frame finds 3-6 of the 8. After a clean frame of the same view
// gives the pose, each noisy frame's markers are searched where that pose puts them (the
// undecoded quadrilaterals read again, and the region around each missing marker searched
// again, enlarged): every frame keeps a reliable pose. Searching the quadrilaterals alone (no
// region search) found 30 markers over six noisy frames and left two frames unreliable; with it,
// 35 and none.
TEST(PoseGuardsTracking, SmallMarkersAreSearchedWhereThePosePutsThem)
{
  if (!HavePovRay())
  {
    GTEST_SKIP() << "povray is not installed";
  }
  char folder[] = "/tmp/catar-small-XXXXXX";
  const std::string dir = mkdtemp(folder);
  const catar::CameraModel camera = DemoMarkerCamera();
  const catar::MarkerBoard board = ResizedBoard(EightMarkerBoard(13.0, 0.03, -0.02), 0.5);
  std::string png, error;
  ASSERT_TRUE(RenderMarkerFrame(dir, "small", camera, board, false, png, error)) << error;
  const cv::Mat clean = cv::imread(png, cv::IMREAD_COLOR);
  catar::MarkerPoseTracker tracker(board);
  int found = 0;
  for (int seed = 0; seed < 7; ++seed)
  {
    const cv::Mat frame = seed == 0 ? clean : LensBlurAndNoise(clean, 1.0, 6.0, seed + 2);
    const std::vector<std::uint8_t> rgba = RgbaPixels(frame);
    const catar::FramePose& pose =
      tracker.Track(camera, frame.cols, frame.rows, rgba.data(), seed / 30.0);
    double mm = 0.0;
    double degrees = 0.0;
    PoseError(pose.result.worldToCamera, camera.worldToCamera, mm, degrees);
    std::cout << (seed == 0 ? "clean" : "noisy") << " frame: " << pose.markersFound << " markers ("
              << pose.markersRecovered << " read where the pose puts them), " << mm << " mm, "
              << degrees << " deg off; one sigma " << 1000.0 * pose.result.uncertainty.positionSigma
              << " mm, " << pose.result.uncertainty.angleSigmaDegrees << " deg" << std::endl;
    EXPECT_EQ(pose.verdict, catar::PoseVerdict::Reliable) << "frame " << seed << ": " << pose.note;
    // Reliable means right (2 cm, 1 degree), and within three of its sigmas.
    EXPECT_LE(mm, std::min(20.0, 3000.0 * pose.result.uncertainty.positionSigma)) << seed;
    EXPECT_LE(degrees, std::min(1.0, 3.0 * pose.result.uncertainty.angleSigmaDegrees)) << seed;
    found += seed == 0 ? 0 : pose.markersFound;
  }
  EXPECT_GE(found, 33) << "markers found over the six noisy frames";
  const std::string remove = "rm -rf '" + dir + "'";
  EXPECT_EQ(std::system(remove.c_str()), 0);
}
