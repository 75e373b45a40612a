// Per-frame tessellation (Module/Projection/ImageTessellation.h) against the exact projection:
// every point of an input triangle that the camera sees lands inside the drawn pieces (to the
// tolerances), every piece is seen, the pieces' edges bend no more than the tolerance, new points
// lie where their barycentric weights say.
#include "EdgeBend.h"
#include "ImageTessellation.h"
#include "Projector.h"
#include "TestCameras.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <random>
#include <vector>

using namespace catar;

namespace
{
// Distance from p to the 2D triangle (a, b, c): 0 inside.
double DistanceToTriangle(const Vec2& p, const Vec2& a, const Vec2& b, const Vec2& c)
{
  auto cross = [](const Vec2& u, const Vec2& v) { return u.x() * v.y() - u.y() * v.x(); };
  const double d1 = cross(b - a, p - a), d2 = cross(c - b, p - b), d3 = cross(a - c, p - c);
  const bool neg = d1 < 0 || d2 < 0 || d3<0, pos = d1> 0 || d2 > 0 || d3 > 0;
  if (!(neg && pos))
  {
    return 0.0;
  }
  return std::min(
    { DistanceToSegment(p, a, b), DistanceToSegment(p, b, c), DistanceToSegment(p, c, a) });
}

struct Pieces
{
  Tessellation out;
  std::size_t pieces = 0;
  TriangleFate fate = TriangleFate::Keep;
};

Pieces TessellateOne(
  const Projector& proj, const std::array<Vec3, 3>& world, const TessellationOptions& options)
{
  Pieces r;
  std::array<ProjectedPoint, 3> q;
  for (int i = 0; i < 3; ++i)
  {
    q[i] = proj.ProjectWorld(world[i]);
  }
  r.fate = TriangleFateOf(proj, world, q, options);
  if (r.fate == TriangleFate::Tessellate)
  {
    r.pieces = TessellateTriangle(proj, 7, { { 0, 1, 2 } }, world, q, 3, options, r.out);
  }
  return r;
}

// The pixel of a piece's point id (0-2: the input triangle's corners).
Vec2 PixelOf(const Pieces& r, const std::array<ProjectedPoint, 3>& corners, std::int64_t id)
{
  return id < 3 ? corners[id].pixel : r.out.points[id - 3].projected.pixel;
}
} // namespace

// A large triangle across the sphere's limb (one corner behind the mirror, hidden): every seen
// point of it is inside the pieces, to the two tolerances; every piece's corners are seen; the
// pieces' edges bend no more than the bend tolerance.
TEST(ImageTessellation, ATriangleAcrossTheBoundaryIsDrawnUpToTheTolerance)
{
  const CameraModel model = catar_test::DemoCameraModel();
  const Projector proj(model);
  const std::array<Vec3, 3> camera = { { Vec3(0.01, 0.005, 0.45), Vec3(0.35, -0.05, 0.02),
    Vec3(-0.1, 0.3, -0.05) } };
  std::array<Vec3, 3> world;
  std::array<ProjectedPoint, 3> corners;
  for (int i = 0; i < 3; ++i)
  {
    world[i] = model.CameraToWorld(camera[i]);
    corners[i] = proj.ProjectWorld(world[i]);
  }
  ASSERT_FALSE(HasProjection(corners[0].status)) << "behind the mirror";
  ASSERT_TRUE(HasProjection(corners[1].status));
  ASSERT_TRUE(HasProjection(corners[2].status));
  for (const double tolerance : { 1.0, 0.25 })
  {
    TessellationOptions options;
    options.boundaryTolerance = tolerance;
    options.bendTolerance = tolerance;
    const Pieces r = TessellateOne(proj, world, options);
    ASSERT_EQ(r.fate, TriangleFate::Tessellate);
    ASSERT_GT(r.pieces, 1u);
    // Pieces: corners seen, weights give the world point, edges bend within the tolerance.
    double worstBend = 0.0;
    for (const TessellatedTriangle& t : r.out.triangles)
    {
      EXPECT_EQ(t.cell, 7);
      for (int i = 0; i < 3; ++i)
      {
        const std::int64_t a = t.points[i], b = t.points[(i + 1) % 3];
        const Vec3 wa = a < 3 ? world[a] : r.out.points[a - 3].world;
        const Vec3 wb = b < 3 ? world[b] : r.out.points[b - 3].world;
        // Edges between split points (corners and midpoints); the cut along the boundary, between
        // boundary points, is measured by the samples below.
        const auto onGrid = [&](
                              std::int64_t id) { return id < 3 || !r.out.points[id - 3].boundary; };
        const ProjectedPoint mid = proj.ProjectWorld(0.5 * (wa + wb));
        if (onGrid(a) && onGrid(b) && HasProjection(mid.status))
        {
          worstBend = std::max(worstBend,
            DistanceToSegment(mid.pixel, PixelOf(r, corners, a), PixelOf(r, corners, b)));
        }
      }
    }
    for (const TessellatedPoint& p : r.out.points)
    {
      EXPECT_TRUE(HasProjection(p.projected.status));
      Vec3 w = Vec3::Zero();
      for (int i = 0; i < 3; ++i)
      {
        w += p.weights[i] * world[p.parents[i]];
      }
      EXPECT_LT((w - p.world).norm(), 1e-12);
    }
    // Every seen point of the triangle inside the pieces.
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    int seen = 0;
    double worst = 0.0;
    for (int k = 0; k < 20000; ++k)
    {
      double s = u(rng), t = u(rng);
      if (s + t > 1.0)
      {
        s = 1.0 - s;
        t = 1.0 - t;
      }
      const Vec3 p = world[0] + s * (world[1] - world[0]) + t * (world[2] - world[0]);
      const ProjectedPoint q = proj.ProjectWorld(p);
      if (!HasProjection(q.status))
      {
        continue;
      }
      ++seen;
      double d = 1e300;
      for (const TessellatedTriangle& tri : r.out.triangles)
      {
        d = std::min(d,
          DistanceToTriangle(q.pixel, PixelOf(r, corners, tri.points[0]),
            PixelOf(r, corners, tri.points[1]), PixelOf(r, corners, tri.points[2])));
      }
      worst = std::max(worst, d);
    }
    std::cout << "[ tessel.  ] tolerance " << tolerance << " px: " << r.pieces << " pieces, "
              << r.out.points.size() << " new points; " << seen << " seen samples, the farthest "
              << worst << " px from the pieces; worst edge bend " << worstBend << " px"
              << std::endl;
    EXPECT_GT(seen, 1000);
    EXPECT_LE(worstBend, tolerance);
    EXPECT_LE(worst, 2.0 * tolerance);
  }
}

// Seen whole, within the bend tolerance: kept. Unseen everywhere: dropped. Crossing the boundary
// with boundary tessellation off: dropped (the old behaviour).
TEST(ImageTessellation, FatesOfTriangles)
{
  const CameraModel model = catar_test::DemoCameraModel();
  const Projector proj(model);
  auto world = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    return std::array<Vec3, 3>{ { model.CameraToWorld(a), model.CameraToWorld(b),
      model.CameraToWorld(c) } };
  };
  TessellationOptions options;
  options.bendTolerance = 0.5;
  // A small triangle beside the camera.
  EXPECT_EQ(TessellateOne(
              proj, world(Vec3(0.2, 0.0, 0.0), Vec3(0.21, 0.0, 0.0), Vec3(0.2, 0.01, 0.0)), options)
              .fate,
    TriangleFate::Keep);
  // Behind the mirror, all of it.
  EXPECT_EQ(TessellateOne(
              proj, world(Vec3(0.0, 0.0, 0.5), Vec3(0.01, 0.0, 0.5), Vec3(0.0, 0.01, 0.5)), options)
              .fate,
    TriangleFate::Drop);
  // A large triangle whose edges bend: tessellated, its pieces within the tolerance.
  const Pieces bent = TessellateOne(
    proj, world(Vec3(0.4, 0.0, -0.1), Vec3(0.0, 0.4, -0.1), Vec3(-0.4, -0.2, -0.1)), options);
  EXPECT_EQ(bent.fate, TriangleFate::Tessellate);
  EXPECT_GT(bent.pieces, 4u);
  options.bendTolerance = 0.0;
  EXPECT_EQ(TessellateOne(proj,
              world(Vec3(0.4, 0.0, -0.1), Vec3(0.0, 0.4, -0.1), Vec3(-0.4, -0.2, -0.1)), options)
              .fate,
    TriangleFate::Keep);
  options.boundaryTolerance = 0.0;
  EXPECT_EQ(
    TessellateOne(proj,
      world(Vec3(0.01, 0.005, 0.45), Vec3(0.35, -0.05, 0.02), Vec3(-0.1, 0.3, -0.05)), options)
      .fate,
    TriangleFate::Drop);
}

// Many triangles at once get the fates they get one at a time: random triangles of all sizes
// around the rig (seen whole, across the boundary, hidden, with NaN corners).
TEST(ImageTessellation, FatesOfManyTrianglesAtOnce)
{
  const CameraModel model = catar_test::DemoCameraModel();
  const Projector proj(model);
  std::mt19937 rng(99);
  std::uniform_real_distribution<double> u(-0.5, 0.5), s(0.001, 0.3);
  std::vector<std::array<Vec3, 3>> world;
  std::vector<std::array<ProjectedPoint, 3>> projected;
  for (int t = 0; t < 3000; ++t)
  {
    // Every third one centred in the region the mirror hides (behind it, near its axis).
    const Vec3 c = t % 3 == 0 ? Vec3(0.08 * u(rng), 0.08 * u(rng), 0.35 + 0.3 * u(rng))
                              : Vec3(u(rng), u(rng), u(rng) - 0.3);
    const double size = s(rng);
    std::array<Vec3, 3> w;
    std::array<ProjectedPoint, 3> p;
    for (int k = 0; k < 3; ++k)
    {
      w[k] = model.CameraToWorld(c + size * Vec3(u(rng), u(rng), u(rng)));
      if (t % 97 == 0 && k == 1)
      {
        w[k].x() = std::numeric_limits<double>::quiet_NaN();
      }
      p[k] = proj.ProjectWorld(w[k]);
    }
    world.push_back(w);
    projected.push_back(p);
  }
  for (const double bend : { 0.0, 0.25, 2.0 })
  {
    TessellationOptions options;
    options.bendTolerance = bend;
    std::vector<TriangleFate> batch(world.size());
    TriangleFates(proj, world.size(), world.data(), projected.data(), options, batch.data());
    int counts[3] = { 0, 0, 0 }, differ = 0;
    for (std::size_t t = 0; t < world.size(); ++t)
    {
      const TriangleFate one = TriangleFateOf(proj, world[t], projected[t], options);
      differ += one != batch[t];
      ++counts[static_cast<int>(one)];
    }
    EXPECT_EQ(differ, 0) << "bend " << bend;
    // All three fates occur.
    EXPECT_GT(counts[0], 100) << bend;
    EXPECT_GT(counts[1], 100) << bend;
    EXPECT_GT(counts[2], 100) << bend;
    std::cout << "[ fates    ] bend " << bend << ": kept " << counts[0] << ", dropped " << counts[1]
              << ", tessellated " << counts[2] << std::endl;
  }
}

// Two triangles that share an edge, tessellated each on its own, put the same points on it: the
// pieces on either side meet without T-junctions, whose cracks would show as holes. Quads of all
// sizes around the rig, seen whole, at several tolerances.
TEST(ImageTessellation, NeighboursSplitTheirSharedEdgeAlike)
{
  const CameraModel model = catar_test::DemoCameraModel();
  const Projector proj(model);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.5, 0.5), s(0.05, 0.4);
  int quads = 0, splitEdges = 0;
  for (int n = 0; n < 300; ++n)
  {
    const Vec3 c(u(rng), u(rng), u(rng) - 0.35);
    const double size = s(rng);
    std::array<Vec3, 4> q;
    for (Vec3& p : q)
    {
      p = model.CameraToWorld(c + size * Vec3(u(rng), u(rng), u(rng)));
    }
    // Triangles (0, 1, 2) and (2, 1, 3) share the edge 1-2, traversed in opposite directions.
    const std::array<Vec3, 3> first{ { q[0], q[1], q[2] } }, second{ { q[2], q[1], q[3] } };
    // Seen whole: the corners and points all over both triangles (the pieces of a triangle that
    // crosses the visibility boundary are cut at it, one triangle at a time).
    bool seen = true;
    for (int i = 0; i <= 16 && seen; ++i)
    {
      for (int j = 0; i + j <= 16 && seen; ++j)
      {
        const double wi = i / 16.0, wj = j / 16.0;
        seen =
          HasProjection(proj.ProjectWorld(wi * q[0] + wj * q[1] + (1 - wi - wj) * q[2]).status) &&
          HasProjection(proj.ProjectWorld(wi * q[3] + wj * q[1] + (1 - wi - wj) * q[2]).status);
      }
    }
    if (!seen)
    {
      continue;
    }
    for (const double bend : { 4.0, 1.0, 0.25 })
    {
      TessellationOptions options;
      options.bendTolerance = bend;
      const Pieces a = TessellateOne(proj, first, options),
                   b = TessellateOne(proj, second, options);
      // The new points on the shared edge (weight 0 at the third corner), as world points.
      auto onEdge = [](const Pieces& r, int third) {
        std::vector<std::array<double, 3>> points;
        for (const TessellatedPoint& p : r.out.points)
        {
          if (p.weights[third] == 0.0)
          {
            points.push_back({ p.world.x(), p.world.y(), p.world.z() });
          }
        }
        std::sort(points.begin(), points.end());
        return points;
      };
      const auto pa = onEdge(a, 0), pb = onEdge(b, 2);
      EXPECT_EQ(pa, pb) << "quad " << n << ", tolerance " << bend << ": " << pa.size() << " vs "
                        << pb.size() << " points on the shared edge";
      splitEdges += pa.empty() ? 0 : 1;
    }
    ++quads;
  }
  std::cout << "[ shared   ] " << quads << " quads seen whole; the shared edge split in "
            << splitEdges << " of " << 3 * quads << " tessellations" << std::endl;
  EXPECT_GT(quads, 100);
  EXPECT_GT(splitEdges, 50);
}
