// A quadric mirror's pose from its rim's outline (QuadricFromRim, Module/Vision/MirrorOutline.h):
// on exact outlines (the rim circle's points projected by the lens alone: no mirror solver
// involved), with noise, from a first guess several millimetres and degrees off, and bad inputs.
#include "MirrorOutline.h"
#include "QuadricMirror.h"
#include "TestCameras.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <random>
#include <string>
#include <vector>

using namespace catar;

namespace
{
constexpr double kPi = 3.14159265358979323846;

// The tilted hyperboloid rig (TestCameras.h) seen with a wider lens (f = 500 px, so that the rim,
// 35 degrees off the axis, is in the 1328 x 1048 frame), with or without distortion.
CameraModel RimCamera(bool distorted)
{
  CameraModel camera = catar_test::TiltedHyperboloidCameraModel();
  camera.intrinsics = Intrinsics{ 500.0, 500.0, 663.5, 523.5, 0.0, 1328, 1048 };
  if (distorted)
  {
    camera.distortion.k1 = -0.12;
    camera.distortion.k2 = 0.02;
    camera.distortion.p1 = 0.0008;
  }
  return camera;
}

// The rim circle of a hyperboloid description (the widest end of z_range) in the camera frame.
void TrueRim(const MirrorDescription& mirror, Vec3& centre, Vec3& axis, double& radius)
{
  QuadricGeometry g;
  ASSERT_TRUE(QuadricFromDescription(mirror, g));
  const double a = mirror.parameters[0], b = mirror.parameters[1], z = g.zmax;
  radius = b * std::sqrt(z * z / (a * a) - 1.0);
  centre = g.mirrorToCamera.topLeftCorner<3, 3>() * Vec3(0, 0, z) +
    g.mirrorToCamera.topRightCorner<3, 1>();
  axis = g.mirrorToCamera.topLeftCorner<3, 3>().col(2);
}

// `count` points of the rim's image, projected by the camera's lens (DirectionToPixel).
std::vector<Vec2> RimOutline(const CameraModel& camera, int count)
{
  Vec3 centre, axis;
  double radius = 0.0;
  TrueRim(camera.mirror, centre, axis, radius);
  const Vec3 e1 = axis.unitOrthogonal(), e2 = axis.cross(e1);
  std::vector<Vec2> points;
  for (int k = 0; k < count; ++k)
  {
    const double angle = 2.0 * kPi * k / count;
    points.push_back(
      camera.DirectionToPixel(centre + radius * (std::cos(angle) * e1 + std::sin(angle) * e2)));
  }
  return points;
}

// The description with a nominal mounting instead: tilted `degrees` about x (the true rig: 4),
// the mirror 3 mm across, 2 mm up and 4 mm further (a first guess before calibration).
MirrorDescription Nominal(MirrorDescription mirror, double degrees)
{
  const double t = degrees * kPi / 180.0;
  const double h[16] = { 1, 0, 0, 0.003, 0, std::cos(t), -std::sin(t), -0.002, 0, std::sin(t),
    std::cos(t), 0.054, 0, 0, 0, 1 };
  std::copy(h, h + 16, mirror.parameters.begin() + 2);
  return mirror;
}
} // namespace

TEST(QuadricRim, ExactRimGivesTheAxisAndCentre)
{
  for (const bool distorted : { false, true })
  {
    SCOPED_TRACE(distorted ? "distorted" : "pinhole");
    const CameraModel camera = RimCamera(distorted);
    const std::vector<Vec2> outline = RimOutline(camera, 400);
    for (const Vec2& p : outline)
    {
      ASSERT_TRUE(p.x() > 0 && p.y() > 0 && p.x() < 1327 && p.y() < 1047) << p.transpose();
    }
    // A guess half a degree off the true tilt, nearer it than the other pose the rim allows
    // (about 2.2 degrees from it: the rim, seen nearly head-on, hardly fixes the tilt).
    MirrorDescription mirror = Nominal(camera.mirror, 3.5);
    RimOutlineReport report;
    std::string error;
    ASSERT_TRUE(QuadricFromRim(camera, outline, mirror, report, error)) << error;
    Vec3 centre, axis, foundCentre, foundAxis;
    double radius = 0.0, foundRadius = 0.0;
    TrueRim(camera.mirror, centre, axis, radius);
    TrueRim(mirror, foundCentre, foundAxis, foundRadius);
    const double axisError = std::atan2(axis.cross(foundAxis).norm(), axis.dot(foundAxis));
    std::cout << "[ rim      ] exact, " << (distorted ? "distorted" : "pinhole")
              << ": centre error " << (foundCentre - centre).norm() << " m, axis error "
              << axisError << " rad, rms " << report.rmsPixels << " px, first guess "
              << report.shift * 1e3 << " mm and " << report.axisTurn * 180.0 / kPi << " deg off, "
              << report.iterations << " iterations" << std::endl;
    EXPECT_NEAR(foundRadius, radius, 1e-15);
    EXPECT_LT((foundCentre - centre).norm(), 1e-9 * centre.norm());
    EXPECT_LT(axisError, 1e-8);
    EXPECT_LT(report.rmsPixels, 1e-3); // the rim's image is drawn with 2880 segments
    EXPECT_NEAR(report.axisTurn, 0.5 * kPi / 180.0, 1e-6);
    // Through this lens the other pose fits exactly too: flagged, the other axis reported.
    EXPECT_GT(report.ambiguousTilt, 0.5 * kPi / 180.0);
    EXPECT_NEAR(report.otherAxis.norm(), 1.0, 1e-12);
    // The fitted mirror reflects as the true one: same surface (the turn about the axis aside).
    QuadricGeometry g;
    ASSERT_TRUE(QuadricFromDescription(mirror, g));
    const Mat3 R = g.mirrorToCamera.topLeftCorner<3, 3>();
    EXPECT_NEAR(R.determinant(), 1.0, 1e-12);
    EXPECT_LT((R.transpose() * R - Mat3::Identity()).norm(), 1e-12);
  }
}

// With 0.3 px of noise: the rim seen nearly head-on fixes its distance but not its tilt. Fitting
// the axis too, both poses a circle's image allows fit: a trial is flagged (and then the true axis
// lies within the range of tilts reported to fit alike) or right within four sigmas; keeping the
// axis (a rig built on axis, the guess's axis right), the centre is within 0.1 % of its distance
// and its spread matches the reported sigma.
TEST(QuadricRim, NoisyRimIsCloseToTheTruth)
{
  const CameraModel camera = RimCamera(false);
  const std::vector<Vec2> exact = RimOutline(camera, 600);
  Vec3 centre, axis;
  double radius = 0.0;
  TrueRim(camera.mirror, centre, axis, radius);
  for (const bool fitAxis : { true, false })
  {
    SCOPED_TRACE(fitAxis ? "axis fitted" : "axis kept");
    std::mt19937 random(7);
    std::normal_distribution<double> noise(0.0, 0.3);
    double worstCentre = 0.0, worstAxis = 0.0, centreSpread = 0.0, axisSpread = 0.0;
    double centreSigma = 0.0, axisSigma = 0.0;
    int ambiguous = 0;
    constexpr int kTrials = 50;
    for (int trial = 0; trial < kTrials; ++trial)
    {
      std::vector<Vec2> outline = exact;
      for (Vec2& p : outline)
      {
        p += Vec2(noise(random), noise(random));
      }
      // Kept, the axis is the true one: the guess is off in position only.
      MirrorDescription mirror = camera.mirror;
      if (fitAxis)
      {
        mirror = Nominal(mirror, 2.5);
      }
      else
      {
        mirror.parameters[2 + 3] += 0.003;
        mirror.parameters[2 + 11] += 0.004;
      }
      RimFitOptions options;
      options.fitAxis = fitAxis;
      RimOutlineReport report;
      std::string error;
      ASSERT_TRUE(QuadricFromRim(camera, outline, options, mirror, report, error)) << error;
      Vec3 foundCentre, foundAxis;
      double foundRadius = 0.0;
      TrueRim(mirror, foundCentre, foundAxis, foundRadius);
      const double c = (foundCentre - centre).norm();
      const double a = std::atan2(axis.cross(foundAxis).norm(), axis.dot(foundAxis));
      // Fitting the axis: never silently wrong. Either the axis is right within four sigmas, or
      // the range of tilts that fit alike is flagged and holds the true axis.
      if (fitAxis)
      {
        if (report.ambiguousTilt > 0.0)
        {
          // The true axis lies within the range of tilts reported to fit alike.
          EXPECT_LT(a, report.ambiguousTilt + 4.0 * report.axisSigma) << "trial " << trial;
          EXPECT_NEAR(report.otherAxis.norm(), 1.0, 1e-9);
        }
        else
        {
          EXPECT_LT(a, 4.0 * report.axisSigma) << "trial " << trial;
        }
      }
      ambiguous += report.ambiguousTilt > 0.0;
      worstCentre = std::max(worstCentre, c / centre.norm());
      worstAxis = std::max(worstAxis, a);
      centreSpread += c * c / kTrials;
      axisSpread += a * a / kTrials;
      centreSigma += report.centreSigma / kTrials;
      axisSigma += report.axisSigma / kTrials;
      EXPECT_NEAR(report.rmsPixels, 0.3, 0.1);
    }
    // The spread's RMS (3 or 2 directions) against the worst direction's sigma.
    centreSpread = std::sqrt(centreSpread);
    axisSpread = std::sqrt(axisSpread);
    std::cout << "[ rim      ] 0.3 px noise, 600 points, " << kTrials << " trials, "
              << (fitAxis ? "axis fitted" : "axis kept") << ": worst centre error "
              << 100.0 * worstCentre << " % of the distance, worst axis error "
              << worstAxis * 180.0 / kPi << " deg; spread " << centreSpread * 1e3 << " mm, "
              << axisSpread * 180.0 / kPi << " deg; reported sigma " << centreSigma * 1e3 << " mm, "
              << axisSigma * 180.0 / kPi << " deg; " << ambiguous << " flagged ambiguous"
              << std::endl;
    if (!fitAxis)
    {
      EXPECT_GT(centreSpread, 0.5 * centreSigma);
      EXPECT_LT(centreSpread, 2.0 * centreSigma);
      EXPECT_LT(worstCentre, 1e-3);
      EXPECT_EQ(axisSigma, 0.0);
      EXPECT_EQ(ambiguous, 0);
    }
  }
}

TEST(QuadricRim, BadInputsAreRefused)
{
  const CameraModel camera = RimCamera(false);
  const std::vector<Vec2> outline = RimOutline(camera, 100);
  RimOutlineReport report;
  std::string error;
  const auto refused = [&](MirrorDescription mirror, const std::vector<Vec2>& points,
                         const std::string& words) {
    error.clear();
    const MirrorDescription before = mirror;
    EXPECT_FALSE(QuadricFromRim(camera, points, mirror, report, error)) << words;
    EXPECT_NE(error.find(words), std::string::npos) << error;
    EXPECT_EQ(mirror, before);
  };
  refused(MirrorDescription("sphere", { 0, 0, 0.14, 0.05 }), outline, "not a quadric mirror");
  MirrorDescription ellipsoid = camera.mirror;
  ellipsoid.type = "ellipsoid";
  ellipsoid.parameters = { 0.03, 0.04, 0.05 };
  ellipsoid.parameters.insert(ellipsoid.parameters.end(), camera.mirror.parameters.begin() + 2,
    camera.mirror.parameters.end());
  ellipsoid.parameters[ellipsoid.parameters.size() - 2] = -0.02;
  ellipsoid.parameters.back() = 0.02;
  refused(ellipsoid, outline, "not a surface of revolution");
  refused(camera.mirror, std::vector<Vec2>(outline.begin(), outline.begin() + 4), "at least 5");
  std::vector<Vec2> withNaN = outline;
  withNaN[2].x() = std::nan("");
  refused(camera.mirror, withNaN, "outline point 2");
}
