// Pose from the image (PoseEstimation.h and the catadioptric-pose program): correspondences come
// from the project's own forward projection (Projector::ProjectWorld) of world points ~1 m away
// under a known pose; that true pose is the oracle. Both mirrors: the demo sphere and the tilted
// hyperboloid (a general quadric, not central).
#include "CalibrationIO.h"
#include "PoseEstimation.h"
#include "Projector.h"
#include "TestCameras.h"

#include "TestPrograms.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <vector>

using namespace catar;

namespace
{
constexpr double kPi = 3.14159265358979323846;

struct Named
{
  const char* name;
  CameraModel camera;
};

std::vector<Named> Cameras()
{
  return { { "sphere", catar_test::DemoCameraModel() },
    { "tilted hyperboloid", catar_test::TiltedHyperboloidCameraModel() } };
}

// World-to-camera: the camera centre at `centre`, turned by `angle` about `axis` from the demo
// orientation (looking along world +y, image up = world +z).
Mat4 MakePose(const Vec3& axis, double angleDegrees, const Vec3& centre)
{
  const Mat3 demo = catar_test::DemoCameraModel().worldToCamera.topLeftCorner<3, 3>();
  const Mat3 R = demo * Eigen::AngleAxisd(angleDegrees * kPi / 180.0, axis.normalized());
  Mat4 pose = Mat4::Identity();
  pose.topLeftCorner<3, 3>() = R;
  pose.topRightCorner<3, 1>() = -R * centre;
  return pose;
}

std::vector<Mat4> TruePoses()
{
  return { catar_test::DemoCameraModel().worldToCamera,
    MakePose(Vec3(0.3, -1.0, 0.5), 37.0, Vec3(2.5, -1.0, 0.4)),
    MakePose(Vec3(1.0, 0.2, -0.4), 170.0, Vec3(-3.0, 7.0, 1.5)) };
}

Vec3 Centre(const Mat4& pose)
{
  return -pose.topLeftCorner<3, 3>().transpose() * pose.topRightCorner<3, 1>();
}

double PositionError(const Mat4& a, const Mat4& b)
{
  return (Centre(a) - Centre(b)).norm();
}

double RotationError(const Mat4& a, const Mat4& b)
{
  const Mat3 d = a.topLeftCorner<3, 3>() * b.topLeftCorner<3, 3>().transpose();
  return Eigen::AngleAxisd(d).angle();
}

// A pixel inside the image whose reflected ray leaves the mirror (camera-frame ray).
BackProjectedRay RandomRay(const Projector& projector, std::mt19937& rng, Vec2& pixel)
{
  const Intrinsics& k = projector.GetModel().intrinsics;
  std::uniform_real_distribution<double> u(-0.5, k.width - 0.5), v(-0.5, k.height - 0.5);
  for (;;)
  {
    pixel = Vec2(u(rng), v(rng));
    const BackProjectedRay ray = projector.BackProjectCamera(pixel);
    if (ray.status == ProjectionStatus::Valid)
    {
      return ray;
    }
  }
}

// Is the pixel 3 px or more inside the mirror's image? At the rim of a cut mirror (the
// hyperboloid's z_range) a pose off by noise can take a point's reflection off the mirror.
bool AwayFromRim(const Projector& projector, const Vec2& pixel)
{
  for (const Vec2& step : { Vec2(3, 0), Vec2(-3, 0), Vec2(0, 3), Vec2(0, -3) })
  {
    if (projector.BackProjectCamera(pixel + step).status != ProjectionStatus::Valid)
    {
      return false;
    }
  }
  return true;
}

// n exact correspondences: world points 0.8 to 1.2 m along the reflected rays of random pixels on
// the mirror's image (away from its rim), with the pixels their forward projection gives under
// the true pose.
std::vector<PoseObservation> Exact(
  const CameraModel& camera, const Mat4& truePose, int n, std::mt19937& rng)
{
  CameraModel posed = camera;
  posed.worldToCamera = truePose;
  const Projector projector(posed);
  std::uniform_real_distribution<double> distance(0.8, 1.2);
  std::vector<PoseObservation> out;
  while (static_cast<int>(out.size()) < n)
  {
    Vec2 pixel;
    const BackProjectedRay ray = RandomRay(projector, rng, pixel);
    const Vec3 world = projector.GetPose().ToWorld(ray.mirrorPoint + distance(rng) * ray.direction);
    const ProjectedPoint q = projector.ProjectWorld(world);
    if (q.status == ProjectionStatus::Valid && AwayFromRim(projector, q.pixel))
    {
      out.push_back({ q.pixel, world });
    }
  }
  return out;
}

// Gaussian pixel noise, sigma per coordinate; noise longer than `clip` pixels is drawn again.
void AddNoise(std::vector<PoseObservation>& obs, double sigma, std::mt19937& rng,
  double clip = std::numeric_limits<double>::infinity())
{
  std::normal_distribution<double> g(0.0, sigma);
  for (PoseObservation& o : obs)
  {
    Vec2 e;
    do
    {
      e = Vec2(g(rng), g(rng));
    } while (e.norm() > clip);
    o.pixel += e;
  }
}

// Replaces a fraction of the pixels by random pixels on the mirror's image at least 10 px from
// the true one; returns the true inliers.
std::vector<unsigned char> AddOutliers(
  const CameraModel& camera, std::vector<PoseObservation>& obs, double fraction, std::mt19937& rng)
{
  const Projector projector(camera);
  std::vector<unsigned char> inlier(obs.size(), 1);
  const int outliers = static_cast<int>(std::lround(fraction * static_cast<double>(obs.size())));
  for (int k = 0; k < outliers; ++k)
  {
    const std::size_t i = static_cast<std::size_t>(k) * obs.size() / outliers; // spread out
    Vec2 pixel;
    do
    {
      RandomRay(projector, rng, pixel);
    } while ((pixel - obs[i].pixel).norm() < 10.0);
    obs[i].pixel = pixel;
    inlier[i] = 0;
  }
  return inlier;
}

void ExpectFinite(const PoseResult& r)
{
  EXPECT_TRUE(r.worldToCamera.allFinite());
  EXPECT_TRUE(std::isfinite(r.rmsPixels));
}

double Quantile(std::vector<double> v, double q)
{
  std::sort(v.begin(), v.end());
  return v[static_cast<std::size_t>(std::lround(q * static_cast<double>(v.size() - 1)))];
}

std::vector<PoseObservation> SomeExact(const CameraModel& camera, int n)
{
  std::mt19937 rng(99);
  return Exact(camera, TruePoses()[1], n, rng);
}

void ExpectRefused(const CameraModel& camera, const std::vector<PoseObservation>& obs,
  const std::string& words, const PoseOptions& options = {})
{
  const PoseResult r = EstimatePose(camera, obs, options);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find(words), std::string::npos) << r.error;
  ExpectFinite(r);
}
} // namespace

// Exact correspondences give the true pose to 1e-6 (m and rad), every point an inlier; so do the
// first 4 of them.
TEST(PoseEstimation, ExactCorrespondences)
{
  std::mt19937 rng(1);
  for (const Named& c : Cameras())
  {
    for (const Mat4& truePose : TruePoses())
    {
      const std::vector<PoseObservation> obs = Exact(c.camera, truePose, 50, rng);
      const PoseResult r = EstimatePose(c.camera, obs);
      ASSERT_TRUE(r.ok) << c.name << ": " << r.error;
      EXPECT_LE(PositionError(r.worldToCamera, truePose), 1e-6) << c.name;
      EXPECT_LE(RotationError(r.worldToCamera, truePose), 1e-6) << c.name;
      EXPECT_EQ(r.inlierCount, 50) << c.name;
      EXPECT_LT(r.rmsPixels, 1e-6) << c.name;
      // The fewest the solver takes: 3 points and one to choose among their poses.
      const std::vector<PoseObservation> four(obs.begin(), obs.begin() + 4);
      const PoseResult m = EstimatePose(c.camera, four);
      ASSERT_TRUE(m.ok) << c.name << ": " << m.error;
      EXPECT_LE(PositionError(m.worldToCamera, truePose), 1e-6) << c.name;
      EXPECT_LE(RotationError(m.worldToCamera, truePose), 1e-6) << c.name;
    }
  }
}

// 0.5 px Gaussian noise on 50 points ~1 m away, 200 trials per mirror: the error distribution is
// printed and its maximum bounded (5 mm, 0.5 degree).
TEST(PoseEstimation, NoiseDistribution)
{
  const int trials = 200;
  for (const Named& c : Cameras())
  {
    std::mt19937 rng(2);
    std::vector<double> mm, degrees;
    for (int trial = 0; trial < trials; ++trial)
    {
      const Mat4 truePose = TruePoses()[trial % 3];
      std::vector<PoseObservation> obs = Exact(c.camera, truePose, 50, rng);
      AddNoise(obs, 0.5, rng);
      const PoseResult r = EstimatePose(c.camera, obs);
      ASSERT_TRUE(r.ok) << c.name << ": " << r.error;
      mm.push_back(1000.0 * PositionError(r.worldToCamera, truePose));
      degrees.push_back(RotationError(r.worldToCamera, truePose) * 180.0 / kPi);
    }
    std::cout << c.name << ", 0.5 px noise, 50 points at ~1 m, " << trials
              << " trials: position error median " << Quantile(mm, 0.5) << " mm, 95% "
              << Quantile(mm, 0.95) << " mm, max " << Quantile(mm, 1.0)
              << " mm; rotation error median " << Quantile(degrees, 0.5) << " deg, 95% "
              << Quantile(degrees, 0.95) << " deg, max " << Quantile(degrees, 1.0) << " deg\n";
    EXPECT_LE(Quantile(mm, 1.0), 5.0) << c.name;
    EXPECT_LE(Quantile(degrees, 1.0), 0.5) << c.name;
  }
}

// The pose's uncertainty (PoseUncertainty.h) against the spread of poses from noisy pixels: the
// same 20 world points, new Gaussian noise (0.5 px a coordinate) each trial. The covariance the
// estimate reports (the noise estimated from the residuals, no floor) must match the empirical
// covariance of the camera centre and rotation over the trials: the one-sigma along the worst
// direction within 25 %, and the pixel noise estimated within 15 %.
TEST(PoseEstimation, UncertaintyMatchesTheSpreadOfNoisyPoses)
{
  const int trials = 150;
  for (const Named& c : Cameras())
  {
    std::mt19937 rng(5);
    const Mat4 truePose = TruePoses()[0];
    const std::vector<PoseObservation> exact = Exact(c.camera, truePose, 20, rng);
    PoseOptions options;
    options.minimumPixelSigma = 0.0;
    std::vector<Eigen::Matrix<double, 6, 1>> deviations;
    double predictedPosition = 0.0, predictedAngle = 0.0, pixelSigma = 0.0;
    for (int trial = 0; trial < trials; ++trial)
    {
      std::vector<PoseObservation> obs = exact;
      AddNoise(obs, 0.5, rng);
      const PoseResult r = EstimatePose(c.camera, obs, options);
      ASSERT_TRUE(r.ok && r.uncertainty.known) << c.name << ": " << r.error;
      // Rotation about world axes (camera to world: found = turn * true), centre shift.
      const Mat3 turn =
        r.worldToCamera.topLeftCorner<3, 3>().transpose() * truePose.topLeftCorner<3, 3>();
      const Eigen::AngleAxisd aa(turn);
      Eigen::Matrix<double, 6, 1> d;
      d << aa.angle() * aa.axis(), Centre(r.worldToCamera) - Centre(truePose);
      deviations.push_back(d);
      predictedPosition += r.uncertainty.positionSigma / trials;
      predictedAngle += r.uncertainty.angleSigmaDegrees / trials;
      pixelSigma += r.uncertainty.pixelSigma / trials;
    }
    Eigen::Matrix<double, 6, 6> empirical = Eigen::Matrix<double, 6, 6>::Zero();
    for (const auto& d : deviations)
    {
      empirical += d * d.transpose() / trials;
    }
    const auto worst = [](const Mat3& m) {
      return std::sqrt(Eigen::SelfAdjointEigenSolver<Mat3>(m).eigenvalues().maxCoeff());
    };
    const double position = worst(empirical.bottomRightCorner<3, 3>());
    const double angle = worst(empirical.topLeftCorner<3, 3>()) * 180.0 / kPi;
    std::cout << c.name << ": one sigma reported " << 1000.0 * predictedPosition << " mm, "
              << predictedAngle << " deg; over " << trials << " noisy trials " << 1000.0 * position
              << " mm, " << angle << " deg; pixel noise estimated " << pixelSigma
              << " px (true 0.5)\n";
    EXPECT_NEAR(predictedPosition / position, 1.0, 0.25) << c.name;
    EXPECT_NEAR(predictedAngle / angle, 1.0, 0.25) << c.name;
    EXPECT_NEAR(pixelSigma, 0.5, 0.075) << c.name;
  }
}

// 30 % of the pixels replaced by random pixels on the mirror's image: every outlier is rejected,
// every inlier kept, and the pose is as good as without outliers (1e-6 exact; the noisy bound
// with 0.5 px noise, clipped at 1.5 px so that no inlier is an outlier by chance).
TEST(PoseEstimation, Outliers)
{
  for (const Named& c : Cameras())
  {
    std::mt19937 rng(3);
    for (int trial = 0; trial < 20; ++trial)
    {
      const bool noisy = trial % 2 == 1;
      const Mat4 truePose = TruePoses()[trial % 3];
      std::vector<PoseObservation> obs = Exact(c.camera, truePose, 50, rng);
      if (noisy)
      {
        AddNoise(obs, 0.5, rng, 1.5);
      }
      const std::vector<unsigned char> truth = AddOutliers(c.camera, obs, 0.3, rng);
      PoseOptions options;
      options.seed = static_cast<unsigned>(trial);
      const PoseResult r = EstimatePose(c.camera, obs, options);
      ASSERT_TRUE(r.ok) << c.name << ": " << r.error;
      EXPECT_EQ(r.inliers, truth) << c.name << ", trial " << trial;
      EXPECT_EQ(r.inlierCount, 35) << c.name << ", trial " << trial;
      EXPECT_LE(PositionError(r.worldToCamera, truePose), noisy ? 5e-3 : 1e-6) << c.name;
      EXPECT_LE(RotationError(r.worldToCamera, truePose), noisy ? 0.5 * kPi / 180.0 : 1e-6)
        << c.name;
    }
  }
}

// One seed, one result: the same bits twice; without refinement the pose is still close.
TEST(PoseEstimation, SeededAndUnrefined)
{
  const CameraModel camera = catar_test::TiltedHyperboloidCameraModel();
  std::mt19937 rng(4);
  std::vector<PoseObservation> obs = Exact(camera, TruePoses()[1], 50, rng);
  AddNoise(obs, 0.5, rng, 1.5);
  AddOutliers(camera, obs, 0.3, rng);
  PoseOptions options;
  options.seed = 17;
  const PoseResult a = EstimatePose(camera, obs, options);
  const PoseResult b = EstimatePose(camera, obs, options);
  ASSERT_TRUE(a.ok) << a.error;
  EXPECT_EQ(a.worldToCamera, b.worldToCamera);
  EXPECT_EQ(a.inliers, b.inliers);
  options.refine = false;
  const PoseResult u = EstimatePose(camera, obs, options);
  ASSERT_TRUE(u.ok) << u.error;
  EXPECT_LE(PositionError(u.worldToCamera, TruePoses()[1]), 0.02);
  EXPECT_GE(u.rmsPixels, a.rmsPixels - 1e-9); // Ceres minimises what rms measures
}

// Bad input is refused with a sentence that says why, never a crash or NaN.
TEST(PoseEstimation, BadInput)
{
  const CameraModel camera = catar_test::DemoCameraModel();
  std::vector<PoseObservation> obs = SomeExact(camera, 50);

  ExpectRefused(camera, { obs.begin(), obs.begin() + 3 }, "at least 4");
  ExpectRefused(camera, {}, "at least 4");

  std::vector<PoseObservation> bad = obs;
  bad[7].world.y() = std::numeric_limits<double>::quiet_NaN();
  ExpectRefused(camera, bad, "observation 7 is not finite");
  bad = obs;
  bad[12].pixel.x() = std::numeric_limits<double>::infinity();
  ExpectRefused(camera, bad, "observation 12 is not finite");

  CameraModel invalid = camera;
  invalid.intrinsics.fx = -1.0;
  ExpectRefused(invalid, obs, "invalid camera");

  PoseOptions zero;
  zero.inlierThreshold = 0.0;
  ExpectRefused(camera, obs, "threshold", zero);

  // All but 3 pixels off the mirror's image (the image's corner).
  bad = obs;
  for (std::size_t i = 3; i < bad.size(); ++i)
  {
    bad[i].pixel = Vec2(0.0, 0.0);
  }
  ExpectRefused(camera, bad, "miss the mirror");
}

TEST(PoseEstimation, DegenerateGeometry)
{
  const CameraModel camera = catar_test::DemoCameraModel();
  const Mat4 truePose = TruePoses()[1];
  CameraModel posed = camera;
  posed.worldToCamera = truePose;
  const Projector projector(posed);
  const std::vector<PoseObservation> obs = SomeExact(camera, 2);
  // Projections of world points, kept where they have a pixel.
  const auto project = [&](const std::vector<Vec3>& points) {
    std::vector<PoseObservation> out;
    for (const Vec3& p : points)
    {
      const ProjectedPoint q = projector.ProjectWorld(p);
      if (q.status == ProjectionStatus::Valid)
      {
        out.push_back({ q.pixel, p });
      }
    }
    return out;
  };
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);

  // Collinear: 40 points on the segment between two seen points.
  std::vector<Vec3> line;
  for (int k = 0; k < 40; ++k)
  {
    line.push_back(obs[0].world + u(rng) * (obs[1].world - obs[0].world));
  }
  const std::vector<PoseObservation> collinear = project(line);
  ASSERT_GE(collinear.size(), 10u);
  ExpectRefused(camera, collinear, "collinear");

  // A tiny cluster (a 0.1 mm cube 1 m away): its rays are parallel to 0.01 degree.
  std::vector<Vec3> cluster;
  for (int k = 0; k < 40; ++k)
  {
    cluster.push_back(obs[0].world + 1e-4 * Vec3(u(rng), u(rng), u(rng)));
  }
  ExpectRefused(camera, project(cluster), "parallel");

  // Random pixels for random points: no pose explains them.
  std::vector<PoseObservation> random = SomeExact(camera, 12);
  AddOutliers(camera, random, 1.0, rng);
  ExpectRefused(camera, random, "RANSAC found no pose");
}

namespace
{
using catar_test::ProgramRun;

ProgramRun RunProgram(const std::string& arguments)
{
  return catar_test::RunProgram(CATAR_POSE_PROGRAM, arguments);
}

std::string Temp(const std::string& name)
{
  return ::testing::TempDir() + "/catar_pose_" + name;
}

void WriteCsv(const std::string& path, const std::vector<PoseObservation>& obs)
{
  std::ofstream out(path);
  out << "u,v,X,Y,Z\n# pixels and world points (m)\n\n";
  char line[256];
  for (const PoseObservation& o : obs)
  {
    std::snprintf(line, sizeof(line), "%.17g,%.17g,%.17g,%.17g,%.17g\n", o.pixel.x(), o.pixel.y(),
      o.world.x(), o.world.y(), o.world.z());
    out << line;
  }
}

// The 4x4 matrix of the program's first four lines.
bool ReadMatrix(const std::string& output, Mat4& m)
{
  std::istringstream in(output);
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < 4; ++j)
    {
      if (!(in >> m(i, j)))
      {
        return false;
      }
    }
  }
  return true;
}
} // namespace

// The program prints the true pose from a CSV of exact correspondences, and -o writes a
// calibration that loads back with that pose.
TEST(PoseProgram, PrintsAndWritesThePose)
{
  const CameraModel camera = catar_test::TiltedHyperboloidCameraModel();
  std::mt19937 rng(6);
  const Mat4 truePose = TruePoses()[2];
  const std::string calibration = Temp("camera.yaml"), csv = Temp("points.csv"),
                    written = Temp("posed.yaml");
  std::string error;
  ASSERT_TRUE(SaveCalibration(calibration, camera, error)) << error;
  WriteCsv(csv, Exact(camera, truePose, 50, rng));
  std::remove(written.c_str());

  const ProgramRun run = RunProgram("'" + calibration + "' '" + csv + "' -o '" + written + "'");
  ASSERT_EQ(run.status, 0) << run.output;
  Mat4 printed;
  ASSERT_TRUE(ReadMatrix(run.output, printed)) << run.output;
  EXPECT_LE((printed - truePose).cwiseAbs().maxCoeff(), 1e-6) << run.output;
  EXPECT_NE(run.output.find("\ninliers: 50 of 50\n"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("\nrms: "), std::string::npos) << run.output;

  CameraModel loaded;
  ASSERT_TRUE(LoadCalibration(written, loaded, error)) << error;
  EXPECT_LE((loaded.worldToCamera - truePose).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_EQ(loaded.mirror.type, camera.mirror.type);
}

TEST(PoseProgram, Errors)
{
  const CameraModel camera = catar_test::DemoCameraModel();
  const std::string calibration = Temp("demo.yaml"), csv = Temp("malformed.csv");
  std::string error;
  ASSERT_TRUE(SaveCalibration(calibration, camera, error)) << error;
  {
    std::ofstream out(csv);
    out << "u,v,X,Y,Z\n1,2,3,4,5\n# comment\n1,2,3,4,5\n1,2,three,4,5\n";
  }
  ProgramRun run = RunProgram("'" + calibration + "' '" + csv + "'");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_EQ(run.output.rfind("catadioptric-pose: ", 0), 0u) << run.output;
  EXPECT_NE(run.output.find("line 5"), std::string::npos) << run.output;

  run = RunProgram("'" + calibration + "'");
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_EQ(run.output.rfind("catadioptric-pose: ", 0), 0u) << run.output;

  run = RunProgram("'" + Temp("no-such.yaml") + "' '" + csv + "'");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_EQ(run.output.rfind("catadioptric-pose: ", 0), 0u) << run.output;

  run = RunProgram("--help");
  EXPECT_EQ(run.status, 0) << run.output;
  EXPECT_NE(run.output.find("CALIBRATION"), std::string::npos) << run.output;

  // Points from a device that never ends or a FIFO nobody writes: refused at once (it read an
  // unbounded line from /dev/zero, and blocked on the FIFO). `timeout` ends a hang as a failure.
  const std::string fifo = Temp("points.fifo");
  std::remove(fifo.c_str());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& input : { std::string("/dev/zero"), fifo })
  {
    const ProgramRun refused = catar_test::RunProgram("timeout",
      "20 '" + std::string(CATAR_POSE_PROGRAM) + "' '" + calibration + "' '" + input + "'");
    EXPECT_EQ(refused.status, 1) << input << ": " << refused.output;
    EXPECT_NE(refused.output.find("is not a regular file"), std::string::npos) << refused.output;
  }
  std::remove(fifo.c_str());
}
