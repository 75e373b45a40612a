// The mirror seam: the catalogue of mirror types, descriptions, and the calibration file's mirror
// keyed by type.
#include "CalibrationIO.h"
#include "Mirror.h"
#include "Projector.h"
#include "SphereMirror.h"
#include "TestCameras.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

using namespace catar;

TEST(MirrorTypes, EveryTypeDescribesItselfConsistently)
{
  ASSERT_FALSE(MirrorTypes().empty());
  for (const MirrorType& t : MirrorTypes())
  {
    SCOPED_TRACE(t.name);
    EXPECT_EQ(FindMirrorType(t.name, static_cast<std::size_t>(t.ParameterCount())), &t);
    EXPECT_EQ(static_cast<int>(t.defaults.size()), t.ParameterCount());
    ASSERT_TRUE(t.make && t.validate);
    int offset = 0;
    for (const MirrorParameter& p : t.parameters)
    {
      EXPECT_EQ(t.ParameterOffset(p.key), offset);
      EXPECT_GE(p.count, 1);
      offset += p.count;
    }
    // The defaults make a usable mirror that describes itself as given.
    const MirrorDescription d(t.name, t.defaults);
    std::string error;
    const std::shared_ptr<const Mirror> m = MakeMirror(d, error);
    ASSERT_TRUE(m) << error;
    EXPECT_EQ(m->Describe(), d);
    EXPECT_GE(m->BatchSize(), 1);
    EXPECT_LE(m->BatchSize(), Mirror::kMaxBatchSize);
  }
  EXPECT_EQ(MirrorDescription().type, MirrorTypes().front().name);
  EXPECT_EQ(FindMirrorType("no such mirror"), nullptr);
}

TEST(MirrorTypes, EveryTypeIsAQuadricOfTheCameraFrame)
{
  // The points where camera rays meet each type's default mirror (its own Intersect) lie on the
  // quadric MirrorQuadric gives (F = 0 to rounding, relative to |grad F| |r|), and the normal
  // there is along grad F.
  for (const MirrorType& t : MirrorTypes())
  {
    SCOPED_TRACE(t.name);
    const MirrorDescription d(t.name, t.defaults);
    Mat3 A;
    Vec3 B;
    double C = 0.0;
    ASSERT_TRUE(MirrorQuadric(d, A, B, C));
    std::string error;
    const std::shared_ptr<const Mirror> m = MakeMirror(d, error);
    ASSERT_TRUE(m) << error;
    int hits = 0;
    for (int i = -10; i <= 10; ++i)
    {
      for (int j = -10; j <= 10; ++j)
      {
        const Vec3 ray = Vec3(0.04 * i, 0.04 * j, 1.0).normalized();
        Vec3 r, n;
        if (!m->Intersect(ray, r, n))
        {
          continue;
        }
        ++hits;
        const Vec3 g = 2.0 * (A * r + B);
        const double F = r.dot(A * r) + 2.0 * B.dot(r) + C;
        EXPECT_LE(std::abs(F), 1e-12 * g.norm() * std::max(1.0, r.norm()));
        EXPECT_GT(std::abs(g.normalized().dot(n)), 1.0 - 1e-9);
      }
    }
    EXPECT_GT(hits, 10);
  }
  Mat3 A;
  Vec3 B;
  double C = 0.0;
  EXPECT_FALSE(MirrorQuadric(MirrorDescription("no such mirror", { 1.0 }), A, B, C));
  EXPECT_FALSE(MirrorQuadric(MirrorDescription("sphere", { 0.0, 0.0 }), A, B, C));
}

TEST(MirrorTypes, BadDescriptionsAreRefusedWithASentence)
{
  std::string error;
  EXPECT_FALSE(MakeMirror(MirrorDescription("paraboloid of doom", { 1.0 }), error));
  EXPECT_NE(error.find("unknown mirror type 'paraboloid of doom'"), std::string::npos) << error;
  EXPECT_NE(error.find(MirrorTypeNames()), std::string::npos) << error;

  const MirrorType& first = MirrorTypes().front();
  std::vector<double> shortList = first.defaults;
  shortList.pop_back();
  EXPECT_FALSE(MakeMirror(MirrorDescription(first.name, shortList), error));
  EXPECT_NE(
    error.find("takes " + std::to_string(first.ParameterCount()) + " numbers"), std::string::npos)
    << error;

  std::vector<double> withNaN = first.defaults;
  withNaN[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(MakeMirror(MirrorDescription(first.name, withNaN), error));
  EXPECT_EQ(error, "mirror contains NaN or Inf");

  // A camera model with a bad mirror is invalid, and so is its projector (no NaN comes out).
  CameraModel m = catar_test::DemoCameraModel();
  m.mirror = MirrorDescription(first.name, withNaN);
  EXPECT_FALSE(m.Validate().empty());
  const Projector projector(m);
  EXPECT_FALSE(projector.IsValid());
  EXPECT_EQ(projector.GetMirror(), nullptr);
  EXPECT_EQ(projector.ProjectWorld(Vec3(0.1, -0.3, 0.9)).status, ProjectionStatus::InvalidInput);
  EXPECT_EQ(projector.BackProjectWorld(Vec2(600, 500)).status, ProjectionStatus::InvalidInput);
}

TEST(SphereMirror, DescriptionRoundTrip)
{
  const SphereMirror s{ Vec3(0.01, -0.02, 0.2), 0.06 };
  const MirrorDescription d = s;
  EXPECT_EQ(d.type, "sphere");
  ASSERT_EQ(d.parameters.size(), 4u);
  SphereMirror back;
  ASSERT_TRUE(SphereMirror::From(d, back));
  EXPECT_EQ(back.center, s.center);
  EXPECT_EQ(back.radius, s.radius);
  EXPECT_FALSE(SphereMirror::From(MirrorDescription("other", d.parameters), back));

  std::string error;
  const std::shared_ptr<const Mirror> m = MakeMirror(d, error);
  ASSERT_TRUE(m) << error;
  EXPECT_EQ(m->Viewpoint(), s.center);
  // The first point a ray meets lies on the sphere, with the outward normal there.
  const Vec3 dir = Vec3(0.01, -0.02, 0.2).normalized();
  Vec3 point, normal;
  ASSERT_TRUE(m->Intersect(dir, point, normal));
  EXPECT_NEAR((point - s.center).norm(), s.radius, 1e-15);
  EXPECT_NEAR(normal.norm(), 1.0, 1e-15);
  EXPECT_LT(normal.dot(dir), 0.0);
  EXPECT_FALSE(m->Intersect(Vec3(1.0, 0.0, 0.0), point, normal));
}

TEST(CalibrationIO, MirrorIsKeyedByType)
{
  const std::string lens = R"({"image_width": 640, "image_height": 480,
    "camera_matrix": [480, 0, 319.5, 0, 480, 239.5, 0, 0, 1], )";
  CameraModel m;
  std::string error;
  // No type: the default type (a sphere file of before keeps loading).
  ASSERT_TRUE(
    ParseCalibration(lens + R"("mirror": {"center": [0, 0, 0.3], "radius": 0.1}})", m, error))
    << error;
  EXPECT_EQ(m.mirror, MirrorDescription("sphere", { 0, 0, 0.3, 0.1 }));
  ASSERT_TRUE(ParseCalibration(
    lens + R"("mirror": {"type": "sphere", "center": [0, 0, 0.3], "radius": 0.1}})", m, error));
  EXPECT_EQ(m.mirror, MirrorDescription("sphere", { 0, 0, 0.3, 0.1 }));
  EXPECT_FALSE(ParseCalibration(
    lens + R"("mirror": {"type": "blob", "center": [0, 0, 0.3], "radius": 0.1}})", m, error));
  EXPECT_NE(error.find("mirror type 'blob' is not supported (known: sphere"), std::string::npos)
    << error;
  EXPECT_FALSE(ParseCalibration(lens + R"("mirror": 3})", m, error));
  EXPECT_NE(error.find("missing map 'mirror' {type, center, radius}"), std::string::npos) << error;
}

TEST(Projector, BackProjectionOfManyPixelsIsOneAtATime)
{
  // Pixels over and beyond the image (hits, misses, outside, NaN), more than a batch: the batched
  // call gives exactly what one call per pixel gives.
  const CameraModel model = catar_test::DemoCameraModel();
  const Projector projector(model);
  std::vector<Vec2> pixels;
  for (int y = -40; y < model.intrinsics.height + 40; y += 37)
  {
    for (int x = -40; x < model.intrinsics.width + 40; x += 29)
    {
      pixels.emplace_back(x + 0.25, y - 0.5);
    }
  }
  pixels.emplace_back(std::numeric_limits<double>::quiet_NaN(), 3.0);
  ASSERT_GT(pixels.size(), static_cast<std::size_t>(3 * Mirror::kMaxBatchSize));
  std::vector<BackProjectedRay> many(pixels.size());
  projector.BackProjectWorld(pixels.size(), pixels.data(), many.data());
  int hits = 0, misses = 0;
  for (std::size_t i = 0; i < pixels.size(); ++i)
  {
    const BackProjectedRay one = projector.BackProjectWorld(pixels[i]);
    ASSERT_EQ(many[i].status, one.status) << i;
    EXPECT_EQ(many[i].mirrorPoint, one.mirrorPoint) << i;
    EXPECT_EQ(many[i].direction, one.direction) << i;
    hits += HasProjection(one.status) ? 1 : 0;
    misses += one.status == ProjectionStatus::NoReflection ? 1 : 0;
  }
  EXPECT_GT(hits, 100);
  EXPECT_GT(misses, 100);
  EXPECT_EQ(many.back().status, ProjectionStatus::InvalidInput);
}
