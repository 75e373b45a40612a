// The lens models (CameraModel, LensModels.h) against OpenCV, the outside implementation of each:
// OpenCV's pinhole with every length of its distortion vector (cv::projectPoints) and the fisheye
// (cv::fisheye::projectPoints); pixel -> ray -> pixel over the whole image; calibration files of
// each model; and the projection through the mirror with each lens, forward against backward.
#include "CalibrationIO.h"
#include "Projector.h"
#include "SphereMirror.h"

#include <gtest/gtest.h>
#include <opencv2/calib3d.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

using namespace catar;

namespace
{
// A 1280x960 camera with a realistic lens of each OpenCV length (the rational model's numerator
// and denominator both growing, as cv::calibrateCamera's CALIB_RATIONAL_MODEL gives them; the
// thin prism and tilt small), invertible over the whole image.
CameraModel Pinhole(int count)
{
  CameraModel m;
  m.intrinsics = Intrinsics{ 820.5, 815.25, 640.2, 470.8, 0.0, 1280, 960 };
  const std::vector<double> all = { 0.25, 0.11, 0.0012, -0.0007, 0.009, 0.61, 0.18, 0.012, 0.0011,
    -0.0005, 0.0008, 0.0002, 0.012, -0.018 };
  EXPECT_TRUE(m.distortion.SetCoefficients(
    LensType::Pinhole, std::vector<double>(all.begin(), all.begin() + count)));
  m.mirror = SphereMirror{ Vec3(0.0, 0.0, 0.2), 0.06 };
  return m;
}

// A fisheye of about 195 degrees across the image's diagonal (cv::fisheye's coefficients of a
// real 180-degree lens are of this size).
CameraModel Fisheye(double skew = 0.0)
{
  CameraModel m;
  m.lens = LensType::Fisheye;
  m.intrinsics = Intrinsics{ 464.0, 463.0, 640.5, 479.5, skew, 1280, 960 };
  EXPECT_TRUE(m.distortion.SetCoefficients(LensType::Fisheye, { 0.01, -0.002, 0.0003, -0.00002 }));
  m.mirror = SphereMirror{ Vec3(0.0, 0.0, 0.2), 0.06 };
  return m;
}

cv::Mat CameraMatrix(const CameraModel& m)
{
  return (cv::Mat_<double>(3, 3) << m.intrinsics.fx, m.intrinsics.skew, m.intrinsics.cx, 0,
    m.intrinsics.fy, m.intrinsics.cy, 0, 0, 1);
}

// Directions whose pixels cover the image (and a margin): from pixels of the image, through the
// model's own inverse, then jittered, so that OpenCV sees points all over the field.
std::vector<Vec3> DirectionsOverTheImage(const CameraModel& m, int count)
{
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<Vec3> out;
  while (static_cast<int>(out.size()) < count)
  {
    const Vec2 px(-0.5 + u(rng) * m.intrinsics.width, -0.5 + u(rng) * m.intrinsics.height);
    Vec3 d;
    if (m.PixelToDirection(px, d))
    {
      out.push_back(d * (0.5 + 2.0 * u(rng)));
    }
  }
  return out;
}

// The largest distance between the model's pixels of the directions and OpenCV's (`project`:
// cv::projectPoints or cv::fisheye::projectPoints of the directions as points).
template<class Project>
double WorstAgainstOpenCV(const CameraModel& m, const std::vector<Vec3>& dirs, Project project)
{
  std::vector<cv::Point3d> pts;
  pts.reserve(dirs.size());
  for (const Vec3& d : dirs)
  {
    pts.emplace_back(d.x(), d.y(), d.z());
  }
  std::vector<cv::Point2d> px;
  project(pts, px);
  double worst = 0.0;
  for (std::size_t i = 0; i < pts.size(); ++i)
  {
    worst = std::max(worst, (m.DirectionToPixel(dirs[i]) - Vec2(px[i].x, px[i].y)).norm());
  }
  return worst;
}

// Pixel -> direction -> pixel on a grid over the image, borders included: the largest error.
double WorstRoundTrip(const CameraModel& m, int& failures)
{
  double worst = 0.0;
  failures = 0;
  const int w = m.intrinsics.width;
  const int h = m.intrinsics.height;
  for (double y = -0.5; y <= h - 0.5; y += (h - 1) / 60.0)
  {
    for (double x = -0.5; x <= w - 0.5; x += (w - 1) / 80.0)
    {
      Vec3 d;
      if (!m.PixelToDirection(Vec2(x, y), d))
      {
        ++failures;
        continue;
      }
      EXPECT_NEAR(d.norm(), 1.0, 1e-14);
      worst = std::max(worst, (m.DirectionToPixel(d) - Vec2(x, y)).norm());
    }
  }
  return worst;
}
} // namespace

TEST(LensModels, PinholeOfEveryLengthMatchesOpenCV)
{
  for (const int count : { 4, 5, 8, 12, 14 })
  {
    SCOPED_TRACE("distortion coefficients: " + std::to_string(count));
    const CameraModel m = Pinhole(count);
    ASSERT_EQ(m.Validate(), "");
    const std::vector<double> coefficients = m.distortion.Coefficients(m.lens);
    EXPECT_EQ(coefficients.size(), static_cast<std::size_t>(std::max(count, 5)));
    const double worst = WorstAgainstOpenCV(m, DirectionsOverTheImage(m, 3000),
      [&](const std::vector<cv::Point3d>& pts, std::vector<cv::Point2d>& px) {
        cv::projectPoints(
          pts, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), CameraMatrix(m), cv::Mat(coefficients), px);
      });
    EXPECT_LE(worst, 1e-9);
    int failures = 0;
    EXPECT_LE(WorstRoundTrip(m, failures), 1e-9);
    EXPECT_EQ(failures, 0);
  }
}

TEST(LensModels, FisheyeMatchesOpenCVAndSeesPast90Degrees)
{
  for (const double skew : { 0.0, 0.9 })
  {
    SCOPED_TRACE("skew " + std::to_string(skew));
    const CameraModel m = Fisheye(skew);
    ASSERT_EQ(m.Validate(), "");
    // OpenCV's fisheye takes points in front (z > 0): compare there.
    std::vector<Vec3> dirs;
    for (const Vec3& d : DirectionsOverTheImage(m, 6000))
    {
      if (d.z() > 1e-3 * d.norm())
      {
        dirs.push_back(d);
      }
    }
    ASSERT_GT(dirs.size(), 3000u);
    const std::vector<double> D = m.distortion.Coefficients(m.lens);
    ASSERT_EQ(D.size(), 4u);
    const double worst = WorstAgainstOpenCV(
      m, dirs, [&](const std::vector<cv::Point3d>& pts, std::vector<cv::Point2d>& px) {
        cv::fisheye::projectPoints(pts, px, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), CameraMatrix(m),
          cv::Mat(D), m.intrinsics.skew / m.intrinsics.fx);
      });
    EXPECT_LE(worst, 1e-9);
    int failures = 0;
    EXPECT_LE(WorstRoundTrip(m, failures), 1e-9);
    EXPECT_EQ(failures, 0);
  }
  // The corners are past 90 degrees from the axis: directions behind the lens's plane, which the
  // lens sees and PixelToNormalized (x/z) cannot give.
  const CameraModel m = Fisheye();
  Vec3 corner;
  ASSERT_TRUE(m.PixelToDirection(Vec2(-0.5, -0.5), corner));
  EXPECT_LT(corner.z(), 0.0);
  EXPECT_TRUE(m.Sees(corner));
  Vec2 xy;
  EXPECT_FALSE(m.PixelToNormalized(Vec2(-0.5, -0.5), xy));
  // The angle from the axis is the model's: theta_d = |distorted normalised coordinates|.
  const double thetaD = Vec2((-0.5 - 640.5) / 464.0, (-0.5 - 479.5) / 463.0).norm();
  const double theta = std::acos(corner.z());
  const double t2 = theta * theta;
  EXPECT_NEAR(
    theta * (1 + t2 * (0.01 + t2 * (-0.002 + t2 * (0.0003 + t2 * -0.00002)))), thetaD, 1e-13);
}

TEST(LensModels, MeetsTheMirrorForwardAndBackward)
{
  // With each lens: a pixel's reflected ray, a point on it, and that point's projection land on
  // the pixel again (the projector's forward and backward directions through the lens).
  const CameraModel pinhole = Pinhole(14);
  CameraModel fisheye = Fisheye();
  // A sphere the fisheye sees whole, not too small in the image.
  fisheye.mirror = SphereMirror{ Vec3(0.0, 0.0, 0.09), 0.06 };
  for (const CameraModel* m : { &pinhole, static_cast<const CameraModel*>(&fisheye) })
  {
    SCOPED_TRACE(LensName(m->lens));
    Projector projector(*m);
    ASSERT_TRUE(projector.IsValid());
    int seen = 0;
    double worst = 0.0;
    for (int y = 0; y < m->intrinsics.height; y += 24)
    {
      for (int x = 0; x < m->intrinsics.width; x += 24)
      {
        const BackProjectedRay ray = projector.BackProjectCamera(Vec2(x, y));
        if (ray.status != ProjectionStatus::Valid)
        {
          continue;
        }
        const Vec3 point = ray.mirrorPoint + 0.7 * ray.direction;
        const ProjectedPoint p = projector.ProjectCamera(point, SolverType::Quartic);
        ASSERT_EQ(p.status, ProjectionStatus::Valid) << x << ", " << y;
        worst = std::max(worst, (p.pixel - Vec2(x, y)).norm());
        ++seen;
      }
    }
    EXPECT_GT(seen, 300);
    EXPECT_LE(worst, 1e-6);
  }
}

TEST(LensModels, CalibrationFilesOfEachModel)
{
  for (const int count : { 4, 5, 8, 12, 14 })
  {
    const CameraModel m = Pinhole(count);
    CameraModel back;
    std::string error;
    ASSERT_TRUE(ParseCalibration(CalibrationToString(m), back, error)) << error;
    EXPECT_EQ(back.lens, LensType::Pinhole);
    EXPECT_TRUE(back.distortion == m.distortion) << count;
    ASSERT_TRUE(ParseCalibration(CalibrationToString(m, true), back, error)) << error;
    EXPECT_TRUE(back.distortion == m.distortion) << count;
  }
  const CameraModel f = Fisheye(0.5);
  const std::string text = CalibrationToString(f);
  EXPECT_NE(text.find("lens: fisheye"), std::string::npos) << text;
  CameraModel back;
  std::string error;
  ASSERT_TRUE(ParseCalibration(text, back, error)) << error;
  EXPECT_EQ(back.lens, LensType::Fisheye);
  EXPECT_TRUE(back.distortion == f.distortion);
  EXPECT_TRUE(back.SameLens(f));

  // ROS camera_info's names of the models.
  const std::string head = "image_width: 640\nimage_height: 480\n"
                           "camera_matrix: [500, 0, 320, 0, 500, 240, 0, 0, 1]\n"
                           "mirror: { center: [0, 0, 0.3], radius: 0.1 }\n";
  ASSERT_TRUE(ParseCalibration(head +
      "distortion_model: rational_polynomial\n"
      "distortion_coefficients: [-0.1, 0.01, 0, 0, 0.001, 0.02, 0.003, 0.0004]\n",
    back, error))
    << error;
  EXPECT_EQ(back.lens, LensType::Pinhole);
  EXPECT_DOUBLE_EQ(back.distortion.k6, 0.0004);
  ASSERT_TRUE(ParseCalibration(
    head + "distortion_model: equidistant\ndistortion_coefficients: [0.01, -0.002, 0.0003, 0]\n",
    back, error))
    << error;
  EXPECT_EQ(back.lens, LensType::Fisheye);
  EXPECT_DOUBLE_EQ(back.distortion.k3, 0.0003);

  // Refusals that say what is wrong.
  const struct
  {
    std::string text;
    std::string expected;
  } refused[] = {
    { head + "distortion_coefficients: [0.1, 0, 0, 0, 0, 0]\n", "4, 5, 8, 12 or 14" },
    { head + "lens: fisheye\ndistortion_coefficients: [0.1, 0, 0, 0, 0]\n", "4 numbers" },
    { head + "lens: telephoto\n", "not a lens model" },
    { head + "lens: fisheye\ndistortion_model: plumb_bob\n", "contradicts" },
    { head + "distortion_model: fov\n", "not supported" },
    { head + "distortion_coefficients: [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 2, 0]\n", "tilt" },
  };
  for (const auto& r : refused)
  {
    std::string why;
    CameraModel ignored;
    EXPECT_FALSE(ParseCalibration(r.text, ignored, why)) << r.text;
    EXPECT_NE(why.find(r.expected), std::string::npos) << why;
  }
}
