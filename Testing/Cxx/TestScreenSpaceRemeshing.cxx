// Remeshing to a pixel tolerance. On two camera/object placements the bend of every visible edge
// of the result, measured independently by projecting each edge's midpoint exactly and taking its
// distance to the image of the straight edge, stays within the tolerance; the result needs fewer
// triangles than a uniform mesh meeting the same tolerance, its sizes follow the mirror's
// magnification, it stays closed with its shape and sharp edges, and a smaller tolerance costs
// more triangles. Bad input fails cleanly; unseen objects stay coarse.
#include "ScreenSpaceRemeshing.h"

#include "EdgeBend.h"
#include "Projector.h"

#include "TestCameras.h"
#include <Eigen/Geometry>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>
#include <vector>

using namespace catar;
using catar_test::Sphere;
using namespace catar::mesh;

namespace
{
constexpr double Pi = 3.14159265358979323846;

/// A tilted 6 cm mirror 20 cm away, with lens distortion and skew (as in TestSphereProjection).
CameraModel TiltedCamera()
{
  CameraModel m;
  m.intrinsics = Intrinsics{ 1100.0, 1050.0, 640.2, 470.8, 0.7, 1280, 960 };
  m.distortion = Distortion{ -0.21, 0.08, 0.0012, -0.0007, -0.01 };
  m.mirror = SphereMirror{ Vec3(0.01, -0.02, 0.2), 0.06 };
  m.worldToCamera.topLeftCorner<3, 3>() =
    Eigen::AngleAxisd(0.7, Vec3(0.3, -1.0, 0.2).normalized()).toRotationMatrix();
  m.worldToCamera.topRightCorner<3, 1>() = Vec3(0.1, -0.3, 0.5);
  return m;
}

/// A box of the given size, rotated about world z and centred at `centre`: 8 points,
/// 12 outward-oriented triangles.
TriangleMesh MakeBox(const Vec3& size, double yawDegrees, const Vec3& centre)
{
  const Mat3 rotation =
    Eigen::AngleAxisd(yawDegrees * Pi / 180.0, Vec3::UnitZ()).toRotationMatrix();
  TriangleMesh box;
  for (int i = 0; i < 8; ++i)
  {
    const Vec3 corner((i & 1) ? 0.5 : -0.5, (i & 2) ? 0.5 : -0.5, (i & 4) ? 0.5 : -0.5);
    box.points.push_back(centre + rotation * corner.cwiseProduct(size));
  }
  box.triangles = { { 0, 2, 1 }, { 1, 2, 3 }, { 4, 5, 6 }, { 5, 7, 6 }, { 0, 1, 4 }, { 1, 5, 4 },
    { 2, 6, 3 }, { 3, 6, 7 }, { 0, 4, 2 }, { 2, 4, 6 }, { 1, 3, 5 }, { 3, 7, 5 } };
  return box;
}

/// Splits every triangle into four at its edge midpoints (the surface does not change).
TriangleMesh Subdivide(const TriangleMesh& mesh)
{
  TriangleMesh out;
  out.points = mesh.points;
  std::map<std::pair<int, int>, int> midpoints;
  const auto midpoint = [&](int a, int b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    const auto found = midpoints.find(key);
    if (found != midpoints.end())
    {
      return found->second;
    }
    out.points.push_back(0.5 * (mesh.points[a] + mesh.points[b]));
    const int index = static_cast<int>(out.points.size()) - 1;
    midpoints.emplace(key, index);
    return index;
  };
  for (const auto& t : mesh.triangles)
  {
    const int ab = midpoint(t[0], t[1]), bc = midpoint(t[1], t[2]), ca = midpoint(t[2], t[0]);
    out.triangles.push_back({ t[0], ab, ca });
    out.triangles.push_back({ ab, t[1], bc });
    out.triangles.push_back({ ca, bc, t[2] });
    out.triangles.push_back({ ab, bc, ca });
  }
  return out;
}

/// An icosphere: the icosahedron subdivided `levels` times, points pushed onto the sphere.
TriangleMesh MakeIcosphere(const Vec3& centre, double radius, int levels)
{
  const double g = (1.0 + std::sqrt(5.0)) / 2.0;
  TriangleMesh unit;
  unit.points = { { -1, g, 0 }, { 1, g, 0 }, { -1, -g, 0 }, { 1, -g, 0 }, { 0, -1, g }, { 0, 1, g },
    { 0, -1, -g }, { 0, 1, -g }, { g, 0, -1 }, { g, 0, 1 }, { -g, 0, -1 }, { -g, 0, 1 } };
  unit.triangles = { { 0, 11, 5 }, { 0, 5, 1 }, { 0, 1, 7 }, { 0, 7, 10 }, { 0, 10, 11 },
    { 1, 5, 9 }, { 5, 11, 4 }, { 11, 10, 2 }, { 10, 7, 6 }, { 7, 1, 8 }, { 3, 9, 4 }, { 3, 4, 2 },
    { 3, 2, 6 }, { 3, 6, 8 }, { 3, 8, 9 }, { 4, 9, 5 }, { 2, 4, 11 }, { 6, 2, 10 }, { 8, 6, 7 },
    { 9, 8, 1 } };
  for (int level = 0; level < levels; ++level)
  {
    unit = Subdivide(unit);
  }
  for (Vec3& p : unit.points)
  {
    p = centre + radius * p.normalized();
  }
  return unit;
}

/// The unique edges of a mesh with the number of triangles using each, and whether every
/// directed edge occurs once (consistent orientation).
struct Topology
{
  std::map<std::pair<int, int>, int> edges;
  std::size_t boundaryEdges = 0;
  std::size_t nonManifoldEdges = 0;
  bool consistentlyOriented = true;
};

Topology Analyse(const TriangleMesh& mesh)
{
  Topology topology;
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : mesh.triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int a = t[k], b = t[(k + 1) % 3];
      ++topology.edges[std::make_pair(std::min(a, b), std::max(a, b))];
      if (++directed[std::make_pair(a, b)] > 1)
      {
        topology.consistentlyOriented = false;
      }
    }
  }
  for (const auto& edge : topology.edges)
  {
    topology.boundaryEdges += edge.second == 1 ? 1 : 0;
    topology.nonManifoldEdges += edge.second > 2 ? 1 : 0;
  }
  return topology;
}

double SignedVolume(const TriangleMesh& mesh)
{
  double volume = 0.0;
  for (const auto& t : mesh.triangles)
  {
    volume += mesh.points[t[0]].dot(mesh.points[t[1]].cross(mesh.points[t[2]])) / 6.0;
  }
  return volume;
}

/// Total length of the edges whose triangles' normals differ by more than `degrees`.
double SharpLength(const TriangleMesh& mesh, double degrees)
{
  std::map<std::pair<int, int>, std::vector<Vec3>> normals;
  for (const auto& t : mesh.triangles)
  {
    const Vec3 n = (mesh.points[t[1]] - mesh.points[t[0]])
                     .cross(mesh.points[t[2]] - mesh.points[t[0]])
                     .normalized();
    for (int k = 0; k < 3; ++k)
    {
      normals[std::make_pair(std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3]))]
        .push_back(n);
    }
  }
  double length = 0.0;
  for (const auto& edge : normals)
  {
    if (edge.second.size() == 2 &&
      edge.second[0].dot(edge.second[1]) < std::cos(degrees * Pi / 180))
    {
      length += (mesh.points[edge.first.first] - mesh.points[edge.first.second]).norm();
    }
  }
  return length;
}

/// Distance from p to the triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
double PointTriangleDistance(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0)
  {
    return ap.norm();
  }
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3)
  {
    return bp.norm();
  }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
  {
    return (p - (a + d1 / (d1 - d3) * ab)).norm();
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6)
  {
    return cp.norm();
  }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
  {
    return (p - (a + d2 / (d2 - d6) * ac)).norm();
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0)
  {
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  }
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

/// Largest distance from the points and triangle centroids of `from` to the surface `to`.
double SurfaceDeviation(const TriangleMesh& from, const TriangleMesh& to)
{
  std::vector<Vec3> samples = from.points;
  for (const auto& t : from.triangles)
  {
    samples.push_back((from.points[t[0]] + from.points[t[1]] + from.points[t[2]]) / 3.0);
  }
  double deviation = 0.0;
  for (const Vec3& p : samples)
  {
    double nearest = std::numeric_limits<double>::infinity();
    for (const auto& t : to.triangles)
    {
      nearest = std::min(
        nearest, PointTriangleDistance(p, to.points[t[0]], to.points[t[1]], to.points[t[2]]));
    }
    deviation = std::max(deviation, nearest);
  }
  return deviation;
}

/// The bend of every edge measured here, without EdgeBendPixels: the exact image of the edge's
/// midpoint against the segment between the images of its ends. Edges with an end or the midpoint
/// without a reflection, or with both ends outside the image, are not visible.
struct MidpointBends
{
  double max = 0.0;
  std::size_t visible = 0;
  std::vector<double> visibleLengths;
  std::vector<double> hiddenLengths;
};

MidpointBends MeasureMidpoints(const TriangleMesh& mesh, const Projector& projector)
{
  MidpointBends bends;
  for (const auto& edge : Analyse(mesh).edges)
  {
    const Vec3& a = mesh.points[edge.first.first];
    const Vec3& b = mesh.points[edge.first.second];
    const ProjectedPoint pa = projector.ProjectWorld(a);
    const ProjectedPoint pb = projector.ProjectWorld(b);
    const ProjectedPoint pm = projector.ProjectWorld(0.5 * (a + b));
    const bool visible = HasProjection(pa.status) && HasProjection(pb.status) &&
      HasProjection(pm.status) &&
      (pa.status == ProjectionStatus::Valid || pb.status == ProjectionStatus::Valid);
    (visible ? bends.visibleLengths : bends.hiddenLengths).push_back((a - b).norm());
    if (visible)
    {
      const Vec2 ab = pb.pixel - pa.pixel;
      const double t =
        std::clamp((pm.pixel - pa.pixel).dot(ab) / std::max(ab.squaredNorm(), 1e-300), 0.0, 1.0);
      bends.max = std::max(bends.max, (pm.pixel - (pa.pixel + t * ab)).norm());
      ++bends.visible;
    }
  }
  return bends;
}

double Mean(const std::vector<double>& values)
{
  double sum = 0.0;
  for (double v : values)
  {
    sum += v;
  }
  return values.empty() ? 0.0 : sum / static_cast<double>(values.size());
}

/// Midpoint subdivision of `mesh` until every visible edge bends at most `tolerance`: the uniform
/// mesh (same refinement everywhere) that meets the tolerance.
TriangleMesh UniformMeetingTolerance(
  const TriangleMesh& mesh, const EdgeErrorFunction& edgeError, double tolerance)
{
  TriangleMesh uniform = mesh;
  for (int level = 0; level < 8; ++level)
  {
    double maxError = 0.0, meanError = 0.0;
    std::size_t visible = 0;
    MeasureEdgeError(uniform, edgeError, maxError, meanError, visible);
    if (maxError <= tolerance)
    {
      return uniform;
    }
    uniform = Subdivide(uniform);
  }
  ADD_FAILURE() << "no uniform subdivision meets " << tolerance << " px";
  return uniform;
}

/// Remeshes and checks what must hold for every placement; returns the result.
ScreenSpaceResult RemeshAndCheck(const std::string& name, const TriangleMesh& input,
  const Projector& projector, const ScreenSpaceOptions& options)
{
  const EdgeErrorFunction edgeError = [&projector](const Vec3& a, const Vec3& b) {
    return EdgeBendPixels(projector, a, b);
  };
  const auto start = std::chrono::steady_clock::now();
  const ScreenSpaceResult result = RemeshToPixelTolerance(input, edgeError, options);
  const double seconds =
    std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_TRUE(result.ok) << name << ": " << result.error;
  EXPECT_TRUE(result.error.empty()) << name;
  EXPECT_GT(result.mesh.NumberOfTriangles(), 0u) << name;
  EXPECT_GT(result.visibleEdges, 0u) << name;
  EXPECT_LE(result.maxError, options.tolerance) << name;
  EXPECT_LE(result.meanError, result.maxError) << name;
  EXPECT_GT(result.meanError, 0.0) << name;
  EXPECT_GE(result.iterations, 1) << name;

  // The same numbers, measured here.
  const MidpointBends measured = MeasureMidpoints(result.mesh, projector);
  EXPECT_LE(measured.max, options.tolerance) << name;
  EXPECT_NEAR(measured.max, result.maxError, 1e-9) << name;
  EXPECT_EQ(measured.visible, result.visibleEdges) << name;
  double maxError = -1.0, meanError = -1.0;
  std::size_t visible = 0;
  MeasureEdgeError(result.mesh, edgeError, maxError, meanError, visible);
  EXPECT_DOUBLE_EQ(maxError, result.maxError) << name;
  EXPECT_DOUBLE_EQ(meanError, result.meanError) << name;
  EXPECT_EQ(visible, result.visibleEdges) << name;

  // A closed, consistently oriented manifold, like the input.
  const Topology topology = Analyse(result.mesh);
  EXPECT_EQ(topology.boundaryEdges, 0u) << name;
  EXPECT_EQ(topology.nonManifoldEdges, 0u) << name;
  EXPECT_TRUE(topology.consistentlyOriented) << name;
  EXPECT_GT(SignedVolume(result.mesh), 0.0) << name;

  std::cout << "[ screen   ] " << name << ": " << input.NumberOfTriangles() << " -> "
            << result.mesh.NumberOfTriangles() << " triangles, max " << result.maxError
            << " px, mean " << result.meanError << " px, " << result.visibleEdges
            << " visible edges, " << result.iterations << " round(s), " << seconds << " s"
            << std::endl;
  return result;
}

struct PlacementCase
{
  double tolerance;
  ScreenSpaceResult result;
};
} // namespace

// Placement 1: a 20 x 15 x 10 cm box, 12 triangles, beside and behind the demo camera where it is
// seen in the mirror.
TEST(ScreenSpaceRemeshing, BoxInDemoCameraMeetsTolerance)
{
  const Projector projector(catar_test::DemoCameraModel());
  ASSERT_TRUE(projector.IsValid()) << projector.GetError();
  const EdgeErrorFunction edgeError = [&projector](const Vec3& a, const Vec3& b) {
    return EdgeBendPixels(projector, a, b);
  };
  const Vec3 size(0.2, 0.15, 0.1);
  const TriangleMesh box = MakeBox(size, 30.0, Vec3(0.14, -0.22, 0.87));
  double inputMax = 0.0, inputMean = 0.0;
  std::size_t inputVisible = 0;
  MeasureEdgeError(box, edgeError, inputMax, inputMean, inputVisible);
  ASSERT_EQ(inputVisible, 18u); // every edge of the box is seen
  ASSERT_GT(inputMax, 2.0);     // and bends far more than the tolerances below

  std::vector<PlacementCase> cases;
  for (double tolerance : { 1.0, 0.25 })
  {
    ScreenSpaceOptions options;
    options.tolerance = tolerance;
    options.maxEdgeLength = 1.0; // only the tolerance decides the sizes
    const std::string name = "box, " + std::to_string(tolerance) + " px";
    const ScreenSpaceResult result = RemeshAndCheck(name, box, projector, options);
    cases.push_back({ tolerance, result });
    const TriangleMesh& mesh = result.mesh;

    // The shape is kept exactly: planar faces, the same volume, every corner and the full length
    // of the twelve sharp edges.
    EXPECT_LT(SurfaceDeviation(mesh, box), 1e-12) << name;
    EXPECT_LT(SurfaceDeviation(box, mesh), 1e-12) << name;
    EXPECT_NEAR(SignedVolume(mesh), size.prod(), 1e-9 * size.prod()) << name;
    EXPECT_NEAR(SharpLength(mesh, 60.0), 4.0 * size.sum(), 1e-9) << name;
    for (const Vec3& corner : box.points)
    {
      double nearest = std::numeric_limits<double>::infinity();
      for (const Vec3& p : mesh.points)
      {
        nearest = std::min(nearest, (p - corner).norm());
      }
      EXPECT_LT(nearest, 1e-12) << name;
    }

    // Fewer triangles than the uniform subdivision that meets the same tolerance.
    const TriangleMesh uniform = UniformMeetingTolerance(box, edgeError, tolerance);
    std::cout << "[ screen   ] uniform subdivision meeting " << tolerance
              << " px: " << uniform.NumberOfTriangles() << " triangles" << std::endl;
    EXPECT_LT(2 * mesh.NumberOfTriangles(), uniform.NumberOfTriangles()) << name;
  }
  // A smaller tolerance costs more triangles.
  EXPECT_GT(cases[1].result.mesh.NumberOfTriangles(), 2 * cases[0].result.mesh.NumberOfTriangles());
}

// Placement 2: another camera (tilted mirror, distortion) and a sphere of 6 cm radius behind the
// mirror, 15 cm further along the camera-mirror axis and 10 cm off it: about half of it is hidden
// by the mirror, the rest is seen near the rim of the mirror's image, where the magnification
// changes fast.
TEST(ScreenSpaceRemeshing, SphereBehindMirrorMeetsTolerance)
{
  const CameraModel camera = TiltedCamera();
  const Projector projector(camera);
  ASSERT_TRUE(projector.IsValid()) << projector.GetError();
  const Vec3 axis = Sphere(camera.mirror).center.normalized();
  const Vec3 centre =
    camera.CameraToWorld(Sphere(camera.mirror).center + 0.15 * axis + 0.1 * axis.unitOrthogonal());
  const double radius = 0.06;
  const TriangleMesh sphere = MakeIcosphere(centre, radius, 2);

  const MidpointBends before = MeasureMidpoints(sphere, projector);
  ASSERT_GT(before.visible, 0u);
  ASSERT_GT(before.hiddenLengths.size(), 0u); // partly hidden
  ASSERT_GT(before.max, 1.0);

  std::vector<double> inputLengths = before.visibleLengths;
  inputLengths.insert(inputLengths.end(), before.hiddenLengths.begin(), before.hiddenLengths.end());
  std::vector<double> visibleMeans, hiddenMeans;
  std::vector<PlacementCase> cases;
  for (double tolerance : { 0.5, 0.1 })
  {
    ScreenSpaceOptions options;
    options.tolerance = tolerance;
    options.maxGeometricError = 2e-3; // lets the hidden part coarsen beyond the input
    const std::string name = "sphere, " + std::to_string(tolerance) + " px";
    const ScreenSpaceResult result = RemeshAndCheck(name, sphere, projector, options);
    cases.push_back({ tolerance, result });
    const TriangleMesh& mesh = result.mesh;

    // The shape stays within the geometric bound of the input, both ways.
    EXPECT_LE(SurfaceDeviation(mesh, sphere), options.maxGeometricError) << name;
    EXPECT_LE(SurfaceDeviation(sphere, mesh), options.maxGeometricError) << name;
    std::cout << "[ screen   ] " << name << ": deviation from the input "
              << SurfaceDeviation(mesh, sphere) << " m, of the input "
              << SurfaceDeviation(sphere, mesh) << " m" << std::endl;
    EXPECT_NEAR(SignedVolume(mesh), SignedVolume(sphere), 0.02 * SignedVolume(sphere)) << name;

    // The sphere looks small in the mirror, so its seen half may coarsen as far as the
    // geometric bound allows; the hidden half is bound by it alone and is never refined: its
    // edges stay at least 0.8 of the input's on average.
    const MidpointBends measured = MeasureMidpoints(mesh, projector);
    ASSERT_GT(measured.hiddenLengths.size(), 0u) << name;
    EXPECT_GT(Mean(measured.hiddenLengths), 0.8 * Mean(inputLengths)) << name;
    visibleMeans.push_back(Mean(measured.visibleLengths));
    hiddenMeans.push_back(Mean(measured.hiddenLengths));

    // Fewer triangles than the uniform subdivision that meets the same tolerance.
    const TriangleMesh uniform = UniformMeetingTolerance(
      sphere,
      [&projector](const Vec3& a, const Vec3& b) { return EdgeBendPixels(projector, a, b); },
      tolerance);
    std::cout << "[ screen   ] uniform subdivision meeting " << tolerance
              << " px: " << uniform.NumberOfTriangles() << " triangles" << std::endl;
    EXPECT_LT(2 * mesh.NumberOfTriangles(), uniform.NumberOfTriangles()) << name;
  }
  EXPECT_GT(cases[1].result.mesh.NumberOfTriangles(), 2 * cases[0].result.mesh.NumberOfTriangles());
  // The tighter tolerance refines where the sphere is seen, not where it is hidden.
  ASSERT_EQ(visibleMeans.size(), 2u);
  EXPECT_LT(visibleMeans[1], 0.8 * visibleMeans[0]);
  EXPECT_NEAR(hiddenMeans[1], hiddenMeans[0], 0.2 * hiddenMeans[0]);
}

TEST(ScreenSpaceRemeshing, RejectsBadOptionsAndInput)
{
  const TriangleMesh box = MakeBox(Vec3(0.2, 0.15, 0.1), 0.0, Vec3(0.1, -0.3, 0.9));
  const Projector projector(catar_test::DemoCameraModel());
  const EdgeErrorFunction edgeError = [&projector](const Vec3& a, const Vec3& b) {
    return EdgeBendPixels(projector, a, b);
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (double tolerance : { 0.0, -1.0, nan, inf })
  {
    ScreenSpaceOptions options;
    options.tolerance = tolerance;
    const ScreenSpaceResult result = RemeshToPixelTolerance(box, edgeError, options);
    EXPECT_FALSE(result.ok) << tolerance;
    EXPECT_NE(result.error.find("tolerance"), std::string::npos) << result.error;
    EXPECT_TRUE(result.mesh.Empty());
  }
  std::vector<ScreenSpaceOptions> bad(6);
  bad[0].minEdgeLength = -1.0;
  bad[1].maxEdgeLength = nan;
  bad[2].maxGeometricError = -inf;
  bad[3].minEdgeLength = 0.1;
  bad[3].maxEdgeLength = 0.01;
  bad[4].maxIterations = 0;
  bad[5].featureAngle = 200.0;
  for (std::size_t i = 0; i < bad.size(); ++i)
  {
    const ScreenSpaceResult result = RemeshToPixelTolerance(box, edgeError, bad[i]);
    EXPECT_FALSE(result.ok) << i;
    EXPECT_FALSE(result.error.empty()) << i;
  }
  // No edge error function; no triangles.
  EXPECT_FALSE(RemeshToPixelTolerance(box, EdgeErrorFunction(), ScreenSpaceOptions()).ok);
  const ScreenSpaceResult empty =
    RemeshToPixelTolerance(TriangleMesh(), edgeError, ScreenSpaceOptions());
  EXPECT_FALSE(empty.ok);
  EXPECT_FALSE(empty.error.empty());
  TriangleMesh pointsOnly;
  pointsOnly.points = box.points;
  EXPECT_FALSE(RemeshToPixelTolerance(pointsOnly, edgeError, ScreenSpaceOptions()).ok);
  // An edge error function that throws: an error, not an exception.
  const EdgeErrorFunction throwing = [](const Vec3&, const Vec3&) -> double {
    throw std::runtime_error("camera lost");
  };
  ScreenSpaceResult thrown;
  EXPECT_NO_THROW(thrown = RemeshToPixelTolerance(box, throwing, ScreenSpaceOptions()));
  EXPECT_FALSE(thrown.ok);
  EXPECT_NE(thrown.error.find("camera lost"), std::string::npos) << thrown.error;
}

// An object the camera does not see is bound by maxEdgeLength only: it stays coarse.
TEST(ScreenSpaceRemeshing, UnseenObjectStaysCoarse)
{
  const TriangleMesh box = MakeBox(Vec3(0.2, 0.15, 0.1), 0.0, Vec3(0.0, 0.0, 0.0));
  const EdgeErrorFunction unseen = [](const Vec3&, const Vec3&) { return -1.0; };
  ScreenSpaceOptions options;
  options.tolerance = 0.1;
  const ScreenSpaceResult result = RemeshToPixelTolerance(box, unseen, options);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.visibleEdges, 0u);
  EXPECT_EQ(result.maxError, 0.0);
  EXPECT_EQ(result.meanError, 0.0);
  // Edges at most a quarter of the diagonal (the default maxEdgeLength), and not many more
  // triangles than that needs.
  const double diagonal = Vec3(0.2, 0.15, 0.1).norm();
  const Topology topology = Analyse(result.mesh);
  for (const auto& edge : topology.edges)
  {
    EXPECT_LE((result.mesh.points[edge.first.first] - result.mesh.points[edge.first.second]).norm(),
      0.25 * diagonal * (1 + 1e-12));
  }
  EXPECT_EQ(topology.boundaryEdges, 0u);
  EXPECT_LT(result.mesh.NumberOfTriangles(), 300u);
  EXPECT_NEAR(SignedVolume(result.mesh), 0.2 * 0.15 * 0.1, 1e-12);
  std::cout << "[ screen   ] unseen box: " << result.mesh.NumberOfTriangles() << " triangles"
            << std::endl;
}

// A tolerance that the minimum edge length does not allow: ok, the achieved error is reported
// and a warning says why.
TEST(ScreenSpaceRemeshing, ReportsUnreachableTolerance)
{
  const Projector projector(catar_test::DemoCameraModel());
  const EdgeErrorFunction edgeError = [&projector](const Vec3& a, const Vec3& b) {
    return EdgeBendPixels(projector, a, b);
  };
  const TriangleMesh box = MakeBox(Vec3(0.2, 0.15, 0.1), 30.0, Vec3(0.14, -0.22, 0.87));
  ScreenSpaceOptions options;
  options.tolerance = 1e-3;
  options.minEdgeLength = 0.03;
  const ScreenSpaceResult result = RemeshToPixelTolerance(box, edgeError, options);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_GT(result.maxError, options.tolerance);
  EXPECT_FALSE(result.warnings.empty());
  // Only edges too short to be split bend more than the tolerance.
  for (const auto& edge : Analyse(result.mesh).edges)
  {
    const Vec3& a = result.mesh.points[edge.first.first];
    const Vec3& b = result.mesh.points[edge.first.second];
    if (edgeError(a, b) > options.tolerance)
    {
      EXPECT_LE((a - b).norm(), options.minEdgeLength);
    }
  }
  // A budget below what the tolerance needs: refused at once, with the estimate and the key that
  // raises it (before, refinement ran to the budget: minutes and gigabytes for a large one).
  options.minEdgeLength = 0.0;
  options.maxTriangles = 500;
  const ScreenSpaceResult budget = RemeshToPixelTolerance(box, edgeError, options);
  EXPECT_FALSE(budget.ok);
  EXPECT_GT(budget.estimatedTriangles, 500.0);
  EXPECT_NE(budget.error.find("max_triangles"), std::string::npos) << budget.error;
  EXPECT_TRUE(budget.mesh.Empty());
}

// The estimate of the triangles a tolerance needs is of the size refinement makes.
TEST(ScreenSpaceRemeshing, EstimatesTheTrianglesAToleranceNeeds)
{
  const Projector projector(catar_test::DemoCameraModel());
  const EdgeErrorFunction edgeError = [&projector](const Vec3& a, const Vec3& b) {
    return EdgeBendPixels(projector, a, b);
  };
  const TriangleMesh box = MakeBox(Vec3(0.2, 0.15, 0.1), 30.0, Vec3(0.14, -0.22, 0.87));
  for (const double tolerance : { 0.1, 0.03, 0.01 })
  {
    ScreenSpaceOptions options;
    options.tolerance = tolerance;
    options.relax = false;
    options.maxIterations = 1;
    const ScreenSpaceResult result = RemeshToPixelTolerance(box, edgeError, options);
    ASSERT_TRUE(result.ok) << result.error;
    const double made = static_cast<double>(result.mesh.NumberOfTriangles());
    std::cout << "tolerance " << tolerance << ": estimated " << result.estimatedTriangles
              << " triangles, made " << made << "\n";
    EXPECT_GT(result.estimatedTriangles, made / 4.0) << tolerance;
    EXPECT_LT(result.estimatedTriangles, made * 4.0) << tolerance;
  }
}

// An open surface keeps its boundary; point data follow; progress is reported.
TEST(ScreenSpaceRemeshing, OpenSurfaceKeepsBoundaryAndPointData)
{
  const Projector projector(catar_test::DemoCameraModel());
  const EdgeErrorFunction edgeError = [&projector](const Vec3& a, const Vec3& b) {
    return EdgeBendPixels(projector, a, b);
  };
  // The top of the demo box alone: an open 20 x 15 cm rectangle (2 triangles), with a scalar
  // that varies linearly over it.
  TriangleMesh patch = MakeBox(Vec3(0.2, 0.15, 0.1), 30.0, Vec3(0.14, -0.22, 0.87));
  patch.triangles = { { 4, 5, 6 }, { 5, 7, 6 } };
  patch.points.erase(patch.points.begin(), patch.points.begin() + 4);
  for (auto& t : patch.triangles)
  {
    for (int& i : t)
    {
      i -= 4;
    }
  }
  PointAttribute height{ "u", 1, {} };
  for (const Vec3& p : patch.points)
  {
    height.values.push_back(3.0 * p.x() - 2.0 * p.y());
  }
  patch.pointData.push_back(height);

  std::vector<double> fractions;
  ScreenSpaceOptions options;
  options.tolerance = 0.25;
  options.progressData = &fractions;
  options.progress = [](double fraction, void* data) {
    static_cast<std::vector<double>*>(data)->push_back(fraction);
  };
  const ScreenSpaceResult result = RemeshToPixelTolerance(patch, edgeError, options);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_LE(result.maxError, options.tolerance);
  EXPECT_GT(result.mesh.NumberOfTriangles(), 2u);

  // The boundary is the same rectangle: its length, and its four corners.
  const Topology topology = Analyse(result.mesh);
  double boundary = 0.0;
  for (const auto& edge : topology.edges)
  {
    if (edge.second == 1)
    {
      boundary +=
        (result.mesh.points[edge.first.first] - result.mesh.points[edge.first.second]).norm();
    }
  }
  EXPECT_NEAR(boundary, 2.0 * (0.2 + 0.15), 1e-9);
  EXPECT_TRUE(topology.consistentlyOriented);

  ASSERT_EQ(result.mesh.pointData.size(), 1u);
  EXPECT_EQ(result.mesh.pointData[0].name, "u");
  ASSERT_EQ(result.mesh.pointData[0].values.size(), result.mesh.NumberOfPoints());
  for (std::size_t i = 0; i < result.mesh.NumberOfPoints(); ++i)
  {
    const Vec3& p = result.mesh.points[i];
    EXPECT_NEAR(result.mesh.pointData[0].values[i], 3.0 * p.x() - 2.0 * p.y(), 1e-9);
  }

  ASSERT_GE(fractions.size(), 2u);
  EXPECT_EQ(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
}

// MeasureEdgeError counts each edge once and skips edges the function does not see.
TEST(ScreenSpaceRemeshing, MeasureEdgeErrorCountsEachEdgeOnce)
{
  const TriangleMesh box = MakeBox(Vec3(1.0, 1.0, 1.0), 0.0, Vec3::Zero());
  // Bend = edge length for edges in the upper half (z > -0.5 at both ends), else unseen.
  const EdgeErrorFunction lengthAbove = [](const Vec3& a, const Vec3& b) {
    return a.z() > 0.0 && b.z() > 0.0 ? (a - b).norm() : -1.0;
  };
  double maxError = 0.0, meanError = 0.0;
  std::size_t visible = 0;
  MeasureEdgeError(box, lengthAbove, maxError, meanError, visible);
  // The top face: 4 sides of length 1 and a diagonal of sqrt(2).
  EXPECT_EQ(visible, 5u);
  EXPECT_DOUBLE_EQ(maxError, std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(meanError, (4.0 + std::sqrt(2.0)) / 5.0);
  MeasureEdgeError(TriangleMesh(), lengthAbove, maxError, meanError, visible);
  EXPECT_EQ(visible, 0u);
  EXPECT_EQ(maxError, 0.0);
}
