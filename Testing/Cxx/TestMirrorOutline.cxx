// A spherical mirror's centre from its outline (Module/Vision/MirrorOutline.h): the closed form on
// exact and noisy outlines, detection in rendered frames, bad inputs, and the program.
#include "CalibrationIO.h"
#include "Environment.h"
#include "MirrorOutline.h"
#include "Projector.h"
#include "SphereMirror.h"
#include "TestCameras.h"

#include "TestPrograms.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

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
CameraModel WithSphere(CameraModel camera, const Vec3& centre, double radius)
{
  camera.mirror = SphereMirror{ centre, radius };
  return camera;
}

CameraModel Distorted(CameraModel camera)
{
  camera.distortion.k1 = -0.18;
  camera.distortion.k2 = 0.04;
  camera.distortion.p1 = 0.0012;
  camera.distortion.p2 = -0.0008;
  camera.distortion.k3 = 0.0;
  return camera;
}

struct Placement
{
  const char* name;
  CameraModel camera;
  Vec3 centre;
  double radius;
};

// Known spheres: centred, off-axis, near the image's edge, and with lens distortion.
std::vector<Placement> KnownSpheres()
{
  const CameraModel demo = catar_test::DemoCameraModel();
  return {
    { "centred", demo, Vec3(0.0, 0.0, 0.14), 0.05 },
    { "off-axis", demo, Vec3(0.05, -0.03, 0.2), 0.04 },
    { "near the edge", demo, Vec3(0.105, 0.06, 0.25), 0.03 },
    { "distorted, off-axis", Distorted(demo), Vec3(-0.04, 0.03, 0.18), 0.045 },
    { "distorted, near the edge", Distorted(demo), Vec3(0.1, -0.05, 0.24), 0.035 },
  };
}

bool AllInImage(const CameraModel& camera, const std::vector<Vec2>& pixels)
{
  return std::all_of(
    pixels.begin(), pixels.end(), [&](const Vec2& p) { return camera.InImage(p); });
}

// The distance from a point to the line through the origin along ray.
double DistanceToRay(const Vec3& point, const Vec3& ray)
{
  return point.cross(ray.normalized()).norm();
}

double Percentile(std::vector<double> values, double fraction)
{
  std::sort(values.begin(), values.end());
  const std::size_t k = std::min(values.size() - 1,
    static_cast<std::size_t>(std::floor(fraction * static_cast<double>(values.size() - 1) + 0.5)));
  return values[k];
}
} // namespace

// The predicted outline, checked without the cone: each pixel's camera ray touches the sphere
// (its distance from the centre is the radius), and the Projector finds the mirror just inside
// each outline pixel and misses it just outside.
TEST(MirrorOutline, PredictedOutlineTouchesTheSphere)
{
  for (const Placement& s : KnownSpheres())
  {
    SCOPED_TRACE(s.name);
    const CameraModel camera = WithSphere(s.camera, s.centre, s.radius);
    const std::vector<Vec2> outline = SphereOutline(camera, s.centre, s.radius, 360);
    ASSERT_EQ(outline.size(), 360u);
    EXPECT_TRUE(AllInImage(camera, outline));
    const Projector projector(camera);
    ASSERT_TRUE(projector.IsValid()) << projector.GetError();
    const Vec2 middle = camera.DirectionToPixel(s.centre);
    for (const Vec2& p : outline)
    {
      Vec2 xy;
      ASSERT_TRUE(camera.PixelToNormalized(p, xy));
      EXPECT_NEAR(DistanceToRay(s.centre, Vec3(xy.x(), xy.y(), 1.0)), s.radius, 1e-12);
      const Vec2 inward = (middle - p).normalized();
      EXPECT_TRUE(HasProjection(projector.BackProjectCamera(p + 0.01 * inward).status));
      EXPECT_EQ(
        projector.BackProjectCamera(p - 0.01 * inward).status, ProjectionStatus::NoReflection);
    }
  }
  // A camera inside the sphere, a bad radius or count: no outline.
  const CameraModel demo = catar_test::DemoCameraModel();
  EXPECT_TRUE(SphereOutline(demo, Vec3(0, 0, 0.04), 0.05, 100).empty());
  EXPECT_TRUE(SphereOutline(demo, Vec3(0, 0, 0.14), -0.05, 100).empty());
  EXPECT_TRUE(SphereOutline(demo, Vec3(0, 0, 0.14), 0.05, 0).empty());
}

TEST(MirrorOutline, ExactOutlineGivesTheCentre)
{
  for (const Placement& s : KnownSpheres())
  {
    SCOPED_TRACE(s.name);
    for (int count : { 5, 12, 200 })
    {
      SCOPED_TRACE(count);
      const std::vector<Vec2> outline = SphereOutline(s.camera, s.centre, s.radius, count);
      ASSERT_EQ(outline.size(), static_cast<std::size_t>(count));
      Vec3 centre;
      SphereOutlineReport report;
      std::string error;
      ASSERT_TRUE(SphereFromOutline(s.camera, s.radius, outline, centre, report, error)) << error;
      EXPECT_LE((centre - s.centre).norm(), 1e-9 * s.centre.norm())
        << centre.transpose() << " vs " << s.centre.transpose();
      EXPECT_EQ(report.pointCount, count);
      EXPECT_LT(report.rmsAngle, 1e-10);
      EXPECT_LT(report.rmsPixels, 1e-7);
      EXPECT_NEAR(report.distance, s.centre.norm(), 1e-9 * s.centre.norm());
      EXPECT_NEAR(report.halfAngle, std::asin(s.radius / s.centre.norm()), 1e-9);
    }
  }
  // Only part of the outline (a 120 degree arc) fixes it too.
  const Placement s = KnownSpheres()[1];
  std::vector<Vec2> arc = SphereOutline(s.camera, s.centre, s.radius, 300);
  arc.resize(100);
  Vec3 centre;
  SphereOutlineReport report;
  std::string error;
  ASSERT_TRUE(SphereFromOutline(s.camera, s.radius, arc, centre, report, error)) << error;
  EXPECT_LE((centre - s.centre).norm(), 1e-9 * s.centre.norm());
}

TEST(MirrorOutline, NoisyOutlineIsCloseToTheCentre)
{
  std::mt19937 rng(42);
  std::normal_distribution<double> noise(0.0, 0.3);
  for (const Placement& s : KnownSpheres())
  {
    SCOPED_TRACE(s.name);
    std::vector<double> relative, rms;
    for (int trial = 0; trial < 200; ++trial)
    {
      std::vector<Vec2> outline = SphereOutline(s.camera, s.centre, s.radius, 200);
      for (Vec2& p : outline)
      {
        p += Vec2(noise(rng), noise(rng));
      }
      Vec3 centre;
      SphereOutlineReport report;
      std::string error;
      ASSERT_TRUE(SphereFromOutline(s.camera, s.radius, outline, centre, report, error)) << error;
      relative.push_back((centre - s.centre).norm() / s.centre.norm());
      rms.push_back(report.rmsPixels);
    }
    const double median = Percentile(relative, 0.5), p95 = Percentile(relative, 0.95);
    const double worst = *std::max_element(relative.begin(), relative.end());
    std::cout << "[ outline  ] 0.3 px noise, 200 points, 200 trials, " << s.name
              << ": centre error median " << 100.0 * median << " %, 95th percentile " << 100.0 * p95
              << " %, max " << 100.0 * worst << " % of the distance (max "
              << 1e3 * worst * s.centre.norm() << " mm at " << 1e3 * s.centre.norm()
              << " mm); rms residual median " << Percentile(rms, 0.5) << " px" << std::endl;
    EXPECT_LE(worst, 0.01);
    EXPECT_GT(median, 0.0);
    // The residual is the noise across the outline (0.3 px), less the fit's three parameters.
    EXPECT_NEAR(Percentile(rms, 0.5), 0.3, 0.03);
  }
}

// The centre's reported sigma (SphereOutlineReport::centreSigma) against the spread of the
// centres over noisy trials: with independent noise on each point (0.3 px), and with noise that
// is correlated along the outline (a moving average over 7 neighbours, as profiles smoothed along
// the rim give), which independent points' sigma would understate by about 2.6 times. Also
// half the outline (a dome's limb).
TEST(MirrorOutline, CentreSigmaMatchesTheSpread)
{
  const Placement s = KnownSpheres().front();
  for (const bool correlated : { false, true })
  {
    for (const bool half : { false, true })
    {
      SCOPED_TRACE(std::string(correlated ? "correlated" : "independent") +
        (half ? ", half the outline" : ", whole outline"));
      std::mt19937 rng(correlated ? 7 : 5);
      std::normal_distribution<double> noise(0.0, correlated ? 0.3 * std::sqrt(7.0) : 0.3);
      std::vector<Vec3> centres;
      double sigmas = 0.0;
      const int trials = 300;
      for (int trial = 0; trial < trials; ++trial)
      {
        std::vector<Vec2> outline = SphereOutline(s.camera, s.centre, s.radius, 400);
        if (half)
        {
          outline.resize(outline.size() / 2);
        }
        std::vector<Vec2> raw(outline.size());
        for (Vec2& r : raw)
        {
          r = Vec2(noise(rng), noise(rng));
        }
        for (std::size_t i = 0; i < outline.size(); ++i)
        {
          Vec2 offset = Vec2::Zero();
          const int reach = correlated ? 3 : 0;
          for (int k = -reach; k <= reach; ++k)
          {
            const std::size_t j = std::clamp<std::size_t>(i + k, 0, raw.size() - 1);
            offset += raw[j] / (2.0 * reach + 1.0);
          }
          outline[i] += offset;
        }
        Vec3 centre;
        SphereOutlineReport report;
        std::string error;
        ASSERT_TRUE(SphereFromOutline(s.camera, s.radius, outline, centre, report, error)) << error;
        centres.push_back(centre);
        sigmas += report.centreSigma / trials;
      }
      Vec3 mean = Vec3::Zero();
      for (const Vec3& c : centres)
      {
        mean += c / trials;
      }
      Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
      for (const Vec3& c : centres)
      {
        covariance += (c - mean) * (c - mean).transpose() / (trials - 1);
      }
      const double spread = std::sqrt(
        Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(covariance).eigenvalues().maxCoeff());
      std::cout << "[ outline  ] " << (correlated ? "correlated" : "independent") << " noise, "
                << (half ? "half" : "whole") << " outline: reported sigma " << 1e6 * sigmas
                << " um, spread " << 1e6 * spread << " um" << std::endl;
      EXPECT_NEAR(sigmas / spread, 1.0, 0.25);
    }
  }
}

namespace
{
// The camera frame of a sphere (camera frame centre and radius; the camera's pose places it in
// the world) reflecting the procedural room as a panorama taken from the sphere's centre, the
// rest a plain backdrop (inRoom: the room itself, reflected and seen directly); RGBA8, row 0 at
// the top.
std::vector<std::uint8_t> RenderMirror(const CameraModel& camera, bool inRoom = false)
{
  const Projector projector(camera);
  EXPECT_TRUE(projector.IsValid()) << projector.GetError();
  const SphereMirror sphere = catar_test::Sphere(camera.mirror);
  const EquirectangularPanorama panorama =
    MakeRoomPanorama(RoomEnvironment(), camera.CameraToWorld(sphere.center), 512);
  PanoramaPlacement placement;
  placement.backdrop = Vec3(0.1, 0.45, 0.35);
  const int w = camera.intrinsics.width, h = camera.intrinsics.height;
  std::vector<std::uint8_t> rgba(static_cast<std::size_t>(w) * h * 4, 0);
  ImageView view;
  view.data = rgba.data();
  view.width = w;
  view.height = h;
  view.rowStride = 4 * static_cast<std::ptrdiff_t>(w);
  if (inRoom)
  {
    RenderEnvironmentRows(projector, RoomEnvironment(), 4, view, 0, h);
  }
  else
  {
    RenderPanoramaRows(projector, panorama, placement, 4, view, 0, h);
  }
  return rgba;
}

// The demo rig's small variant with its sphere moved (camera frame).
std::vector<Placement> RenderedSpheres()
{
  const CameraModel small = catar_test::SmallDemoCameraModel();
  return {
    { "demo (5 cm sphere 14 cm ahead)", small, Vec3(0.0, 0.0, 0.14), 0.05 },
    { "off-axis", small, Vec3(0.045, -0.02, 0.17), 0.05 },
    { "off-axis, distorted lens", Distorted(small), Vec3(-0.05, 0.035, 0.22), 0.05 },
    { "demo, full size (1328 x 1048)", catar_test::DemoCameraModel(), Vec3(0.0, 0.0, 0.14), 0.05 },
  };
}

// The mean (signed: positive outside) and largest distance of detected points from the true
// outline, pixels: each point's distance from the polyline of 4000 points of SphereOutline (a
// quarter of a pixel apart), its side from the angle between its ray and the sphere's centre.
void OutlineErrors(const CameraModel& camera, const Vec3& centre, double radius,
  const std::vector<Vec2>& points, double& mean, double& largest)
{
  const std::vector<Vec2> truth = SphereOutline(camera, centre, radius, 4000);
  const double alpha = std::asin(radius / centre.norm());
  mean = 0.0;
  largest = 0.0;
  for (const Vec2& p : points)
  {
    double nearest = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < truth.size(); ++k)
    {
      const Vec2 a = truth[k], b = truth[(k + 1) % truth.size()];
      const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
      nearest = std::min(nearest, (a + t * (b - a) - p).norm());
    }
    Vec2 xy;
    EXPECT_TRUE(camera.PixelToNormalized(p, xy));
    const Vec3 ray(xy.x(), xy.y(), 1.0);
    const double angle = std::atan2(ray.cross(centre).norm(), ray.dot(centre));
    mean += angle > alpha ? nearest : -nearest;
    largest = std::max(largest, nearest);
  }
  mean /= static_cast<double>(points.size());
}

// The fraction of 72 equal turns about the sphere's centre direction that hold a detected point:
// how far round the outline the points go.
double Coverage(const CameraModel& camera, const Vec3& centre, const std::vector<Vec2>& points)
{
  const Vec3 d = centre.normalized();
  const Vec3 e1 = d.unitOrthogonal(), e2 = d.cross(e1);
  std::array<bool, 72> hit{};
  for (const Vec2& p : points)
  {
    Vec2 xy;
    if (camera.PixelToNormalized(p, xy))
    {
      const Vec3 ray(xy.x(), xy.y(), 1.0);
      const double turn = std::atan2(ray.dot(e2), ray.dot(e1)) / (2.0 * 3.14159265358979323846);
      hit[static_cast<std::size_t>(std::clamp(static_cast<int>((turn + 0.5) * 72.0), 0, 71))] =
        true;
    }
  }
  return static_cast<double>(std::count(hit.begin(), hit.end(), true)) / 72.0;
}
} // namespace

TEST(MirrorOutline, RenderedMirrorGivesTheCentre)
{
  for (const Placement& s : RenderedSpheres())
  {
    SCOPED_TRACE(s.name);
    const CameraModel camera = WithSphere(s.camera, s.centre, s.radius);
    ASSERT_TRUE(AllInImage(camera, SphereOutline(camera, s.centre, s.radius, 360)));
    const std::vector<std::uint8_t> rgba = RenderMirror(camera);
    std::vector<Vec2> outline;
    std::string error;
    ASSERT_TRUE(DetectMirrorOutline(
      camera, camera.intrinsics.width, camera.intrinsics.height, rgba.data(), outline, error))
      << error;
    double bias = 0.0, largest = 0.0;
    OutlineErrors(camera, s.centre, s.radius, outline, bias, largest);
    // The detected points lie on the outline, about all the way round.
    const double perimeter = [&] {
      const std::vector<Vec2> truth = SphereOutline(camera, s.centre, s.radius, 1000);
      double length = 0.0;
      for (std::size_t k = 0; k < truth.size(); ++k)
      {
        length += (truth[(k + 1) % truth.size()] - truth[k]).norm();
      }
      return length;
    }();
    Vec3 centre;
    SphereOutlineReport report;
    ASSERT_TRUE(SphereFromOutline(camera, s.radius, outline, centre, report, error)) << error;
    const double errorMm = 1e3 * (centre - s.centre).norm();
    const double percent = 100.0 * (centre - s.centre).norm() / s.centre.norm();
    std::cout << "[ outline  ] rendered, " << s.name << ": " << outline.size()
              << " points (perimeter " << perimeter << " px), mean signed offset " << bias
              << " px, largest " << largest << " px; centre error " << errorMm << " mm (" << percent
              << " % of " << 1e3 * s.centre.norm() << " mm), rms " << report.rmsPixels << " px"
              << std::endl;
    // Measured: offsets 0.02 to 0.12 px, largest 0.48 to 0.64 px, centre errors 0.012 to 0.17 mm
    // (0.009 to 0.090 %). Points every 2 to 3 px of the outline round 71 to 100 % of it (where the
    // reflection's edges meet the rim, the points they pull off the sphere's cone are left out).
    EXPECT_GT(static_cast<double>(outline.size()), 0.25 * perimeter);
    EXPECT_GE(Coverage(camera, s.centre, outline), 0.65);
    EXPECT_LT(largest, 1.5);
    EXPECT_LT(std::abs(bias), 0.2);
    EXPECT_LT(errorMm, 0.3);
    EXPECT_LT(percent, 0.15);
    EXPECT_LT(report.rmsPixels, 0.4);
  }
}

// Against the room itself (no backdrop): the mirror's rim reflects, at grazing angles, the wall
// behind it, so that the image's boundary there is the wall against its own reflection (8 %
// darker), weaker than the reflection's first strong change of colour a few pixels inside the
// outline. The search outwards from that edge finds the rim.
TEST(MirrorOutline, RenderedMirrorInTheRoom)
{
  const Placement s = RenderedSpheres()[0];
  const CameraModel camera = WithSphere(s.camera, s.centre, s.radius);
  const std::vector<std::uint8_t> rgba = RenderMirror(camera, true);
  std::vector<Vec2> outline;
  std::string error;
  ASSERT_TRUE(DetectMirrorOutline(
    camera, camera.intrinsics.width, camera.intrinsics.height, rgba.data(), outline, error))
    << error;
  double bias = 0.0, largest = 0.0;
  OutlineErrors(camera, s.centre, s.radius, outline, bias, largest);
  Vec3 centre;
  SphereOutlineReport report;
  ASSERT_TRUE(SphereFromOutline(camera, s.radius, outline, centre, report, error)) << error;
  const double percent = 100.0 * (centre - s.centre).norm() / s.centre.norm();
  std::cout << "[ outline  ] rendered in the room, " << s.name << ": " << outline.size()
            << " points, mean signed offset " << bias << " px, largest " << largest
            << " px; centre error " << 1e3 * (centre - s.centre).norm() << " mm (" << percent
            << " %)" << std::endl;
  // Measured: 377 points, offset -0.16 px, largest 0.83 px, centre error 0.10 mm (0.073 %); the
  // strong edge alone (before the search outwards): offset -3.4 px, 2.1 mm (1.5 %).
  EXPECT_GT(outline.size(), 300u);
  EXPECT_LT(largest, 2.0);
  EXPECT_LT(std::abs(bias), 0.5);
  EXPECT_LT(percent, 0.2);
}

TEST(MirrorOutline, BadInputsAreRefused)
{
  const Placement s = KnownSpheres()[0];
  const std::vector<Vec2> outline = SphereOutline(s.camera, s.centre, s.radius, 50);
  Vec3 centre(7, 7, 7);
  SphereOutlineReport report;
  std::string error;
  const auto refused = [&](const CameraModel& camera, double radius,
                         const std::vector<Vec2>& points, const std::string& words) {
    error.clear();
    EXPECT_FALSE(SphereFromOutline(camera, radius, points, centre, report, error)) << words;
    EXPECT_NE(error.find(words), std::string::npos) << error;
    EXPECT_EQ(centre, Vec3(7, 7, 7));
  };
  refused(s.camera, 0.0, outline, "radius must be positive and finite");
  refused(s.camera, -0.05, outline, "radius must be positive and finite");
  refused(s.camera, std::numeric_limits<double>::quiet_NaN(), outline, "radius");
  refused(s.camera, std::numeric_limits<double>::infinity(), outline, "radius");
  refused(s.camera, s.radius, std::vector<Vec2>(outline.begin(), outline.begin() + 4),
    "at least 5 points");
  std::vector<Vec2> withNaN = outline;
  withNaN[3].y() = std::numeric_limits<double>::quiet_NaN();
  refused(s.camera, s.radius, withNaN, "point 3 is not finite");
  std::vector<Vec2> line;
  for (int k = 0; k < 20; ++k)
  {
    line.push_back(Vec2(100.0 + 20.0 * k, 50.0 + 10.0 * k));
  }
  refused(s.camera, s.radius, line, "collinear");
  refused(s.camera, s.radius, std::vector<Vec2>(10, Vec2(300, 200)), "coincide");
  // Five points, two of them the same: many conics pass through them.
  std::vector<Vec2> repeated(outline.begin(), outline.begin() + 5);
  repeated[4] = repeated[0];
  refused(s.camera, s.radius, repeated, "single conic");
  // Both branches of a hyperbola centred on the principal point.
  std::vector<Vec2> hyperbola;
  for (int k = -10; k <= 10; ++k)
  {
    const double t = 0.15 * k;
    hyperbola.push_back(Vec2(663.5 + 100.0 * std::cosh(t), 523.5 + 80.0 * std::sinh(t)));
    hyperbola.push_back(Vec2(663.5 - 100.0 * std::cosh(t), 523.5 + 80.0 * std::sinh(t)));
  }
  refused(s.camera, s.radius, hyperbola, "do not lie on an ellipse");
  // A circle so wide that its cone is a half-space (tan(alpha) = 1e9): the camera would be
  // inside the sphere.
  std::vector<Vec2> huge;
  for (int k = 0; k < 40; ++k)
  {
    const double t = 2.0 * 3.14159265358979323846 * k / 40.0;
    huge.push_back(Vec2(663.5 + 1e12 * std::cos(t), 523.5 + 1e12 * std::sin(t)));
  }
  refused(s.camera, s.radius, huge, "inside the");
  // A camera with an unusable lens.
  CameraModel broken = s.camera;
  broken.intrinsics.fx = -5.0;
  refused(broken, s.radius, outline, "camera is not usable");
  // A pixel beyond the reach of a strong distortion's inverse.
  CameraModel strong = s.camera;
  strong.distortion.k1 = -2.0;
  std::vector<Vec2> far = outline;
  far[0] = Vec2(1e7, 1e7);
  refused(strong, s.radius, far, "beyond the range");

  // Detection.
  const CameraModel small = catar_test::SmallDemoCameraModel();
  const int w = small.intrinsics.width, h = small.intrinsics.height;
  std::vector<Vec2> points(3, Vec2(1, 1));
  const auto notFound = [&](const CameraModel& camera, int width, int height,
                          const std::uint8_t* rgba, const std::string& words) {
    error.clear();
    EXPECT_FALSE(DetectMirrorOutline(camera, width, height, rgba, points, error)) << words;
    EXPECT_NE(error.find(words), std::string::npos) << error;
    EXPECT_TRUE(points.empty());
  };
  std::vector<std::uint8_t> blank(static_cast<std::size_t>(w) * h * 4, 200);
  notFound(small, w, h, nullptr, "empty");
  notFound(small, 0, h, blank.data(), "empty");
  notFound(small, w, h, blank.data(), "blank");
  notFound(small, w / 2, h / 2, blank.data(), "intrinsics are for 640 x 480");
  // Stripes: straight edges only, no elliptical boundary.
  std::vector<std::uint8_t> stripes = blank;
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      std::uint8_t* p = stripes.data() + 4 * (static_cast<std::size_t>(y) * w + x);
      p[0] = p[1] = p[2] = ((x / 40) % 2) ? 230 : 20;
    }
  }
  notFound(small, w, h, stripes.data(), "no mirror outline found");
  // The mirror mostly beyond the right border.
  const CameraModel cut = WithSphere(small, Vec3(0.13, 0.0, 0.17), 0.05);
  const std::vector<std::uint8_t> cutFrame = RenderMirror(cut);
  notFound(cut, w, h, cutFrame.data(), "cut by the image frame");
  // The same intrinsics without distortion (the Intrinsics overload) find a whole mirror.
  const CameraModel whole = WithSphere(small, Vec3(0.0, 0.0, 0.14), 0.05);
  const std::vector<std::uint8_t> wholeFrame = RenderMirror(whole);
  EXPECT_TRUE(DetectMirrorOutline(whole.intrinsics, w, h, wholeFrame.data(), points, error))
    << error;
  EXPECT_GT(points.size(), 300u);
  EXPECT_GE(Coverage(whole, Vec3(0.0, 0.0, 0.14), points), 0.65);
}

namespace
{
using catar_test::ProgramRun;

ProgramRun RunOutlineProgram(const std::string& arguments)
{
  return catar_test::RunProgram(CATAR_MIRROR_OUTLINE_PROGRAM, arguments);
}

std::string TempPath(const std::string& name)
{
  return ::testing::TempDir() + "/catar_outline_" + name;
}

// Writes an RGBA8 frame as a PNG (OpenCV's BGR order).
bool WritePng(const std::string& path, const std::vector<std::uint8_t>& rgba, int w, int h)
{
  cv::Mat bgr(h, w, CV_8UC3);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      const std::uint8_t* p = rgba.data() + 4 * (static_cast<std::size_t>(y) * w + x);
      bgr.at<cv::Vec3b>(y, x) = cv::Vec3b(p[2], p[1], p[0]);
    }
  }
  return cv::imwrite(path, bgr);
}
} // namespace

TEST(MirrorOutline, ProgramFindsTheCentre)
{
  const Vec3 truth(0.045, -0.02, 0.17);
  const double radius = 0.05;
  const CameraModel rendered = WithSphere(catar_test::SmallDemoCameraModel(), truth, radius);
  const int w = rendered.intrinsics.width, h = rendered.intrinsics.height;
  const std::string image = TempPath("frame.png"), calibration = TempPath("camera.yaml"),
                    written = TempPath("found.yaml"), overlay = TempPath("overlay.png");
  ASSERT_TRUE(WritePng(image, RenderMirror(rendered), w, h));
  // The calibration's own mirror is wrong: the program replaces it.
  const CameraModel given = WithSphere(rendered, Vec3(0.0, 0.0, 0.3), 0.02);
  std::string error;
  ASSERT_TRUE(SaveCalibration(calibration, given, error)) << error;
  std::remove(written.c_str());
  std::remove(overlay.c_str());

  ProgramRun run = RunOutlineProgram("'" + calibration + "' '" + image + "' --radius 0.05 -o '" +
    written + "' --overlay '" + overlay + "'");
  ASSERT_EQ(run.status, 0) << run.output;
  const std::size_t at = run.output.find("centre: ");
  ASSERT_NE(at, std::string::npos) << run.output;
  Vec3 printed;
  std::istringstream(run.output.substr(at + 8)) >> printed.x() >> printed.y() >> printed.z();
  EXPECT_LT((printed - truth).norm(), 0.5e-3) << run.output;
  EXPECT_NE(run.output.find("\noutline points: "), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("\nrms: "), std::string::npos) << run.output;
  const std::size_t sigmaAt = run.output.find("\ncentre sigma: ");
  ASSERT_NE(sigmaAt, std::string::npos) << run.output;
  double sigma = 0.0;
  std::istringstream(run.output.substr(sigmaAt + 15)) >> sigma;
  EXPECT_GT(sigma, 0.0) << run.output;
  EXPECT_LT(sigma, 0.5e-3) << run.output;

  // A centre the outline fixes less well than --max-uncertainty asks: refused, nothing written,
  // the overlay still drawn.
  {
    std::remove(written.c_str());
    std::remove(overlay.c_str());
    const ProgramRun refused = RunOutlineProgram("'" + calibration + "' '" + image +
      "' --radius 0.05 --max-uncertainty 1e-6 -o '" + written + "' --overlay '" + overlay + "'");
    EXPECT_EQ(refused.status, 1) << refused.output;
    EXPECT_NE(refused.output.find("--max-uncertainty"), std::string::npos) << refused.output;
    EXPECT_NE(::access(written.c_str(), F_OK), 0) << "a refused fit was written";
    EXPECT_EQ(::access(overlay.c_str(), F_OK), 0) << "no overlay for the refused fit";
  }
  run = RunOutlineProgram("'" + calibration + "' '" + image + "' --radius 0.05 -o '" + written +
    "' --overlay '" + overlay + "'");
  ASSERT_EQ(run.status, 0) << run.output;

  CameraModel loaded;
  ASSERT_TRUE(LoadCalibration(written, loaded, error)) << error;
  SphereMirror found;
  ASSERT_TRUE(SphereMirror::From(loaded.mirror, found)) << loaded.mirror.type;
  EXPECT_EQ(found.radius, radius);
  EXPECT_LT((found.center - printed).norm(), 1e-8);
  EXPECT_EQ(loaded.intrinsics.fx, rendered.intrinsics.fx);
  EXPECT_EQ(loaded.worldToCamera, rendered.worldToCamera);
  const cv::Mat drawn = cv::imread(overlay);
  EXPECT_EQ(drawn.cols, w);
  EXPECT_EQ(drawn.rows, h);

  // A missing image, a blank one, a missing radius.
  run = RunOutlineProgram("'" + calibration + "' '" + TempPath("no-such.png") + "' --radius 0.05");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_EQ(run.output.rfind("catadioptric-mirror-outline: ", 0), 0u) << run.output;
  EXPECT_NE(run.output.find("no-such.png"), std::string::npos) << run.output;
  const std::string blank = TempPath("blank.png");
  ASSERT_TRUE(
    WritePng(blank, std::vector<std::uint8_t>(static_cast<std::size_t>(w) * h * 4, 90), w, h));
  run = RunOutlineProgram("'" + calibration + "' '" + blank + "' --radius 0.05");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_EQ(run.output.rfind("catadioptric-mirror-outline: ", 0), 0u) << run.output;
  EXPECT_NE(run.output.find("blank"), std::string::npos) << run.output;
  run = RunOutlineProgram("'" + calibration + "' '" + image + "'");
  EXPECT_EQ(run.status, 2) << run.output;
  EXPECT_EQ(run.output.rfind("catadioptric-mirror-outline: ", 0), 0u) << run.output;
  // A calibration of the lens alone (OpenCV's of the bare camera, no mirror): read, the mirror
  // found as with the other.
  {
    const CameraModel& m = rendered;
    std::ofstream lens(TempPath("lens.yaml"));
    lens.precision(17);
    lens << "image_width: " << w << "\nimage_height: " << h << "\ncamera_matrix: [ "
         << m.intrinsics.fx << ", " << m.intrinsics.skew << ", " << m.intrinsics.cx << ", 0, "
         << m.intrinsics.fy << ", " << m.intrinsics.cy << ", 0, 0, 1 ]\n"
         << "distortion_coefficients: [ " << m.distortion.k1 << ", " << m.distortion.k2 << ", "
         << m.distortion.p1 << ", " << m.distortion.p2 << ", " << m.distortion.k3 << " ]\n";
  }
  run = RunOutlineProgram(
    "'" + TempPath("lens.yaml") + "' '" + image + "' --radius 0.05 -o '" + written + "'");
  ASSERT_EQ(run.status, 0) << run.output;
  const std::size_t lensAt = run.output.find("centre: ");
  ASSERT_NE(lensAt, std::string::npos) << run.output;
  Vec3 fromLens;
  std::istringstream(run.output.substr(lensAt + 8)) >> fromLens.x() >> fromLens.y() >> fromLens.z();
  EXPECT_LT((fromLens - printed).norm(), 1e-9) << run.output;
  ASSERT_TRUE(LoadCalibration(written, loaded, error)) << error;
  ASSERT_TRUE(SphereMirror::From(loaded.mirror, found)) << loaded.mirror.type;
  EXPECT_EQ(found.radius, radius);

  // A radius far out of scale: an error that names the radius, never "rms: -nan" and status 0.
  std::remove(written.c_str());
  run =
    RunOutlineProgram("'" + calibration + "' '" + image + "' --radius 1e200 -o '" + written + "'");
  EXPECT_EQ(run.status, 1) << run.output;
  EXPECT_EQ(run.output.find("nan"), std::string::npos) << run.output;
  EXPECT_NE(run.output.find("radius"), std::string::npos) << run.output;
  EXPECT_NE(::access(written.c_str(), F_OK), 0) << "a calibration was written";
}
