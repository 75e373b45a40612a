// Forward/back projection through a spherical mirror: accuracy on random points over several
// geometries, agreement of the two solvers, and statuses at the extremes.
#include "Polynomials.h"
#include "Projector.h"
#include "SphereMirror.h"
#include "TestCameras.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

using namespace catar;
using catar_test::Sphere;

namespace
{
struct Geometry
{
  std::string name;
  CameraModel model;
};

Mat4 PoseFromAxisAngle(const Vec3& axis, double angle, const Vec3& t)
{
  Mat4 m = Mat4::Identity();
  m.topLeftCorner<3, 3>() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  m.topRightCorner<3, 1>() = t;
  return m;
}

std::vector<Geometry> Geometries()
{
  std::vector<Geometry> g;
  {
    Geometry s{ "on-axis, no distortion", CameraModel() };
    s.model.intrinsics = Intrinsics{ 900, 900, 663.5, 523.5, 0, 1328, 1048 };
    s.model.mirror = SphereMirror{ Vec3(0, 0, 0.12), 0.05 };
    g.push_back(s);
  }
  {
    Geometry s{ "tilted mirror, distortion and skew", CameraModel() };
    s.model.intrinsics = Intrinsics{ 1100, 1050, 640.2, 470.8, 0.7, 1280, 960 };
    s.model.distortion = Distortion{ -0.21, 0.08, 0.0012, -0.0007, -0.01 };
    s.model.mirror = SphereMirror{ Vec3(0.01, -0.02, 0.2), 0.06 };
    s.model.worldToCamera = PoseFromAxisAngle(Vec3(0.3, -1, 0.2), 0.7, Vec3(0.1, -0.3, 0.5));
    g.push_back(s);
  }
  {
    Geometry s{ "camera close to the mirror (a = 1.25)", CameraModel() };
    s.model.intrinsics = Intrinsics{ 300, 300, 399.5, 299.5, 0, 800, 600 };
    s.model.mirror = SphereMirror{ Vec3(0, 0, 1.25), 1.0 };
    g.push_back(s);
  }
  {
    Geometry s{ "far small mirror (a = 25), long lens", CameraModel() };
    s.model.intrinsics = Intrinsics{ 8000, 8000, 511.5, 383.5, 0, 1024, 768 };
    s.model.mirror = SphereMirror{ Vec3(0.002, 0.001, 0.5), 0.02 };
    s.model.worldToCamera = PoseFromAxisAngle(Vec3(1, 1, 1), -2.0, Vec3(0, 0, 3));
    g.push_back(s);
  }
  return g;
}

// Angle between two unit vectors, accurate for small and large angles.
double Angle(const Vec3& u, const Vec3& v)
{
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

Vec3 RandomUnit(std::mt19937_64& rng)
{
  std::normal_distribution<double> n(0.0, 1.0);
  Vec3 v(n(rng), n(rng), n(rng));
  return v.normalized();
}

// A point at distance in [1.02 R, 60 R] from the mirror centre, in a random direction.
Vec3 RandomPointAroundMirror(const SphereMirror& m, std::mt19937_64& rng)
{
  std::uniform_real_distribution<double> logd(std::log(1.02), std::log(60.0));
  return m.center + m.radius * std::exp(logd(rng)) * RandomUnit(rng);
}
} // namespace

TEST(SphereProjection, RandomValidPointsSatisfyTheReflectionLaw)
{
  constexpr int kPoints = 100000;
  std::mt19937_64 rng(20261122);
  for (const Geometry& g : Geometries())
  {
    SCOPED_TRACE(g.name);
    const Projector proj(g.model);
    ASSERT_TRUE(proj.IsValid()) << proj.GetError();
    const Vec3 c = Sphere(g.model.mirror).center;
    const double R = Sphere(g.model.mirror).radius;
    int valid = 0;
    int attempts = 0;
    double worstSphere = 0, worstAngle = 0, worstCoplanar = 0, worstBack = 0, worstAgree = 0;
    double worstQuartic = 0;
    int quarticMisses = 0;
    while (valid < kPoints)
    {
      ASSERT_LT(++attempts, 50 * kPoints) << "too few valid points";
      const Vec3 pCam = RandomPointAroundMirror(Sphere(g.model.mirror), rng);
      const ProjectedPoint q = proj.ProjectCamera(pCam, SolverType::Quartic);
      if (q.status != ProjectionStatus::Valid)
      {
        continue;
      }
      ++valid;
      const Vec3 r = q.mirrorPoint;
      // On the sphere.
      worstSphere = std::max(worstSphere, std::abs((r - c).norm() - R) / R);
      // Reflection law: equal angles, coplanar directions.
      const Vec3 n = (r - c).normalized();
      const Vec3 toCamera = (-r).normalized();
      const Vec3 toPoint = (pCam - r).normalized();
      worstAngle = std::max(worstAngle, std::abs(Angle(toCamera, n) - Angle(toPoint, n)));
      worstCoplanar = std::max(worstCoplanar, std::abs(toCamera.cross(toPoint).dot(n)));
      EXPECT_NEAR(q.pathLength, (pCam - r).norm(), 1e-13 * (1.0 + pCam.norm()));
      // The pixel's back-projected ray passes through the point.
      const BackProjectedRay ray = proj.BackProjectCamera(q.pixel);
      ASSERT_EQ(ray.status, ProjectionStatus::Valid);
      const double dist = (pCam - ray.mirrorPoint).norm();
      worstBack = std::max(worstBack, (pCam - ray.mirrorPoint).cross(ray.direction).norm() / dist);
      EXPECT_GT((pCam - ray.mirrorPoint).dot(ray.direction), 0.0);
      // Both solvers agree.
      const ProjectedPoint it = proj.ProjectCamera(pCam, SolverType::Iterative);
      ASSERT_EQ(it.status, ProjectionStatus::Valid);
      worstAgree = std::max(worstAgree, (it.mirrorPoint - r).norm() / R);
      // The closed-form quartic root itself (before Newton polish) lands next to the answer.
      const Vec3 A = -c / R;
      const Vec3 B = (pCam - c) / R;
      const Vec3 e1 = A.normalized();
      const double bx = B.dot(e1);
      const double by = (B - bx * e1).norm();
      const double beta = std::atan2(by, bx);
      const double lo = std::max({ -std::acos(1 / A.norm()), beta - std::acos(1 / B.norm()), 0.0 });
      const double hi = std::min({ std::acos(1 / A.norm()), beta });
      double theta = 0;
      if (!detail::QuarticReflectionAngle(A.norm(), bx, by, lo, hi, theta))
      {
        ++quarticMisses;
      }
      else
      {
        worstQuartic = std::max(worstQuartic, std::abs(theta - Angle(e1, n)));
      }
      // World-frame entry points agree with the camera-frame ones.
      if (valid % 100 == 0)
      {
        const ProjectedPoint w = proj.ProjectWorld(g.model.CameraToWorld(pCam));
        EXPECT_LE((w.pixel - q.pixel).norm(), 1e-6);
      }
    }
    EXPECT_EQ(quarticMisses, 0);
    EXPECT_LE(worstQuartic, 1e-6);
    EXPECT_LE(worstSphere, 1e-12);
    EXPECT_LE(worstAngle, 1e-10);
    EXPECT_LE(worstCoplanar, 1e-10);
    EXPECT_LE(worstBack, 1e-9);
    EXPECT_LE(worstAgree, 1e-10);
    std::printf("[%s] %d valid of %d: sphere %.2e, angle %.2e rad, coplanar %.2e, back %.2e, "
                "solvers %.2e, unpolished quartic %.2e rad\n",
      g.name.c_str(), valid, attempts, worstSphere, worstAngle, worstCoplanar, worstBack,
      worstAgree, worstQuartic);
  }
}

TEST(SphereProjection, StartingNearbyGivesTheSameAnswer)
{
  // ProjectWorldNear: a guess next to the answer, far from it, on the far side of the mirror,
  // at the centre or NaN changes the work, never the result or the status.
  std::mt19937_64 rng(99);
  for (const Geometry& g : Geometries())
  {
    SCOPED_TRACE(g.name);
    const Projector proj(g.model);
    const Vec3 c = Sphere(g.model.mirror).center;
    const double R = Sphere(g.model.mirror).radius;
    double worst = 0.0;
    int valid = 0;
    for (int i = 0; i < 20000; ++i)
    {
      std::uniform_real_distribution<double> logd(std::log(0.5), std::log(200.0));
      const Vec3 pCam = c + R * std::exp(logd(rng)) * RandomUnit(rng);
      const Vec3 pWorld = g.model.CameraToWorld(pCam);
      const ProjectedPoint ref = proj.ProjectWorld(pWorld, SolverType::Iterative);
      const Vec3 nearby =
        proj.ProjectWorld(g.model.CameraToWorld(pCam + 1e-3 * R * RandomUnit(rng))).mirrorPoint;
      const Vec3 antipode = 2.0 * c - ref.mirrorPoint;
      const Vec3 guesses[] = { nearby, ref.mirrorPoint, c + R * RandomUnit(rng), antipode, c,
        Vec3::Constant(std::numeric_limits<double>::quiet_NaN()) };
      for (const Vec3& guess : guesses)
      {
        const ProjectedPoint q = proj.ProjectWorldNear(pWorld, guess);
        ASSERT_EQ(q.status, ref.status);
        ASSERT_TRUE(q.mirrorPoint.allFinite() && q.pixel.allFinite());
        worst = std::max(worst, (q.mirrorPoint - ref.mirrorPoint).norm() / R);
      }
      valid += HasProjection(ref.status);
    }
    EXPECT_GT(valid, 1000);
    EXPECT_LE(worst, 1e-12);
    std::printf(
      "[%s] started nearby or anywhere: worst difference %.2e R\n", g.name.c_str(), worst);
  }
}

TEST(SphereProjection, ManyPointsAtOnceGiveWhatOneAtATimeGives)
{
  // ProjectWorldNear(n, ...) solves points side by side; each result must be bit for bit the
  // one-point call's, whatever mix of points (inside the mirror, touching it, on the axis, hidden,
  // far) and guesses (close, anywhere, NaN) a batch holds, and for any batch length.
  std::mt19937_64 rng(5);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  for (const Geometry& g : Geometries())
  {
    SCOPED_TRACE(g.name);
    const Projector proj(g.model);
    const Vec3 c = Sphere(g.model.mirror).center;
    const double R = Sphere(g.model.mirror).radius;
    std::vector<Vec3> points, guesses;
    std::uniform_int_distribution<int> kind(0, 9);
    std::uniform_real_distribution<double> logd(std::log(0.5), std::log(200.0));
    for (int i = 0; i < 5000; ++i)
    {
      Vec3 pCam = c + R * std::exp(logd(rng)) * RandomUnit(rng);
      const int k = kind(rng);
      if (k == 0)
      {
        pCam = c + 0.5 * R * RandomUnit(rng); // inside the mirror
      }
      else if (k == 1)
      {
        pCam = c + R * RandomUnit(rng); // on it
      }
      else if (k == 2)
      {
        pCam = c * (1.0 + std::exp(logd(rng)) * R / c.norm()); // on the camera-mirror axis
      }
      const Vec3 pWorld = g.model.CameraToWorld(pCam);
      const Vec3 answer = proj.ProjectWorld(pWorld, SolverType::Iterative).mirrorPoint;
      Vec3 guess =
        proj.ProjectWorld(g.model.CameraToWorld(pCam + 1e-3 * R * RandomUnit(rng))).mirrorPoint;
      if (k == 3)
      {
        guess = c + R * RandomUnit(rng);
      }
      else if (k == 4)
      {
        guess = Vec3(nan, 0, 0);
      }
      else if (k == 5)
      {
        guess = 2.0 * c - answer;
      }
      points.push_back(k == 6 && i % 7 == 0 ? Vec3(nan, nan, nan) : pWorld);
      guesses.push_back(guess);
    }
    int valid = 0;
    for (const std::size_t length :
      { std::size_t(1), std::size_t(5), std::size_t(8), std::size_t(13), points.size() })
    {
      std::vector<ProjectedPoint> out(points.size());
      for (std::size_t first = 0; first < points.size(); first += length)
      {
        const std::size_t n = std::min(length, points.size() - first);
        proj.ProjectWorldNear(n, points.data() + first, guesses.data() + first, out.data() + first);
      }
      for (std::size_t i = 0; i < points.size(); ++i)
      {
        const ProjectedPoint one = proj.ProjectWorldNear(points[i], guesses[i]);
        ASSERT_EQ(out[i].status, one.status) << i;
        ASSERT_EQ(out[i].mirrorPoint, one.mirrorPoint) << i;
        ASSERT_EQ(out[i].pixel, one.pixel) << i;
        ASSERT_EQ(out[i].pathLength, one.pathLength) << i;
        valid += HasProjection(one.status);
      }
      // Without pixels: the same reflection points, path lengths and whether there is one.
      proj.ProjectWorldNear(points.size(), points.data(), guesses.data(), out.data(), false);
      for (std::size_t i = 0; i < points.size(); ++i)
      {
        const ProjectedPoint one = proj.ProjectWorldNear(points[i], guesses[i]);
        ASSERT_EQ(HasProjection(out[i].status), HasProjection(one.status)) << i;
        ASSERT_EQ(out[i].mirrorPoint, one.mirrorPoint) << i;
        ASSERT_EQ(out[i].pathLength, one.pathLength) << i;
      }
    }
    EXPECT_GT(valid, 1000);
  }
}

TEST(SphereProjection, StatusesAreConsistentAndNeverNaN)
{
  // Every random point, valid or not, gets a status; non-projections carry zeros.
  std::mt19937_64 rng(7);
  for (const Geometry& g : Geometries())
  {
    const Projector proj(g.model);
    for (int i = 0; i < 20000; ++i)
    {
      std::uniform_real_distribution<double> logd(std::log(0.2), std::log(1e6));
      const Vec3 p = Sphere(g.model.mirror).center +
        Sphere(g.model.mirror).radius * std::exp(logd(rng)) * RandomUnit(rng);
      for (SolverType s : { SolverType::Quartic, SolverType::Iterative })
      {
        const ProjectedPoint q = proj.ProjectCamera(p, s);
        ASSERT_TRUE(
          q.pixel.allFinite() && q.mirrorPoint.allFinite() && std::isfinite(q.pathLength));
        if (!HasProjection(q.status))
        {
          EXPECT_EQ(q.mirrorPoint, Vec3::Zero());
          EXPECT_EQ(q.pixel, Vec2::Zero());
        }
        const double d = (p - Sphere(g.model.mirror).center).norm() / Sphere(g.model.mirror).radius;
        if (d < 1.0 - 1e-9)
        {
          EXPECT_EQ(q.status, ProjectionStatus::InsideMirror);
        }
      }
      // Both solvers agree on the status.
      EXPECT_EQ(proj.ProjectCamera(p, SolverType::Quartic).status,
        proj.ProjectCamera(p, SolverType::Iterative).status);
    }
  }
}

class Extremes : public ::testing::TestWithParam<SolverType>
{
protected:
  CameraModel Model;
  void SetUp() override
  {
    this->Model.intrinsics = Intrinsics{ 900, 900, 663.5, 523.5, 0, 1328, 1048 };
    this->Model.mirror = SphereMirror{ Vec3(0, 0, 0.12), 0.05 };
  }
};

TEST_P(Extremes, OnTheCameraMirrorAxis)
{
  const Projector proj(this->Model);
  const Vec3 axis = Vec3::UnitZ();
  const Vec3 vertex(0, 0, 0.07);
  for (double z : { -10.0, -0.3, 0.0, 0.03, 0.0699 })
  {
    const ProjectedPoint q = proj.ProjectCamera(z * axis, GetParam());
    ASSERT_EQ(q.status, ProjectionStatus::Valid) << z;
    EXPECT_LE((q.mirrorPoint - vertex).norm(), 1e-15);
    EXPECT_NEAR(q.pixel.x(), 663.5, 1e-9);
    EXPECT_NEAR(q.pixel.y(), 523.5, 1e-9);
  }
  // Behind the mirror on the axis: hidden.
  for (double z : { 0.1701, 0.5, 1e3 })
  {
    EXPECT_EQ(proj.ProjectCamera(z * axis, GetParam()).status, ProjectionStatus::HiddenByMirror);
  }
  // Just off the axis: continuous.
  const ProjectedPoint q = proj.ProjectCamera(Vec3(1e-13, 0, -0.2), GetParam());
  ASSERT_EQ(q.status, ProjectionStatus::Valid);
  EXPECT_LE((q.mirrorPoint - vertex).norm(), 1e-12);
}

TEST_P(Extremes, TouchingTheMirror)
{
  const Projector proj(this->Model);
  const Vec3 c = Sphere(this->Model.mirror).center;
  const double R = Sphere(this->Model.mirror).radius;
  // A point on the visible side is its own reflection.
  const Vec3 onFront = c + R * Vec3(0.3, -0.2, -1).normalized();
  ProjectedPoint q = proj.ProjectCamera(onFront, GetParam());
  ASSERT_EQ(q.status, ProjectionStatus::Valid);
  EXPECT_LE((q.mirrorPoint - onFront).norm(), 1e-15);
  EXPECT_LE(q.pathLength, 1e-15);
  // A point on the far side is hidden.
  EXPECT_EQ(proj.ProjectCamera(c + R * Vec3(0.3, -0.2, 1).normalized(), GetParam()).status,
    ProjectionStatus::HiddenByMirror);
  // Just off the visible surface: reflection point next to the point.
  const Vec3 near = c + R * (1 + 1e-9) * Vec3(0.3, -0.2, -1).normalized();
  q = proj.ProjectCamera(near, GetParam());
  ASSERT_EQ(q.status, ProjectionStatus::Valid);
  EXPECT_LE((q.mirrorPoint - near).norm(), 1e-8 * R);
}

TEST_P(Extremes, MillionRadiiAway)
{
  const Projector proj(this->Model);
  const Vec3 c = Sphere(this->Model.mirror).center;
  const double R = Sphere(this->Model.mirror).radius;
  std::mt19937_64 rng(3);
  int valid = 0;
  int hidden = 0;
  for (int i = 0; i < 2000; ++i)
  {
    const Vec3 p = c + 1e6 * R * RandomUnit(rng);
    const ProjectedPoint q = proj.ProjectCamera(p, GetParam());
    ASSERT_TRUE(q.pixel.allFinite() && q.mirrorPoint.allFinite());
    if (HasProjection(q.status))
    {
      ++valid;
      const Vec3 n = (q.mirrorPoint - c).normalized();
      const Vec3 toCamera = (-q.mirrorPoint).normalized();
      const Vec3 toPoint = (p - q.mirrorPoint).normalized();
      EXPECT_LE(std::abs(Angle(toCamera, n) - Angle(toPoint, n)), 1e-10);
    }
    else
    {
      EXPECT_TRUE(
        q.status == ProjectionStatus::HiddenByMirror || q.status == ProjectionStatus::NoReflection)
        << ToString(q.status);
      hidden += q.status == ProjectionStatus::HiddenByMirror;
    }
  }
  // Far away, the mirror reflects almost every direction.
  EXPECT_GT(valid, 1800);
  EXPECT_GT(hidden, 0);
}

TEST_P(Extremes, InsideTheSphere)
{
  const Projector proj(this->Model);
  const Vec3 c = Sphere(this->Model.mirror).center;
  const double R = Sphere(this->Model.mirror).radius;
  const std::vector<Vec3> points = { c, c + 0.5 * R * Vec3::UnitX(),
    c + (1 - 1e-9) * R * Vec3(1, 1, -1).normalized() };
  for (const Vec3& p : points)
  {
    const ProjectedPoint q = proj.ProjectCamera(p, GetParam());
    EXPECT_EQ(q.status, ProjectionStatus::InsideMirror);
    EXPECT_EQ(q.mirrorPoint, Vec3::Zero());
  }
}

TEST_P(Extremes, BehindTheMirror)
{
  const Projector proj(this->Model);
  const Vec3 c = Sphere(this->Model.mirror).center;
  const double R = Sphere(this->Model.mirror).radius;
  // In the shadow cone behind the sphere (as seen from the camera side).
  const std::vector<Vec3> points = { c + Vec3(0, 0, 2 * R), c + Vec3(0.2 * R, -0.1 * R, 5 * R),
    c + Vec3(0, 0, 1.0001 * R) };
  for (const Vec3& p : points)
  {
    EXPECT_EQ(proj.ProjectCamera(p, GetParam()).status, ProjectionStatus::HiddenByMirror);
  }
}

TEST_P(Extremes, GrazingReflection)
{
  const Projector proj(this->Model);
  const Vec3 c = Sphere(this->Model.mirror).center;
  const double R = Sphere(this->Model.mirror).radius;
  // Build mirror points whose camera ray meets the sphere at incidence cosine `cosInc`,
  // reflect, and put the point along the reflected ray.
  for (double cosInc : { 1e-2, 1e-4, 1e-6 })
  {
    // In the x-z plane: the camera ray direction d makes angle (pi/2 - asin...) with the normal.
    // Find the ray through the origin that hits the sphere with the requested incidence.
    const double a = c.norm() / R;
    // Sine of the angle between the ray and the axis: a * sin(gamma) = cos(theta_inc) relation:
    // the distance from the centre to the ray is R sin(inc), and equals |c| sin(gamma).
    const double sinInc = std::sqrt(1 - cosInc * cosInc);
    const double gamma = std::asin(sinInc / a);
    const Vec3 d(std::sin(gamma), 0, std::cos(gamma));
    const double dc = d.dot(c);
    const double s = dc - std::sqrt(dc * dc - c.squaredNorm() + R * R);
    const Vec3 r = s * d;
    const Vec3 n = (r - c) / R;
    ASSERT_NEAR(-d.dot(n), cosInc, 1e-9);
    const Vec3 refl = d - 2 * d.dot(n) * n;
    const Vec3 p = r + 3 * R * refl;
    const ProjectedPoint q = proj.ProjectCamera(p, GetParam());
    ASSERT_EQ(q.status, ProjectionStatus::Valid) << cosInc;
    EXPECT_LE((q.mirrorPoint - r).norm(), 1e-6 * R) << cosInc;
  }
  // Exactly tangent: the reflection degenerates; a status, not a NaN.
  const double a = c.norm() / R;
  const double gamma = std::asin(1.0 / a);
  const Vec3 d(std::sin(gamma), 0, std::cos(gamma));
  const Vec3 r = d * std::sqrt(c.squaredNorm() - R * R);
  const ProjectedPoint q = proj.ProjectCamera(r + 2 * R * d, GetParam());
  EXPECT_TRUE(
    q.status == ProjectionStatus::NoReflection || q.status == ProjectionStatus::HiddenByMirror)
    << ToString(q.status);
  EXPECT_TRUE(q.mirrorPoint.allFinite() && q.pixel.allFinite());
}

TEST_P(Extremes, InvalidInput)
{
  const Projector proj(this->Model);
  const double nan = std::nan("");
  const double inf = std::numeric_limits<double>::infinity();
  const std::vector<Vec3> points = { Vec3(nan, 0, 0), Vec3(0, inf, 1), Vec3(0, 0, -inf) };
  for (const Vec3& p : points)
  {
    const ProjectedPoint q = proj.ProjectWorld(p, GetParam());
    EXPECT_EQ(q.status, ProjectionStatus::InvalidInput);
    EXPECT_TRUE(q.pixel.allFinite() && q.mirrorPoint.allFinite() && std::isfinite(q.pathLength));
  }
  // An invalid camera (centre inside the sphere) makes every result invalid.
  CameraModel bad = this->Model;
  bad.mirror = SphereMirror{ Vec3(0, 0, 0.01), Sphere(bad.mirror).radius };
  const Projector badProj(bad);
  EXPECT_FALSE(badProj.IsValid());
  EXPECT_FALSE(badProj.GetError().empty());
  EXPECT_EQ(
    badProj.ProjectCamera(Vec3(0.3, 0, 0), GetParam()).status, ProjectionStatus::InvalidInput);
  EXPECT_EQ(badProj.BackProjectCamera(Vec2(10, 10)).status, ProjectionStatus::InvalidInput);
}

TEST_P(Extremes, OutsideTheImage)
{
  // A narrow image sees only the middle of the mirror; points reflected near the rim fall off it.
  CameraModel m = this->Model;
  m.intrinsics.width = 100;
  m.intrinsics.height = 80;
  m.intrinsics.cx = 49.5;
  m.intrinsics.cy = 39.5;
  const Projector proj(m);
  const ProjectedPoint q = proj.ProjectCamera(Vec3(0.5, 0, 0.12), GetParam());
  ASSERT_EQ(q.status, ProjectionStatus::OutsideImage);
  EXPECT_FALSE(m.InImage(q.pixel));
  EXPECT_TRUE(q.pixel.allFinite());
}

INSTANTIATE_TEST_SUITE_P(BothSolvers, Extremes,
  ::testing::Values(SolverType::Quartic, SolverType::Iterative),
  [](const ::testing::TestParamInfo<SolverType>& info) {
    return info.param == SolverType::Quartic ? std::string("Quartic") : std::string("Iterative");
  });

TEST(SphereProjection, BackProjectionMissesAndHits)
{
  CameraModel m;
  m.intrinsics = Intrinsics{ 900, 900, 663.5, 523.5, 0, 1328, 1048 };
  m.mirror = SphereMirror{ Vec3(0, 0, 0.12), 0.05 };
  const Projector proj(m);
  // The principal point looks at the mirror vertex and reflects straight back.
  BackProjectedRay ray = proj.BackProjectCamera(Vec2(663.5, 523.5));
  ASSERT_EQ(ray.status, ProjectionStatus::Valid);
  EXPECT_LE((ray.mirrorPoint - Vec3(0, 0, 0.07)).norm(), 1e-15);
  EXPECT_LE((ray.direction - Vec3(0, 0, -1)).norm(), 1e-15);
  // A corner pixel misses the mirror (angular radius of the mirror is asin(5/12)).
  ray = proj.BackProjectCamera(Vec2(0, 0));
  EXPECT_EQ(ray.status, ProjectionStatus::NoReflection);
  EXPECT_TRUE(ray.direction.allFinite());
}

TEST(QuarticSolver, RecoversKnownRoots)
{
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-3, 3);
  for (int i = 0; i < 20000; ++i)
  {
    double r[4] = { u(rng), u(rng), u(rng), u(rng) };
    const double lead = std::exp(u(rng));
    // Expand lead (x-r0)(x-r1)(x-r2)(x-r3).
    double c[5] = { lead, 0, 0, 0, 0 };
    for (int k = 0; k < 4; ++k)
    {
      for (int j = k + 1; j >= 1; --j)
      {
        c[j] -= r[k] * c[j - 1];
      }
    }
    double found[4];
    const int n = detail::SolveQuartic(c[0], c[1], c[2], c[3], c[4], found);
    // Well-separated roots must all be found to good accuracy.
    std::sort(r, r + 4);
    double minGap = 1e9;
    for (int k = 0; k < 3; ++k)
    {
      minGap = std::min(minGap, r[k + 1] - r[k]);
    }
    if (minGap < 0.05)
    {
      continue;
    }
    ASSERT_EQ(n, 4) << i;
    std::sort(found, found + 4);
    for (int k = 0; k < 4; ++k)
    {
      EXPECT_NEAR(found[k], r[k], 1e-9 * (1 + std::abs(r[k]))) << i;
    }
  }
}

TEST(QuarticSolver, DegreeReductionAndNoRealRoots)
{
  double roots[4];
  // x^2 + 1 = 0 as a "quartic" with zero leading terms: no real roots.
  EXPECT_EQ(detail::SolveQuartic(0, 0, 1, 0, 1, roots), 0);
  // (x^2+1)(x^2+4): no real roots.
  EXPECT_EQ(detail::SolveQuartic(1, 0, 5, 0, 4, roots), 0);
  // Cubic (x-1)(x-2)(x+3) = x^3 - 7x + 6.
  const int n = detail::SolveQuartic(0, 1, 0, -7, 6, roots);
  ASSERT_EQ(n, 3);
  std::sort(roots, roots + 3);
  EXPECT_NEAR(roots[0], -3, 1e-12);
  EXPECT_NEAR(roots[1], 1, 1e-12);
  EXPECT_NEAR(roots[2], 2, 1e-12);
}
