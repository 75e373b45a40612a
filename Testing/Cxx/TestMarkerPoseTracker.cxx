// The pose of a sequence from its markers, frame to frame (MarkerPoseTracker.h): the markers'
// corners are the board's corners projected under a known camera path (with 0.3 px of noise),
// so the truth is known and the tracker's verdicts can be checked: a smooth path is reliable
// throughout; one frame whose markers give a pose far off the path (a wrong decode, a swapped
// frame) is flagged as a jump and the path goes on from the last reliable pose; a camera that
// really moves there (a cut in the video) is accepted from the second frame that agrees.
#include "MarkerPoseTracker.h"
#include "Projector.h"
#include "TestCameras.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <fstream>
#include <random>
#include <string>
#include <vector>

using namespace catar;

namespace
{
constexpr double kPi = 3.14159265358979323846;
constexpr double kFps = 30.0;

// Six 20 cm markers on the floor behind the demo camera.
MarkerBoard Board()
{
  MarkerBoard b;
  const double xy[6][2] = { { -0.45, -0.5 }, { 0.0, -0.5 }, { 0.45, -0.5 }, { -0.45, -0.95 },
    { 0.0, -0.95 }, { 0.45, -0.95 } };
  for (int k = 0; k < 6; ++k)
  {
    BoardMarker m;
    m.id = k;
    m.translate = Vec3(xy[k][0], xy[k][1], 0.0);
    m.size = 0.2;
    b.markers.push_back(m);
  }
  return b;
}

// The demo camera moved by `shift` (world) and turned by `turnDegrees` about the vertical.
Mat4 CameraPose(const Vec3& shift, double turnDegrees)
{
  const Mat4 demo = catar_test::DemoCameraModel().worldToCamera;
  const Mat3 turn = Eigen::AngleAxisd(turnDegrees * kPi / 180.0, Vec3::UnitZ()).toRotationMatrix();
  const Mat3 R = demo.topLeftCorner<3, 3>() * turn.transpose();
  const Vec3 centre = Vec3(0.0, -0.14, 1.0) + shift;
  Mat4 pose = Mat4::Identity();
  pose.topLeftCorner<3, 3>() = R;
  pose.topRightCorner<3, 1>() = -R * centre;
  return pose;
}

// What a detector would report under the pose: every marker whose four corners are seen.
std::vector<MarkerDetection> Seen(const MarkerBoard& board, const Mat4& pose, std::mt19937& rng)
{
  CameraModel camera = catar_test::DemoCameraModel();
  camera.worldToCamera = pose;
  const Projector projector(camera);
  std::normal_distribution<double> noise(0.0, 0.3);
  std::vector<MarkerDetection> found;
  for (const BoardMarker& m : board.markers)
  {
    MarkerDetection d;
    d.id = m.id;
    bool all = true;
    const std::array<Vec3, 4> corners = m.Corners();
    for (int c = 0; c < 4; ++c)
    {
      const ProjectedPoint p = projector.ProjectWorld(corners[c]);
      all = all && p.status == ProjectionStatus::Valid;
      d.corners[c] = p.pixel + Vec2(noise(rng), noise(rng));
    }
    if (all)
    {
      found.push_back(d);
    }
  }
  return found;
}

// The camera's path: 1 cm a frame along x (0.3 m/s).
Mat4 Path(int k)
{
  return CameraPose(Vec3(0.01 * k, 0.0, 0.0), 0.0);
}

struct TrackedRun
{
  std::vector<PoseVerdict> verdicts;
  std::vector<std::string> notes;
  int failures = 0;
};

// Tracks frames 0..n-1 whose markers are seen under pose(k).
template<typename PoseOf>
TrackedRun Track(int n, PoseOf pose)
{
  const MarkerBoard board = Board();
  MarkerPoseTracker tracker(board);
  std::mt19937 rng(3);
  TrackedRun run;
  for (int k = 0; k < n; ++k)
  {
    const FramePose& f =
      tracker.Track(catar_test::DemoCameraModel(), Seen(board, pose(k), rng), k / kFps);
    run.verdicts.push_back(f.verdict);
    run.notes.push_back(f.note);
  }
  run.failures = tracker.Failures();
  return run;
}
} // namespace

TEST(MarkerPoseTracker, ASmoothPathIsReliableThroughout)
{
  const TrackedRun run = Track(10, Path);
  for (int k = 0; k < 10; ++k)
  {
    EXPECT_EQ(run.verdicts[k], PoseVerdict::Reliable) << "frame " << k << ": " << run.notes[k];
  }
  EXPECT_EQ(run.failures, 0);
}

TEST(MarkerPoseTracker, OneFrameOffThePathIsFlaggedAsAJump)
{
  // Frame 5's markers give a pose 30 cm off the path (1/30 s: 9 m/s, beyond max_speed 5).
  const TrackedRun run =
    Track(9, [](int k) { return k == 5 ? CameraPose(Vec3(0.05, 0.3, 0.0), 0.0) : Path(k); });
  EXPECT_EQ(run.verdicts[5], PoseVerdict::Unreliable);
  EXPECT_EQ(run.notes[5].rfind("the camera jumped", 0), 0u) << run.notes[5];
  for (int k : { 0, 1, 2, 3, 4, 6, 7, 8 })
  {
    EXPECT_EQ(run.verdicts[k], PoseVerdict::Reliable) << "frame " << k << ": " << run.notes[k];
  }
  EXPECT_EQ(run.failures, 1);
}

TEST(MarkerPoseTracker, ATurnFasterThanAllowedIsFlagged)
{
  // 25 degrees in 1/30 s: 750 degrees a second, beyond max_turn_rate 360.
  const TrackedRun run =
    Track(8, [](int k) { return k == 4 ? CameraPose(Vec3(0.04, 0.0, 0.0), 25.0) : Path(k); });
  EXPECT_EQ(run.verdicts[4], PoseVerdict::Unreliable);
  EXPECT_EQ(run.notes[4].rfind("the camera turned", 0), 0u) << run.notes[4];
  EXPECT_EQ(run.verdicts[5], PoseVerdict::Reliable) << run.notes[5];
}

TEST(MarkerPoseTracker, ACutIsAcceptedFromTheSecondFrameThatAgrees)
{
  // From frame 5 on the camera is 30 cm elsewhere and stays there.
  const TrackedRun run =
    Track(9, [](int k) { return k >= 5 ? CameraPose(Vec3(0.01 * k, 0.3, 0.0), 0.0) : Path(k); });
  EXPECT_EQ(run.verdicts[5], PoseVerdict::Unreliable) << run.notes[5];
  for (int k = 6; k < 9; ++k)
  {
    EXPECT_EQ(run.verdicts[k], PoseVerdict::Reliable) << "frame " << k << ": " << run.notes[k];
  }
  EXPECT_EQ(run.failures, 1);
}

TEST(MarkerPoseTracker, TheBoardFileSetsTheGuards)
{
  const std::string path = ::testing::TempDir() + "guards-board.yaml";
  {
    std::ofstream(path) << "dictionary: DICT_4X4_50\n"
                           "guards: { max_position_sigma: 0.02, max_angle_sigma: 1.5, "
                           "min_inlier_fraction: 0.75, allow_single_marker: true, "
                           "pixel_noise_floor: 0.25, max_speed: 1.5, max_turn_rate: 90 }\n"
                           "markers:\n  - { id: 3, size: 0.2 }\n";
  }
  MarkerBoard board;
  std::string error;
  ASSERT_TRUE(LoadMarkerBoard(path, board, error)) << error;
  EXPECT_DOUBLE_EQ(board.pose.maxPositionSigma, 0.02);
  EXPECT_DOUBLE_EQ(board.pose.maxAngleSigmaDegrees, 1.5);
  EXPECT_DOUBLE_EQ(board.pose.minInlierFraction, 0.75);
  EXPECT_TRUE(board.pose.allowSingleMarker);
  EXPECT_DOUBLE_EQ(board.pose.minimumPixelSigma, 0.25);
  EXPECT_DOUBLE_EQ(board.maxSpeed, 1.5);
  EXPECT_DOUBLE_EQ(board.maxTurnRateDegrees, 90.0);
  for (const char* bad : { "max_speed: -1", "min_inlier_fraction: 2", "max_sped: 1" })
  {
    std::ofstream(path) << "dictionary: DICT_4X4_50\nguards: { " << bad
                        << " }\nmarkers:\n  - { id: 3, size: 0.2 }\n";
    EXPECT_FALSE(LoadMarkerBoard(path, board, error)) << bad;
    EXPECT_NE(error.find("guards"), std::string::npos) << error;
  }
}
