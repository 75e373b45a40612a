// The rig's calibration (RigCalibration.h) on corners projected by the project's own exact
// projection, with and without noise: that it finds the mirror it was given from a start 3 mm,
// 2 degrees and 5 % off, for the sphere, the tilted hyperboloid and an off-axis paraboloid, with
// the lens too, and refuses what it cannot calibrate. (TestRigCalibrationPovRay checks it on
// frames an independent ray tracer made, through the marker detection.)
#include "CalibrationTestViews.h"
#include "Mirror.h"
#include "Projector.h"
#include "RigCalibration.h"
#include "TestCameras.h"

#include <gtest/gtest.h>

#include <random>

using namespace catar;

namespace
{
// The views' observations: each board corner the rig images, its pixel plus Gaussian noise.
std::vector<CalibrationView> ProjectedViews(
  const CameraModel& rig, const std::vector<Mat4>& poses, double noise, unsigned seed = 1)
{
  const MarkerBoard board = catar_test::CalibrationBoard();
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n(0.0, noise);
  std::vector<CalibrationView> views;
  for (std::size_t v = 0; v < poses.size(); ++v)
  {
    CameraModel posed = rig;
    posed.worldToCamera = poses[v];
    const Projector projector(posed);
    CalibrationView view;
    view.name = "view " + std::to_string(v);
    for (const BoardMarker& m : board.markers)
    {
      for (const Vec3& corner : m.Corners())
      {
        const ProjectedPoint q = projector.ProjectWorld(corner);
        if (q.status == ProjectionStatus::Valid)
        {
          PoseObservation o;
          o.world = corner;
          o.pixel = q.pixel + (noise > 0.0 ? Vec2(n(rng), n(rng)) : Vec2::Zero());
          view.observations.push_back(o);
        }
      }
    }
    views.push_back(view);
  }
  return views;
}

struct Rig
{
  const char* name;
  CameraModel camera;
};

std::vector<Rig> Rigs()
{
  return { { "sphere", catar_test::DemoCameraModel() },
    { "tilted hyperboloid", catar_test::OffFocusHyperboloidCameraModel() },
    { "off-axis paraboloid", catar_test::OffAxisParaboloidCameraModel() } };
}

std::vector<Mat4> Poses(const CameraModel& rig, int count = 10)
{
  std::string error;
  const auto mirror = MakeMirror(rig.mirror, error);
  return catar_test::BoardPosesAround(mirror->Viewpoint(), count, 0.2);
}
} // namespace

TEST(RigCalibration, FindsTheMirrorOfEachShapeFromAStartOff)
{
  for (const Rig& rig : Rigs())
  {
    for (const double noise : { 0.0, 0.3 })
    {
      SCOPED_TRACE(std::string(rig.name) + ", noise " + std::to_string(noise));
      const std::vector<CalibrationView> views =
        ProjectedViews(rig.camera, Poses(rig.camera), noise);
      for (const CalibrationView& v : views)
      {
        ASSERT_GE(v.observations.size(), 12u) << v.name;
      }
      CameraModel start = rig.camera;
      start.worldToCamera = Mat4::Identity();
      start.mirror = catar_test::MirrorStartOff(rig.camera.mirror, 0.003, 2.0, 0.05);
      int calls = 0;
      CalibrationOptions options;
      options.progress = [&](int, double) { ++calls; };
      const CalibrationResult r = CalibrateRig(start, views, options);
      ASSERT_TRUE(r.ok) << r.error;
      EXPECT_EQ(r.imagesUsed, 10);
      EXPECT_GT(calls, 0);
      double metres = 0, degrees = 0, shape = 0;
      catar_test::MirrorDifference(rig.camera.mirror, r.camera.mirror, metres, degrees, shape);
      if (noise == 0.0)
      {
        // Exact corners: the mirror to the solver's tolerance.
        EXPECT_LE(metres, 1e-9);
        EXPECT_LE(degrees, 1e-6);
        EXPECT_LE(shape, 1e-9);
        EXPECT_LE(r.rmsPixels, 1e-6);
        continue;
      }
      // Noisy corners: the errors within four of the reported standard deviations (which must
      // therefore be honest), and the residuals the noise's.
      double position = 0.0, tilt = 0.0, size = 0.0;
      catar_test::MirrorSigmas(r.mirror, position, tilt, size);
      for (const CalibratedNumber& n : r.mirror)
      {
        ASSERT_TRUE(std::isfinite(n.sigma) && n.sigma > 0.0) << n.name;
      }
      EXPECT_LE(metres, 4.0 * position);
      EXPECT_LE(degrees, 4.0 * tilt);
      EXPECT_LE(shape, 4.0 * size);
      EXPECT_NEAR(r.rmsPixels, noise * std::sqrt(2.0), 0.15);
    }
  }
}

TEST(RigCalibration, RefinesTheLensToo)
{
  const CameraModel rig = catar_test::DemoCameraModel();
  const std::vector<CalibrationView> views = ProjectedViews(rig, Poses(rig, 12), 0.0);
  CameraModel start = rig;
  start.mirror = catar_test::MirrorStartOff(rig.mirror, 0.002, 0.0, 0.02);
  start.intrinsics.fx *= 1.01;
  start.intrinsics.cx += 3.0;
  CalibrationOptions options;
  options.freeLens = true;
  const CalibrationResult r = CalibrateRig(start, views, options);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_NEAR(r.camera.intrinsics.fx, rig.intrinsics.fx, 0.05);
  EXPECT_NEAR(r.camera.intrinsics.cx, rig.intrinsics.cx, 0.05);
  EXPECT_EQ(r.lens.size(), 9u); // fx fy cx cy k1 k2 p1 p2 k3
  double metres = 0, degrees = 0, shape = 0;
  catar_test::MirrorDifference(rig.mirror, r.camera.mirror, metres, degrees, shape);
  EXPECT_LE(metres, 1e-5);
  EXPECT_LE(shape, 1e-4);
}

TEST(RigCalibration, RefusesWhatItCannotCalibrate)
{
  const CameraModel rig = catar_test::DemoCameraModel();
  std::vector<CalibrationView> views = ProjectedViews(rig, Poses(rig), 0.0);
  CameraModel start = rig;
  start.worldToCamera = Mat4::Identity();
  // Too few views.
  const std::vector<CalibrationView> two(views.begin(), views.begin() + 2);
  CalibrationResult r = CalibrateRig(start, two, {});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("too few views"), std::string::npos) << r.error;
  // Views without markers are left out, each said.
  std::vector<CalibrationView> some = two;
  some.resize(5);
  r = CalibrateRig(start, some, {});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("no marker of the board found"), std::string::npos) << r.error;
  EXPECT_EQ(r.skipped.size(), 3u);
  // A board printed at 90 % of its file's size: the mirror scales with it, and that is refused.
  std::vector<CalibrationView> small = views;
  for (CalibrationView& v : small)
  {
    for (PoseObservation& o : v.observations)
    {
      o.world *= 1.0 / 0.9;
    }
  }
  r = CalibrateRig(start, small, {});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("the board does not fit"), std::string::npos) << r.error;
  // A board whose layout is another's (the markers 15 % further apart, each its own size): the
  // corners do not fit.
  const MarkerBoard board = catar_test::CalibrationBoard();
  const MarkerBoard spread = catar_test::CalibrationBoard(0.06, 0.09 * 1.15);
  std::vector<CalibrationView> other = views;
  for (CalibrationView& v : other)
  {
    for (PoseObservation& o : v.observations)
    {
      for (std::size_t m = 0; m < board.markers.size(); ++m)
      {
        for (int c = 0; c < 4; ++c)
        {
          if ((board.markers[m].Corners()[c] - o.world).norm() < 1e-12)
          {
            o.world = spread.markers[m].Corners()[c];
          }
        }
      }
    }
  }
  r = CalibrateRig(start, other, {});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("does not fit"), std::string::npos) << r.error;
  // The general quadric is not calibrated.
  CameraModel general = start;
  QuadricGeometry g;
  ASSERT_TRUE(QuadricFromDescription(catar_test::TiltedHyperboloidCameraModel().mirror, g));
  std::vector<double> numbers(34);
  Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(numbers.data()) = g.omega;
  Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(numbers.data() + 16) = g.mirrorToCamera;
  numbers[32] = g.zmin;
  numbers[33] = g.zmax;
  general.mirror = MirrorDescription("quadric", numbers);
  ASSERT_EQ(general.Validate(), "");
  r = CalibrateRig(general, views, {});
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("cannot be calibrated"), std::string::npos) << r.error;
}
