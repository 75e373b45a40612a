// Quadric mirrors (Module/Mirror/QuadricMirror.h) against independent oracles: the surface's
// equation, the law of reflection, back projection, the closed-form sphere, the hyperboloid's foci.
#include "CalibrationIO.h"
#include "Mirror.h"
#include "Projector.h"
#include "QuadricMirror.h"
#include "SceneDescription.h"
#include "SphereMirror.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <random>
#include <string>
#include <utility>
#include <vector>

using namespace catar;

namespace
{
constexpr double kPi = 3.14159265358979323846;

Mat4 Placement(double tiltDegrees, const Vec3& t)
{
  Mat4 h = Mat4::Identity();
  h.topLeftCorner<3, 3>() =
    Eigen::AngleAxisd(tiltDegrees * kPi / 180.0, Vec3(1.0, 0.3, 0.0).normalized())
      .toRotationMatrix();
  h.topRightCorner<3, 1>() = t;
  return h;
}

std::vector<double> Tail(const Mat4& h, double zmin, double zmax)
{
  std::vector<double> v;
  for (int r = 0; r < 4; ++r)
  {
    for (int c = 0; c < 4; ++c)
    {
      v.push_back(h(r, c));
    }
  }
  v.push_back(zmin);
  v.push_back(zmax);
  return v;
}

MirrorDescription Shape(
  const std::string& type, std::vector<double> shape, const Mat4& h, double zmin, double zmax)
{
  const std::vector<double> tail = Tail(h, zmin, zmax);
  shape.insert(shape.end(), tail.begin(), tail.end());
  return MirrorDescription(type, shape);
}

CameraModel Camera(const MirrorDescription& mirror)
{
  CameraModel m;
  m.intrinsics = Intrinsics{ 400.0, 400.0, 399.5, 399.5, 0.0, 800, 800 };
  m.mirror = mirror;
  return m;
}

struct Case
{
  std::string name;
  MirrorDescription mirror;
};

// Each shape axial, tilted a few degrees and off the camera's axis.
std::vector<Case> Cases()
{
  const double c = std::sqrt(0.02 * 0.02 + 0.03 * 0.03);
  std::vector<Case> cases;
  struct Placed
  {
    const char* name;
    double tilt;
    Vec3 shift;
  };
  const Placed placements[] = { { "axial", 0.0, Vec3::Zero() }, { "tilted", 4.0, Vec3::Zero() },
    { "off-axis", 0.0, Vec3(0.012, -0.007, 0.0) } };
  for (const Placed& p : placements)
  {
    const std::string suffix = std::string(" ") + p.name;
    cases.push_back({ "hyperboloid" + suffix,
      Shape(
        "hyperboloid", { 0.02, 0.03 }, Placement(p.tilt, Vec3(0, 0, c) + p.shift), 0.02, 0.05) });
    cases.push_back({ "paraboloid" + suffix,
      Shape("paraboloid", { 0.01 }, Placement(p.tilt, Vec3(0, 0, 0.1) + p.shift), -0.01, 0.02) });
    cases.push_back({ "ellipsoid" + suffix,
      Shape("ellipsoid", { 0.03, 0.035, 0.02 }, Placement(p.tilt, Vec3(0, 0, 0.15) + p.shift),
        -0.02, 0.01) });
    cases.push_back({ "cone" + suffix,
      Shape("cone", { 35.0 }, Placement(p.tilt, Vec3(0, 0, 0.1) + p.shift), 0.002, 0.04) });
    Mat4 sphere = Mat4::Identity();
    sphere(3, 3) = -0.05 * 0.05;
    std::vector<double> omega(sphere.data(), sphere.data() + 16);
    cases.push_back({ "cut sphere" + suffix,
      Shape("sphere", { 0.05 }, Placement(p.tilt, Vec3(0, 0, 0.2) + p.shift), -0.05, 0.01) });
    cases.push_back({ "quadric sphere" + suffix,
      Shape("quadric", omega, Placement(p.tilt, Vec3(0, 0, 0.2) + p.shift), -0.05, 0.05) });
  }
  return cases;
}

// The mirror-frame quadric of a description: Omega and the camera-to-mirror transform.
void MirrorFrame(const MirrorDescription& d, Mat4& omega, Mat4& cameraToMirror)
{
  QuadricGeometry g;
  ASSERT_TRUE(QuadricFromDescription(d, g));
  omega = g.omega;
  cameraToMirror = g.mirrorToCamera.inverse();
}
} // namespace

TEST(QuadricMirror, EveryPlacementIsValid)
{
  for (const Case& c : Cases())
  {
    EXPECT_EQ(ValidateMirror(c.mirror), "") << c.name;
    EXPECT_EQ(Camera(c.mirror).Validate(), "") << c.name;
  }
}

// Points on back-projected rays have a reflection; the forward projection finds one that lies on
// the quadric, obeys the law of reflection and back-projects through the point.
TEST(QuadricMirror, ReflectionLawOnEveryShapeAndPlacement)
{
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> pixel(0.0, 799.0);
  std::uniform_real_distribution<double> distance(0.01, 3.0);
  for (const Case& c : Cases())
  {
    SCOPED_TRACE(c.name);
    const CameraModel model = Camera(c.mirror);
    const Projector projector(model);
    ASSERT_TRUE(projector.IsValid()) << projector.GetError();
    Mat4 omega = Mat4::Zero(), toMirror = Mat4::Identity();
    MirrorFrame(c.mirror, omega, toMirror);
    int valid = 0, tried = 0;
    double worstSurface = 0.0, worstAngle = 0.0, worstPlane = 0.0, worstBack = 0.0;
    for (int k = 0; k < 4000000 && tried < 100000; ++k)
    {
      const BackProjectedRay ray = projector.BackProjectCamera(Vec2(pixel(rng), pixel(rng)));
      if (!HasProjection(ray.status))
      {
        continue;
      }
      const Vec3 P = ray.mirrorPoint + distance(rng) * ray.direction;
      ++tried;
      const ProjectedPoint q = projector.ProjectCamera(P);
      if (!HasProjection(q.status))
      {
        continue; // hidden by the mirror itself on the way (checked below by the tracer's test)
      }
      ++valid;
      const Vec3& r = q.mirrorPoint;
      const Eigen::Vector4d X = toMirror * Eigen::Vector4d(r.x(), r.y(), r.z(), 1.0);
      const Eigen::Vector4d gradient = 2.0 * omega * X;
      worstSurface = std::max(worstSurface,
        std::abs(X.dot(omega * X)) / (gradient.head<3>().norm() * X.head<3>().norm()));
      // The normal in the camera frame: the mirror-frame gradient rotated.
      const Vec3 n = (toMirror.topLeftCorner<3, 3>().transpose() * gradient.head<3>()).normalized();
      const Vec3 u1 = -r.normalized();
      const Vec3 u2 = (P - r).normalized();
      const double a1 = std::acos(std::min(1.0, std::abs(n.dot(u1))));
      const double a2 = std::acos(std::min(1.0, std::abs(n.dot(u2))));
      worstAngle = std::max(worstAngle, std::abs(a1 - a2));
      worstPlane = std::max(worstPlane, std::abs(n.dot(u1.cross(u2))));
      const BackProjectedRay back = projector.BackProjectCamera(q.pixel);
      ASSERT_TRUE(HasProjection(back.status));
      const Vec3 w = P - back.mirrorPoint;
      worstBack = std::max(worstBack,
        (w - w.dot(back.direction) * back.direction).norm() / std::max(w.norm(), 1e-300));
    }
    std::cout << "[ quadric  ] " << c.name << ": " << valid << " of " << tried
              << " projected; worst: on the quadric " << worstSurface << ", angles " << worstAngle
              << " rad, coplanarity " << worstPlane << ", back projection " << worstBack
              << std::endl;
    EXPECT_EQ(tried, 100000);
    EXPECT_GT(valid, 0.95 * tried) << valid << " of " << tried;
    EXPECT_LE(worstSurface, 1e-12);
    EXPECT_LE(worstAngle, 1e-10);
    EXPECT_LE(worstPlane, 1e-10);
    EXPECT_LE(worstBack, 1e-9);
  }
}

// Axial placements have two independent solvers: the planar reduction (all roots of the
// reflection equation along the camera ray's elevation, bracketed; the quartic solver's choice)
// and Newton on the Lagrange system (the iterative solver's). They find the same reflections.
TEST(QuadricMirror, AxialPlanarReductionAgreesWithNewton)
{
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> pixel(0.0, 799.0);
  std::uniform_real_distribution<double> distance(0.01, 3.0);
  for (const Case& c : Cases())
  {
    // The cases' ellipsoid has unequal x and y axes: no surface of revolution.
    if (c.name.find(" axial") == std::string::npos || c.name.find("ellipsoid") == 0)
    {
      const Projector other(Camera(c.mirror));
      const auto* surface = dynamic_cast<const detail::QuadricSurface*>(other.GetMirror());
      ASSERT_NE(surface, nullptr);
      EXPECT_FALSE(surface->IsAxial()) << c.name;
      continue;
    }
    SCOPED_TRACE(c.name);
    const Projector projector(Camera(c.mirror));
    const auto* surface = dynamic_cast<const detail::QuadricSurface*>(projector.GetMirror());
    ASSERT_NE(surface, nullptr);
    ASSERT_TRUE(surface->IsAxial());
    int both = 0, tried = 0;
    double worst = 0.0;
    for (int k = 0; k < 200000 && tried < 3000; ++k)
    {
      const BackProjectedRay ray = projector.BackProjectCamera(Vec2(pixel(rng), pixel(rng)));
      if (!HasProjection(ray.status))
      {
        continue;
      }
      ++tried;
      const Vec3 P = ray.mirrorPoint + distance(rng) * ray.direction;
      Vec3 planar = Vec3::Zero();
      ProjectionStatus planarStatus = ProjectionStatus::NoReflection;
      const bool answered = surface->AxialReflect(P, planar, planarStatus);
      const ProjectedPoint newton = projector.ProjectCamera(P, SolverType::Iterative);
      if (newton.status == ProjectionStatus::Valid ||
        newton.status == ProjectionStatus::OutsideImage)
      {
        ASSERT_TRUE(answered) << k;
        ASSERT_EQ(planarStatus, ProjectionStatus::Valid) << k;
        ++both;
        worst = std::max(worst, (planar - newton.mirrorPoint).norm());
      }
    }
    EXPECT_GT(both, 0.95 * tried);
    EXPECT_LE(worst, 1e-12 * projector.GetMirror()->Viewpoint().norm());
  }
}

// The default solver, Automatic, is the faster one where it gives the same answer: Iterative for
// the sphere and off-axis quadrics, Quartic (every image, the shortest path kept) for axial
// quadrics; Projector's default gives exactly what the solver it stands for gives.
TEST(QuadricMirror, AutomaticSolverIsTheFasterWhereExact)
{
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> pixel(0.0, 799.0);
  std::uniform_real_distribution<double> distance(0.01, 3.0);
  std::vector<std::pair<std::string, MirrorDescription>> mirrors = { { "sphere",
    SphereMirror{ Vec3(0.0, 0.0, 0.2), 0.05 } } };
  for (const Case& c : Cases())
  {
    mirrors.emplace_back(c.name, c.mirror);
  }
  int axial = 0, offAxis = 0;
  for (const auto& [name, mirror] : mirrors)
  {
    SCOPED_TRACE(name);
    const Projector projector(Camera(mirror));
    const auto* quadric = dynamic_cast<const detail::QuadricSurface*>(projector.GetMirror());
    const SolverType expected =
      quadric && quadric->IsAxial() ? SolverType::Quartic : SolverType::Iterative;
    (expected == SolverType::Quartic ? axial : offAxis) += 1;
    EXPECT_EQ(projector.GetMirror()->Resolve(SolverType::Automatic), expected);
    EXPECT_EQ(projector.GetMirror()->Resolve(SolverType::Quartic), SolverType::Quartic);
    EXPECT_EQ(projector.GetMirror()->Resolve(SolverType::Iterative), SolverType::Iterative);
    int compared = 0;
    for (int k = 0; k < 20000 && compared < 300; ++k)
    {
      const BackProjectedRay ray = projector.BackProjectCamera(Vec2(pixel(rng), pixel(rng)));
      if (!HasProjection(ray.status))
      {
        continue;
      }
      ++compared;
      const Vec3 P = ray.mirrorPoint + distance(rng) * ray.direction;
      const ProjectedPoint byDefault = projector.ProjectCamera(P);
      const ProjectedPoint chosen = projector.ProjectCamera(P, expected);
      ASSERT_EQ(byDefault.status, chosen.status) << k;
      EXPECT_EQ(byDefault.mirrorPoint, chosen.mirrorPoint) << k;
      EXPECT_EQ(byDefault.pixel, chosen.pixel) << k;
    }
    EXPECT_GT(compared, 100);
  }
  EXPECT_GT(axial, 0);
  EXPECT_GT(offAxis, 1);
  // The scene's default.
  EXPECT_EQ(SceneDescription().solver, SolverType::Automatic);
}

// Reflections next to a cone's apex (the mirror's z_range reaching the apex, the camera on its
// axis): the pixels around the apex's image are back-projected, points put on their reflected
// rays, and projected again; each comes back to its pixel. Before, points whose reflection lay
// within about a millimetre of the apex got no-reflection: the axial search's first sample sat
// on the apex, where the normal is undefined, and the root next to it was never bracketed.
TEST(QuadricMirror, ReflectionsNextToAConesApex)
{
  const MirrorDescription cone =
    Shape("cone", { 35.0 }, Placement(0.0, Vec3(0, 0, 0.1)), 0.0, 0.04);
  const Projector projector(Camera(cone));
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * 3.141592653589793);
  std::uniform_real_distribution<double> radius(0.3, 12.0); // pixels from the apex's image
  std::uniform_real_distribution<double> distance(0.02, 1.0);
  int tried = 0, nearApex = 0;
  double worst = 0.0;
  for (int k = 0; k < 4000; ++k)
  {
    const double a = angle(rng), r = radius(rng);
    const Vec2 pixel(399.5 + r * std::cos(a), 399.5 + r * std::sin(a));
    const BackProjectedRay ray = projector.BackProjectCamera(pixel);
    if (!HasProjection(ray.status))
    {
      continue;
    }
    const Vec3 P = ray.mirrorPoint + distance(rng) * ray.direction;
    ++tried;
    // The apex is at camera z = 0.1 on the axis.
    nearApex += (ray.mirrorPoint - Vec3(0, 0, 0.1)).norm() < 1e-3;
    for (const SolverType solver :
      { SolverType::Automatic, SolverType::Quartic, SolverType::Iterative })
    {
      const ProjectedPoint q = projector.ProjectCamera(P, solver);
      ASSERT_TRUE(HasProjection(q.status))
        << "pixel (" << pixel.x() << ", " << pixel.y() << "), mirror point "
        << ray.mirrorPoint.transpose() << ", solver " << static_cast<int>(solver) << ": status "
        << static_cast<int>(q.status);
      worst = std::max(worst, (q.pixel - pixel).norm());
    }
  }
  EXPECT_GT(tried, 3000);
  EXPECT_GT(nearApex, 100);
  EXPECT_LT(worst, 1e-6);
}

TEST(QuadricMirror, SphereAsQuadricIsTheClosedFormSphere)
{
  const double R = 0.05;
  const Vec3 centre(0.01, -0.02, 0.2);
  Mat4 omega = Mat4::Identity();
  omega(3, 3) = -R * R;
  std::vector<double> shape(omega.data(), omega.data() + 16);
  Mat4 h = Mat4::Identity();
  h.topRightCorner<3, 1>() = centre;
  const Projector quadric(Camera(Shape("quadric", shape, h, -R, R)));
  const Projector sphere(Camera(SphereMirror{ centre, R }));
  ASSERT_TRUE(quadric.IsValid()) << quadric.GetError();
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int compared = 0;
  for (int k = 0; k < 20000; ++k)
  {
    const Vec3 P = centre + Vec3(u(rng), u(rng), u(rng)) * 0.6;
    const ProjectedPoint a = sphere.ProjectCamera(P);
    const ProjectedPoint b = quadric.ProjectCamera(P);
    if (a.status == ProjectionStatus::Valid)
    {
      ASSERT_EQ(b.status, ProjectionStatus::Valid) << k;
      EXPECT_LE((a.mirrorPoint - b.mirrorPoint).norm(), 1e-12 * R) << k;
      ++compared;
    }
    else if (a.status == ProjectionStatus::InsideMirror)
    {
      EXPECT_EQ(b.status, ProjectionStatus::InsideMirror) << k;
    }
  }
  EXPECT_GT(compared, 5000);
}

// The camera at the outer focus of a hyperboloid: every reflected ray passes through the inner
// focus (a central camera), back and forth.
TEST(QuadricMirror, HyperboloidWithTheCameraAtItsFocusIsCentral)
{
  const double a = 0.02, b = 0.03, c = std::sqrt(a * a + b * b);
  const MirrorDescription mirror =
    Shape("hyperboloid", { a, b }, Placement(0.0, Vec3(0, 0, c)), a, 0.05);
  const Projector projector(Camera(mirror));
  ASSERT_TRUE(projector.IsValid()) << projector.GetError();
  const Vec3 inner(0.0, 0.0, 2.0 * c); // (0, 0, +c) in the mirror frame
  double worst = 0.0;
  int rays = 0;
  for (int y = 0; y < 800; y += 7)
  {
    for (int x = 0; x < 800; x += 7)
    {
      const BackProjectedRay ray = projector.BackProjectCamera(Vec2(x, y));
      if (!HasProjection(ray.status))
      {
        continue;
      }
      ++rays;
      const Vec3 w = inner - ray.mirrorPoint;
      worst = std::max(worst, (w - w.dot(ray.direction) * ray.direction).norm() / w.norm());
    }
  }
  EXPECT_GT(rays, 1000);
  EXPECT_LE(worst, 1e-12);
  // Forward: the point, the inner focus and the reflected ray of its pixel are collinear.
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  int checked = 0;
  double worstLine = 0.0;
  for (int k = 0; k < 5000; ++k)
  {
    const Vec3 P = inner + Vec3(u(rng), u(rng), u(rng));
    const ProjectedPoint q = projector.ProjectCamera(P);
    if (!HasProjection(q.status))
    {
      continue;
    }
    ++checked;
    const Vec3 toFocus = (inner - q.mirrorPoint).normalized();
    const Vec3 toPoint = (P - q.mirrorPoint).normalized();
    worstLine = std::max(worstLine, toFocus.cross(toPoint).norm());
  }
  EXPECT_GT(checked, 500);
  EXPECT_LE(worstLine, 1e-10);
}

TEST(QuadricMirror, ExtremesGetAStatusAndNeverNaN)
{
  for (const Case& c : Cases())
  {
    SCOPED_TRACE(c.name);
    const Projector projector(Camera(c.mirror));
    const Mirror* mirror = projector.GetMirror();
    ASSERT_NE(mirror, nullptr);
    std::vector<Vec3> points = { Vec3::Zero(), Vec3(0, 0, -1), Vec3(0, 0, 1e6),
      Vec3(1e6, -1e6, 1e6), Vec3(0, 0, -1e6), mirror->Viewpoint(), Vec3(0, 0, 1e-12) };
    // Points on the mirror's rim and surface, and just off it.
    std::mt19937_64 rng(1);
    std::uniform_real_distribution<double> pix(0.0, 799.0);
    for (int k = 0; k < 200; ++k)
    {
      const BackProjectedRay ray = projector.BackProjectCamera(Vec2(pix(rng), pix(rng)));
      if (HasProjection(ray.status))
      {
        points.push_back(ray.mirrorPoint);
        points.push_back(ray.mirrorPoint * (1.0 + 1e-12));
        points.push_back(ray.mirrorPoint * (1.0 - 1e-9));
        points.push_back(ray.mirrorPoint + 1e-6 * ray.direction);
      }
    }
    for (const Vec3& P : points)
    {
      const ProjectedPoint q = projector.ProjectCamera(P);
      EXPECT_TRUE(q.pixel.allFinite() && q.mirrorPoint.allFinite() && std::isfinite(q.pathLength));
      if (!HasProjection(q.status))
      {
        EXPECT_EQ(q.mirrorPoint, Vec3::Zero());
      }
    }
    const ProjectedPoint bad = projector.ProjectCamera(Vec3(NAN, 0, 1));
    EXPECT_EQ(bad.status, ProjectionStatus::InvalidInput);
  }
}

// ProjectWorldNear(n, ...) solves points side by side (QuadricSurface::ReflectNear); each result
// must be bit for bit the one-point call's, whatever mix of points (inside the mirror, on it,
// behind the camera, far, NaN) and guesses (close, anywhere on the mirror, off it, NaN) a batch
// holds, and for any batch length; the answers settled side by side obey the law of reflection.
TEST(QuadricMirror, ManyPointsAtOnceGiveWhatOneAtATimeGives)
{
  std::mt19937_64 rng(7);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::uniform_real_distribution<double> pixel(0.0, 799.0);
  std::uniform_real_distribution<double> distance(0.01, 3.0);
  std::uniform_int_distribution<int> kind(0, 9);
  for (const Case& c : Cases())
  {
    SCOPED_TRACE(c.name);
    const Projector proj(Camera(c.mirror));
    ASSERT_TRUE(proj.IsValid()) << proj.GetError();
    ASSERT_GT(proj.GetBatchSize(), 1);
    std::vector<Vec3> points, guesses, mirrorPoints;
    while (points.size() < 3000)
    {
      const BackProjectedRay ray = proj.BackProjectCamera(Vec2(pixel(rng), pixel(rng)));
      if (!HasProjection(ray.status))
      {
        continue;
      }
      mirrorPoints.push_back(ray.mirrorPoint);
      Vec3 p = ray.mirrorPoint + distance(rng) * ray.direction;
      // A guess: the reflection point of a point 1 mm away (the usual case).
      const Vec3 offset(1e-3 * (pixel(rng) / 400.0 - 1.0), 1e-3, -1e-3);
      Vec3 guess = proj.ProjectCamera(p + offset).mirrorPoint;
      switch (kind(rng))
      {
        case 0:
          p = ray.mirrorPoint - 0.01 * ray.direction; // behind the mirror: inside it, or hidden
          break;
        case 1:
          p = ray.mirrorPoint; // on it
          break;
        case 2:
          p = -p; // behind the camera
          break;
        case 3:
          guess = mirrorPoints[mirrorPoints.size() / 2]; // another point of the mirror
          break;
        case 4:
          guess = Vec3(nan, 0, 0);
          break;
        case 5:
          guess = 3.0 * guess; // off the mirror
          break;
        case 6:
          p = points.size() % 7 == 0 ? Vec3(nan, nan, nan) : 1e6 * p; // NaN, or far away
          break;
        default:
          break;
      }
      points.push_back(p);
      guesses.push_back(guess);
    }
    int valid = 0;
    for (const std::size_t length :
      { std::size_t(1), std::size_t(3), std::size_t(8), std::size_t(11), points.size() })
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
        if (!HasProjection(one.status) || one.mirrorPoint == points[i])
        {
          continue; // no reflection, or a point on the mirror (its own)
        }
        ++valid;
        // The law of reflection at the answer (the normal from the quadric's gradient).
        Mat4 omega = Mat4::Zero(), toMirror = Mat4::Identity();
        MirrorFrame(c.mirror, omega, toMirror);
        const Vec3& r = one.mirrorPoint;
        const Eigen::Vector4d X = toMirror * Eigen::Vector4d(r.x(), r.y(), r.z(), 1.0);
        const Vec3 n =
          (toMirror.topLeftCorner<3, 3>().transpose() * (omega * X).head<3>()).normalized();
        const Vec3 u1 = -r.normalized();
        const Vec3 u2 = (points[i] - r).normalized();
        ASSERT_LE(std::abs(std::abs(n.dot(u1)) - std::abs(n.dot(u2))), 1e-10) << i;
        ASSERT_LE(std::abs(n.dot(u1.cross(u2))), 1e-10) << i;
      }
    }
    EXPECT_GT(valid, 5 * 1000) << "of " << 5 * points.size();
  }
}

// Points whose reflection is on the rim of z_range (the last pixels of each row that see the
// mirror): a reflection on the mirror, or a status, never a point off the mirror or NaN.
TEST(QuadricMirror, TheRimOfZRange)
{
  for (const Case& c : Cases())
  {
    SCOPED_TRACE(c.name);
    const Projector projector(Camera(c.mirror));
    Mat4 omega = Mat4::Zero(), toMirror = Mat4::Identity();
    MirrorFrame(c.mirror, omega, toMirror);
    QuadricGeometry g;
    ASSERT_TRUE(QuadricFromDescription(c.mirror, g));
    int rim = 0, valid = 0;
    for (int y = 0; y < 800; y += 5)
    {
      bool previous = false;
      for (double x = 0.0; x < 800.0; x += 0.25)
      {
        const BackProjectedRay ray = projector.BackProjectCamera(Vec2(x, y));
        const bool hit = HasProjection(ray.status);
        if (hit != previous && hit)
        {
          ++rim;
          for (double s : { 0.001, 0.1, 1.0 })
          {
            const ProjectedPoint q = projector.ProjectCamera(ray.mirrorPoint + s * ray.direction);
            ASSERT_TRUE(q.pixel.allFinite() && q.mirrorPoint.allFinite());
            if (HasProjection(q.status))
            {
              ++valid;
              const Eigen::Vector4d X = toMirror *
                Eigen::Vector4d(q.mirrorPoint.x(), q.mirrorPoint.y(), q.mirrorPoint.z(), 1);
              EXPECT_GE(X.z(), g.zmin - 1e-9) << x << "," << y;
              EXPECT_LE(X.z(), g.zmax + 1e-9) << x << "," << y;
            }
          }
        }
        previous = hit;
      }
    }
    EXPECT_GT(rim, 20);
    EXPECT_GT(valid, rim); // most rim points keep their reflection
  }
}

TEST(QuadricMirror, CalibrationFilesNameTheKeyAtFault)
{
  const std::string lens = R"({"image_width": 800, "image_height": 800,
    "camera_matrix": [400, 0, 399.5, 0, 400, 399.5, 0, 0, 1], "mirror": )";
  const std::string I = "[1,0,0,0, 0,1,0,0, 0,0,1,0.1, 0,0,0,1]";
  struct Bad
  {
    std::string mirror;
    std::string expected;
  };
  const Bad bad[] = {
    { R"({"type": "quadric", "matrix": [1,0,0,0, 0,1,0,1, 0,0,1,0, 0,0,0,-0.01], "mirror_to_camera": )" +
        I + R"(, "z_range": [-1, 1]})",
      "mirror.matrix is not symmetric" },
    { R"({"type": "quadric", "matrix": [1,0,0,0, 0,0,0,0, 0,0,0,0, 0,0,0,-0.01], "mirror_to_camera": )" +
        I + R"(, "z_range": [-1, 1]})",
      "mirror.matrix is degenerate" },
    { R"({"type": "ellipsoid", "semi_axes": [0.5, 0.5, 0.5], "mirror_to_camera": )" + I +
        R"(, "z_range": [-1, 1]})",
      "inside the mirror" },
    { R"({"type": "paraboloid", "focal": 0.01, "mirror_to_camera": )" + I +
        R"(, "z_range": [0.02, 0.01]})",
      "mirror.z_range is empty" },
    { R"({"type": "cone", "half_angle": 30, "mirror_to_camera": [1,0,0,0, 0,2,0,0, 0,0,1,0.1, 0,0,0,1], "z_range": [0, 0.04]})",
      "mirror.mirror_to_camera is not a rigid transform" },
    { R"({"type": "hyperboloid", "a": -1, "b": 0.03, "mirror_to_camera": )" + I +
        R"(, "z_range": [0.02, 0.05]})",
      "mirror.a and mirror.b must be positive" },
    { R"({"type": "hyperboloid", "a": 0.02, "b": 0.03, "mirror_to_camera": )" + I + "}",
      "z_range" },
  };
  for (const Bad& b : bad)
  {
    CameraModel m;
    std::string error;
    EXPECT_FALSE(ParseCalibration(lens + b.mirror + "}", m, error)) << b.mirror;
    EXPECT_NE(error.find(b.expected), std::string::npos) << error;
  }
  // A good one of each type loads, saves under its own type and keys, and loads back the same.
  for (const Case& c : Cases())
  {
    const std::string path = ::testing::TempDir() + "/catar_quadric.yaml";
    std::string error;
    ASSERT_TRUE(SaveCalibration(path, Camera(c.mirror), error)) << c.name << ": " << error;
    CameraModel back;
    ASSERT_TRUE(LoadCalibration(path, back, error)) << c.name << ": " << error;
    EXPECT_EQ(back.mirror.type, c.mirror.type);
    ASSERT_EQ(back.mirror.parameters.size(), c.mirror.parameters.size());
    for (std::size_t i = 0; i < c.mirror.parameters.size(); ++i)
    {
      EXPECT_NEAR(back.mirror.parameters[i], c.mirror.parameters[i],
        1e-15 * std::max(1.0, std::abs(c.mirror.parameters[i])))
        << c.name << " " << i;
    }
    std::remove(path.c_str());
  }
}
