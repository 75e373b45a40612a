// Module/Base/Polygons.h against closed forms, and ProjectRun (Projector.h) against one point at a
// time.
#include "Polygons.h"
#include "Projector.h"
#include "TestCameras.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

using namespace catar;

TEST(Polygons, NewellNormalIsTwiceTheAreaAlongTheNormal)
{
  // A regular hexagon of circumradius r in a tilted plane: area 3 sqrt(3) / 2 r^2.
  const double r = 0.7;
  const Vec3 u = Vec3(1, 2, 0.5).normalized();
  const Vec3 v = u.unitOrthogonal();
  const Vec3 n = u.cross(v);
  const Vec3 origin(3.0, -1.0, 2.0);
  std::vector<Vec3> points;
  for (int k = 0; k < 6; ++k)
  {
    const double a = k * M_PI / 3.0;
    points.push_back(origin + r * (std::cos(a) * u + std::sin(a) * v));
  }
  const std::array<int, 6> ids = { 0, 1, 2, 3, 4, 5 };
  const Vec3 newell = PolygonNormal(ids.data(), ids.size(), [&](int i) { return points[i]; });
  const double area = 1.5 * std::sqrt(3.0) * r * r;
  EXPECT_NEAR((newell - 2.0 * area * n).norm(), 0.0, 1e-12);
  // Reversed order: the opposite normal.
  const std::array<int, 6> reversed = { 5, 4, 3, 2, 1, 0 };
  EXPECT_NEAR(
    (PolygonNormal(reversed.data(), reversed.size(), [&](int i) { return points[i]; }) + newell)
      .norm(),
    0.0, 1e-12);
  EXPECT_EQ(PolygonNormal(ids.data(), 0, [&](int i) { return points[i]; }), Vec3::Zero());
}

TEST(Polygons, FansAndStripsCoverThePolygonFacingOneWay)
{
  // A pentagon's fan: 3 triangles from point 0.
  const std::array<int, 5> pentagon = { 10, 11, 12, 13, 14 };
  std::vector<std::array<int, 3>> fan;
  PolygonTriangles(pentagon.data(), pentagon.size(), [&](int a, int b, int c) {
    fan.push_back({ a, b, c });
  });
  ASSERT_EQ(fan.size(), 3u);
  EXPECT_EQ(fan[0], (std::array<int, 3>{ 10, 11, 12 }));
  EXPECT_EQ(fan[2], (std::array<int, 3>{ 10, 13, 14 }));
  int none = 0;
  PolygonTriangles(pentagon.data(), 2, [&](int, int, int) { ++none; });
  EXPECT_EQ(none, 0);

  // A strip of 6 points along a zig-zag in the plane z = 0: 4 triangles, all facing +z.
  std::vector<Vec3> p;
  for (int k = 0; k < 6; ++k)
  {
    p.emplace_back(0.5 * k, k % 2 == 0 ? 0.0 : 1.0, 0.0);
  }
  const std::array<int, 6> strip = { 0, 1, 2, 3, 4, 5 };
  int triangles = 0;
  double total = 0.0;
  StripTriangles(strip.data(), strip.size(), [&](int a, int b, int c) {
    ++triangles;
    const Vec3 normal = (p[b] - p[a]).cross(p[c] - p[a]);
    EXPECT_LT(normal.z(), 0.0) << a << " " << b << " " << c; // the first one's side
    total += 0.5 * std::abs(normal.z());
  });
  EXPECT_EQ(triangles, 4);
  EXPECT_NEAR(total, 4 * 0.5, 1e-15); // 4 triangles of base 1 and height 1
}

TEST(Polygons, AverageAtPointsIsTheMeanOverTheCellsAround)
{
  // Two triangles sharing an edge (points 1 and 2), values 1 and 3; point 4 in no cell.
  const std::vector<std::array<std::size_t, 3>> cells = { { { 0, 1, 2 } }, { { 1, 3, 2 } } };
  const double values[2][2] = { { 1.0, 10.0 }, { 3.0, 30.0 } };
  const std::vector<double> mean = AverageAtPoints<double>(
    5, cells.size(), 2,
    [&](std::size_t c, auto&& visit) {
      for (std::size_t id : cells[c])
      {
        visit(id);
      }
    },
    [&](std::size_t c, double* v) {
      v[0] = values[c][0];
      v[1] = values[c][1];
    });
  ASSERT_EQ(mean.size(), 10u);
  EXPECT_EQ(mean[0], 1.0);
  EXPECT_EQ(mean[2 * 1], 2.0);
  EXPECT_EQ(mean[2 * 1 + 1], 20.0);
  EXPECT_EQ(mean[2 * 3 + 1], 30.0);
  EXPECT_EQ(mean[2 * 4], 0.0);
}

TEST(ProjectRun, GivesEachPointsOwnProjection)
{
  // Points along a random walk (neighbours follow each other, as in a mesh) and a few far jumps
  // and bad points: ProjectRun's answers are each point's own, to the solvers' tolerance.
  const CameraModel model = catar_test::DemoCameraModel();
  const Projector projector(model);
  std::mt19937_64 rng(5);
  std::normal_distribution<double> step(0.0, 0.002);
  std::uniform_real_distribution<double> jump(-0.4, 0.4);
  std::vector<Vec3> points;
  Vec3 p(0.05, -0.3, 0.95);
  for (int i = 0; i < 500; ++i)
  {
    p += Vec3(step(rng), step(rng), step(rng));
    if (i % 97 == 0)
    {
      p = Vec3(jump(rng), -0.3 + jump(rng), 1.0 + jump(rng));
    }
    points.push_back(p);
  }
  points[123] = Vec3(NAN, 0, 0);
  points[124] = model.CameraToWorld(Vec3(0, 0, 0.14)); // the mirror's centre: inside it
  for (SolverType solver : { SolverType::Quartic, SolverType::Iterative })
  {
    for (std::ptrdiff_t begin : { 0, 7, 130 })
    {
      std::vector<ProjectedPoint> out(points.size());
      std::vector<int> order;
      ProjectRun(
        projector, solver, begin, static_cast<std::ptrdiff_t>(points.size()),
        [&](std::ptrdiff_t i) { return points[i]; },
        [&](std::ptrdiff_t i, const Vec3& q, const ProjectedPoint& r) {
          if (i != 123) // NaN is not equal to itself
          {
            EXPECT_EQ(q, points[i]);
          }
          order.push_back(static_cast<int>(i));
          out[i] = r;
        });
      ASSERT_EQ(order.size(), points.size() - begin);
      for (std::size_t k = 0; k < order.size(); ++k)
      {
        ASSERT_EQ(order[k], static_cast<int>(begin + k));
      }
      for (std::size_t i = begin; i < points.size(); ++i)
      {
        const ProjectedPoint one = projector.ProjectWorld(points[i], solver);
        ASSERT_EQ(out[i].status, one.status) << i;
        EXPECT_LT((out[i].mirrorPoint - one.mirrorPoint).norm(), 1e-12 * 0.05) << i;
        EXPECT_LT((out[i].pixel - one.pixel).norm(), 1e-7) << i;
      }
    }
  }
}
