// Tests of catar::mesh::SurfaceFromPoints: convex hulls of boxes and spheres, the advancing front
// reconstruction of a torus (which must keep its hole), and bad input.
#include "PointSetSurface.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <utility>

namespace
{
using catar::Vec3;
using catar::mesh::PointSetMethod;
using catar::mesh::PointSetOptions;
using catar::mesh::PointSetResult;
using catar::mesh::SurfaceFromPoints;
using catar::mesh::TriangleMesh;

/// Signed volume by the divergence theorem: positive only when the triangles face outward.
double SignedVolume(const TriangleMesh& mesh)
{
  double volume = 0.0;
  for (const auto& t : mesh.triangles)
  {
    volume += mesh.points[t[0]].dot(mesh.points[t[1]].cross(mesh.points[t[2]])) / 6.0;
  }
  return volume;
}

/// Undirected edges and how many triangles use each.
std::map<std::pair<int, int>, int> EdgeUses(const TriangleMesh& mesh)
{
  std::map<std::pair<int, int>, int> uses;
  for (const auto& t : mesh.triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      const int a = t[k];
      const int b = t[(k + 1) % 3];
      ++uses[std::make_pair(std::min(a, b), std::max(a, b))];
    }
  }
  return uses;
}

std::size_t BoundaryEdges(const TriangleMesh& mesh)
{
  std::size_t count = 0;
  for (const auto& edge : EdgeUses(mesh))
  {
    count += edge.second == 1 ? 1 : 0;
  }
  return count;
}

/// V - E + F: 2 for a closed sphere-like surface, 0 for a closed torus.
long EulerCharacteristic(const TriangleMesh& mesh)
{
  return static_cast<long>(mesh.NumberOfPoints()) - static_cast<long>(EdgeUses(mesh).size()) +
    static_cast<long>(mesh.NumberOfTriangles());
}

/// True when no directed edge appears twice: neighbouring triangles are oriented consistently.
bool ConsistentlyOriented(const TriangleMesh& mesh)
{
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : mesh.triangles)
  {
    for (int k = 0; k < 3; ++k)
    {
      if (++directed[std::make_pair(t[k], t[(k + 1) % 3])] > 1)
      {
        return false;
      }
    }
  }
  return true;
}

/// Generalised winding number of the surface around q (solid angles, Van Oosterom-Strackee):
/// 1 inside a closed outward surface, 0 outside.
double WindingNumber(const TriangleMesh& mesh, const Vec3& q)
{
  double solidAngle = 0.0;
  for (const auto& t : mesh.triangles)
  {
    const Vec3 a = mesh.points[t[0]] - q;
    const Vec3 b = mesh.points[t[1]] - q;
    const Vec3 c = mesh.points[t[2]] - q;
    const double la = a.norm();
    const double lb = b.norm();
    const double lc = c.norm();
    solidAngle += 2.0 *
      std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + b.dot(c) * la + c.dot(a) * lb);
  }
  return solidAngle / (4.0 * M_PI);
}

/// Every mesh point is the input point its pointIds entry names.
void ExpectPointsFromInput(const PointSetResult& result, const std::vector<Vec3>& input)
{
  ASSERT_EQ(result.pointIds.size(), result.mesh.NumberOfPoints());
  for (std::size_t i = 0; i < result.mesh.NumberOfPoints(); ++i)
  {
    ASSERT_GE(result.pointIds[i], 0);
    ASSERT_LT(static_cast<std::size_t>(result.pointIds[i]), input.size());
    EXPECT_EQ(result.mesh.points[i], input[result.pointIds[i]]) << "mesh point " << i;
  }
}

/// True when some warning contains the text.
bool HasWarning(const PointSetResult& result, const std::string& text)
{
  for (const std::string& warning : result.warnings)
  {
    if (warning.find(text) != std::string::npos)
    {
      return true;
    }
  }
  return false;
}

/// The 8 corners of an axis-aligned box from lo to hi.
std::vector<Vec3> BoxCorners(const Vec3& lo, const Vec3& hi)
{
  std::vector<Vec3> corners;
  for (int k = 0; k < 8; ++k)
  {
    corners.emplace_back(
      (k & 1) ? hi.x() : lo.x(), (k & 2) ? hi.y() : lo.y(), (k & 4) ? hi.z() : lo.z());
  }
  return corners;
}

std::vector<Vec3> SpherePoints(int count, const Vec3& center, double radius, unsigned seed)
{
  std::mt19937 random(seed);
  std::normal_distribution<double> normal;
  std::vector<Vec3> points;
  while (static_cast<int>(points.size()) < count)
  {
    const Vec3 d(normal(random), normal(random), normal(random));
    if (d.norm() > 1e-6)
    {
      points.push_back(center + radius * d.normalized());
    }
  }
  return points;
}

/// Points uniformly distributed over the area of the torus of ring radius R and tube radius r
/// around the z axis (rejection on the area element (R + r cos v)).
std::vector<Vec3> TorusPoints(int count, double R, double r, unsigned seed)
{
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * M_PI);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Vec3> points;
  while (static_cast<int>(points.size()) < count)
  {
    const double u = angle(random);
    const double v = angle(random);
    if (unit(random) * (R + r) <= R + r * std::cos(v))
    {
      points.emplace_back(
        (R + r * std::cos(v)) * std::cos(u), (R + r * std::cos(v)) * std::sin(u), r * std::sin(v));
    }
  }
  return points;
}

PointSetOptions Options(PointSetMethod method)
{
  PointSetOptions options;
  options.method = method;
  return options;
}

TEST(PointSetSurfaceConvexHull, BoxCornersWithInteriorPoints)
{
  const Vec3 lo(-1.0, 0.5, 2.0);
  const Vec3 hi(1.0, 1.5, 2.5); // 2 x 1 x 0.5
  std::vector<Vec3> points = BoxCorners(lo, hi);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> unit(0.01, 0.99);
  for (int i = 0; i < 300; ++i)
  {
    points.push_back(lo + Vec3(unit(random), unit(random), unit(random)).cwiseProduct(hi - lo));
  }

  const PointSetResult result = SurfaceFromPoints(points, Options(PointSetMethod::ConvexHull));
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_TRUE(result.warnings.empty());
  EXPECT_TRUE(result.closed);
  EXPECT_EQ(result.mesh.NumberOfTriangles(), 12u);
  EXPECT_EQ(result.mesh.NumberOfPoints(), 8u);
  EXPECT_EQ(BoundaryEdges(result.mesh), 0u);
  EXPECT_EQ(EulerCharacteristic(result.mesh), 2);
  EXPECT_TRUE(ConsistentlyOriented(result.mesh));
  EXPECT_NEAR(SignedVolume(result.mesh), 1.0, 1e-12);
  ExpectPointsFromInput(result, points);
  for (int id : result.pointIds)
  {
    EXPECT_LT(id, 8) << "an interior point is on the hull";
  }
}

TEST(PointSetSurfaceConvexHull, SphereIsClosedAndOutward)
{
  const Vec3 center(0.3, -0.2, 1.0);
  const std::vector<Vec3> points = SpherePoints(2000, center, 0.5, 11);
  const PointSetResult result = SurfaceFromPoints(points, Options(PointSetMethod::ConvexHull));
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_TRUE(result.closed);
  EXPECT_EQ(result.mesh.NumberOfPoints(), 2000u); // every point of a sphere is extreme
  EXPECT_EQ(BoundaryEdges(result.mesh), 0u);
  EXPECT_EQ(EulerCharacteristic(result.mesh), 2);
  EXPECT_TRUE(ConsistentlyOriented(result.mesh));
  ExpectPointsFromInput(result, points);

  std::size_t inward = 0;
  for (const auto& t : result.mesh.triangles)
  {
    const Vec3& p0 = result.mesh.points[t[0]];
    const Vec3 normal = (result.mesh.points[t[1]] - p0).cross(result.mesh.points[t[2]] - p0);
    const Vec3 centroid = (p0 + result.mesh.points[t[1]] + result.mesh.points[t[2]]) / 3.0 - center;
    inward += normal.dot(centroid) > 0.0 ? 0 : 1;
  }
  EXPECT_EQ(inward, 0u);
  // An inscribed polyhedron: a little less than the sphere's volume.
  const double sphereVolume = 4.0 / 3.0 * M_PI * 0.125;
  EXPECT_LT(SignedVolume(result.mesh), sphereVolume);
  EXPECT_GT(SignedVolume(result.mesh), 0.99 * sphereVolume);
}

TEST(PointSetSurfaceConvexHull, PaperParallelepiped)
{
  // The demo scene's parallelepiped: 30 x 12 x 9 cm, turned 30 degrees about z, then moved.
  const Eigen::Matrix3d rotation =
    Eigen::AngleAxisd(30.0 * M_PI / 180.0, Vec3::UnitZ()).toRotationMatrix();
  const Vec3 translation(0.14, -0.22, 0.87);
  std::vector<Vec3> points;
  for (const Vec3& corner : BoxCorners(Vec3(-0.15, -0.06, -0.045), Vec3(0.15, 0.06, 0.045)))
  {
    points.push_back(rotation * corner + translation);
  }

  const PointSetResult result = SurfaceFromPoints(points, Options(PointSetMethod::ConvexHull));
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_TRUE(result.closed);
  EXPECT_EQ(result.mesh.NumberOfTriangles(), 12u);
  EXPECT_EQ(result.mesh.NumberOfPoints(), 8u);
  EXPECT_TRUE(ConsistentlyOriented(result.mesh));
  EXPECT_NEAR(SignedVolume(result.mesh), 0.30 * 0.12 * 0.09, 1e-12);
  ExpectPointsFromInput(result, points);

  // Two triangles on each of the 6 faces: each normal is one of the box's outward face normals.
  std::map<int, int> perFace;
  for (const auto& t : result.mesh.triangles)
  {
    const Vec3& p0 = result.mesh.points[t[0]];
    const Vec3 normal =
      (result.mesh.points[t[1]] - p0).cross(result.mesh.points[t[2]] - p0).normalized();
    const Vec3 local = rotation.transpose() * normal;
    int axis = 0;
    local.cwiseAbs().maxCoeff(&axis);
    EXPECT_NEAR(std::abs(local[axis]), 1.0, 1e-9) << "a triangle across a face";
    const Vec3 faceCenter = (p0 + result.mesh.points[t[1]] + result.mesh.points[t[2]]) / 3.0;
    EXPECT_GT(normal.dot(faceCenter - translation), 0.0) << "an inward triangle";
    ++perFace[2 * axis + (local[axis] > 0.0 ? 1 : 0)];
  }
  EXPECT_EQ(perFace.size(), 6u);
  for (const auto& face : perFace)
  {
    EXPECT_EQ(face.second, 2) << "face " << face.first;
  }
}

TEST(PointSetSurfaceAdvancingFront, TorusKeepsItsHole)
{
  const double R = 1.0;
  const double r = 0.3;
  const std::vector<Vec3> points = TorusPoints(3000, R, r, 5);
  const PointSetResult result = SurfaceFromPoints(points, Options(PointSetMethod::AdvancingFront));
  ASSERT_TRUE(result.ok) << result.error;
  ExpectPointsFromInput(result, points);
  EXPECT_TRUE(ConsistentlyOriented(result.mesh));
  const std::size_t boundary = BoundaryEdges(result.mesh);
  EXPECT_EQ(result.closed, boundary == 0);
  EXPECT_EQ(HasWarning(result, "not closed"), !result.closed);
  EXPECT_LE(boundary, 30u);
  if (result.closed)
  {
    EXPECT_EQ(EulerCharacteristic(result.mesh), 0); // genus 1
  }
  EXPECT_GE(result.mesh.NumberOfPoints(), 2950u);

  double farthest = 0.0;
  for (const Vec3& p : result.mesh.points)
  {
    const double ring = std::hypot(p.x(), p.y()) - R;
    farthest = std::max(farthest, std::abs(std::hypot(ring, p.z()) - r));
  }
  EXPECT_LT(farthest, 1e-9);

  const double torusVolume = 2.0 * M_PI * M_PI * R * r * r;
  const double volume = SignedVolume(result.mesh);
  EXPECT_NEAR(volume, torusVolume, 0.1 * torusVolume);
  // The hole is kept: the centre is outside, the middle of the tube inside.
  EXPECT_NEAR(WindingNumber(result.mesh, Vec3::Zero()), 0.0, 0.05);
  EXPECT_NEAR(WindingNumber(result.mesh, Vec3(R, 0.0, 0.0)), 1.0, 0.05);
  EXPECT_NEAR(WindingNumber(result.mesh, Vec3(0.0, -R, 0.0)), 1.0, 0.05);

  // The convex hull of the same points fills the hole: the test above tells the methods apart.
  const PointSetResult hull = SurfaceFromPoints(points, Options(PointSetMethod::ConvexHull));
  ASSERT_TRUE(hull.ok) << hull.error;
  EXPECT_NEAR(WindingNumber(hull.mesh, Vec3::Zero()), 1.0, 1e-6);
}

TEST(PointSetSurfaceAdvancingFront, SphereIsClosedAndOutward)
{
  const Vec3 center(-0.4, 0.1, 0.6);
  const std::vector<Vec3> points = SpherePoints(1500, center, 0.2, 3);
  const PointSetResult result = SurfaceFromPoints(points, Options(PointSetMethod::AdvancingFront));
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_TRUE(result.closed);
  EXPECT_EQ(BoundaryEdges(result.mesh), 0u);
  EXPECT_EQ(EulerCharacteristic(result.mesh), 2);
  EXPECT_TRUE(ConsistentlyOriented(result.mesh));
  ExpectPointsFromInput(result, points);
  const double sphereVolume = 4.0 / 3.0 * M_PI * 0.008;
  EXPECT_NEAR(SignedVolume(result.mesh), sphereVolume, 0.02 * sphereVolume);
  EXPECT_NEAR(WindingNumber(result.mesh, center), 1.0, 1e-6);
}

TEST(PointSetSurfaceAdvancingFront, OpenHemisphereIsOrientedWithWarning)
{
  const Vec3 center(0.0, 0.0, 0.0);
  std::vector<Vec3> points;
  for (const Vec3& p : SpherePoints(3000, center, 1.0, 17))
  {
    if (p.z() > 0.0)
    {
      points.push_back(p);
    }
  }
  const PointSetResult result = SurfaceFromPoints(points, Options(PointSetMethod::AdvancingFront));
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_FALSE(result.closed);
  EXPECT_TRUE(HasWarning(result, "not closed"));
  EXPECT_GT(BoundaryEdges(result.mesh), 0u);
  EXPECT_EQ(EulerCharacteristic(result.mesh), 1); // a disc
  EXPECT_TRUE(ConsistentlyOriented(result.mesh));
  std::size_t inward = 0;
  for (const auto& t : result.mesh.triangles)
  {
    const Vec3& p0 = result.mesh.points[t[0]];
    const Vec3 normal = (result.mesh.points[t[1]] - p0).cross(result.mesh.points[t[2]] - p0);
    inward += normal.dot(p0 - center) > 0.0 ? 0 : 1;
  }
  EXPECT_EQ(inward, 0u);
}

TEST(PointSetSurfaceBadInput, EmptyInput)
{
  for (PointSetMethod method : { PointSetMethod::ConvexHull, PointSetMethod::AdvancingFront })
  {
    const PointSetResult result = SurfaceFromPoints({}, Options(method));
    EXPECT_FALSE(result.ok);
    EXPECT_NE(result.error.find("at least 4"), std::string::npos) << result.error;
    EXPECT_TRUE(result.mesh.Empty());
  }
}

TEST(PointSetSurfaceBadInput, ThreePoints)
{
  const std::vector<Vec3> points = { Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0) };
  const PointSetResult result = SurfaceFromPoints(points, Options(PointSetMethod::ConvexHull));
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.error.find("at least 4"), std::string::npos) << result.error;
  EXPECT_NE(result.error.find("got 3"), std::string::npos) << result.error;
  EXPECT_TRUE(result.mesh.Empty());
}

TEST(PointSetSurfaceBadInput, CoplanarPoints)
{
  // A grid on a tilted plane: rounding puts the rotated points slightly off the plane, which the
  // tolerance must still take as coplanar; and an exactly planar grid.
  const Eigen::Matrix3d tilt =
    Eigen::AngleAxisd(0.7, Vec3(1.0, 2.0, 3.0).normalized()).toRotationMatrix();
  std::vector<Vec3> tilted;
  std::vector<Vec3> flat;
  for (int i = 0; i < 10; ++i)
  {
    for (int j = 0; j < 10; ++j)
    {
      tilted.push_back(tilt * Vec3(0.1 * i, 0.13 * j, 0.0) + Vec3(3.0, -1.0, 2.0));
      flat.emplace_back(0.1 * i, 0.5, 0.13 * j);
    }
  }
  const std::vector<Vec3> collinear = { Vec3(0, 0, 0), Vec3(1, 1, 1), Vec3(2, 2, 2),
    Vec3(-3, -3, -3), Vec3(0.5, 0.5, 0.5) };
  for (const auto& points : { tilted, flat, collinear })
  {
    for (PointSetMethod method : { PointSetMethod::ConvexHull, PointSetMethod::AdvancingFront })
    {
      const PointSetResult result = SurfaceFromPoints(points, Options(method));
      EXPECT_FALSE(result.ok);
      EXPECT_NE(result.error.find("coplanar"), std::string::npos) << result.error;
      EXPECT_TRUE(result.mesh.Empty());
    }
  }
  // A thin but real slab (1e-6 of its size) is accepted.
  std::vector<Vec3> slab = flat;
  slab.emplace_back(0.45, 0.5 + 1e-6, 0.6);
  const PointSetResult result = SurfaceFromPoints(slab, Options(PointSetMethod::ConvexHull));
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_TRUE(result.closed);
  EXPECT_GT(SignedVolume(result.mesh), 0.0);
}

TEST(PointSetSurfaceBadInput, NonFinitePointsDropped)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<Vec3> points = BoxCorners(Vec3(0, 0, 0), Vec3(1, 2, 3));
  points.insert(points.begin() + 3, Vec3(nan, 0.0, 0.0));
  points.insert(points.begin(), Vec3(0.5, inf, 0.5));
  points.emplace_back(0.5, 0.5, -inf);
  const PointSetResult result = SurfaceFromPoints(points, Options(PointSetMethod::ConvexHull));
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_TRUE(HasWarning(result, "dropped 3 of 11 points with NaN or infinite coordinates"));
  EXPECT_EQ(result.mesh.NumberOfTriangles(), 12u);
  EXPECT_NEAR(SignedVolume(result.mesh), 6.0, 1e-12);
  ExpectPointsFromInput(result, points);

  // Too few left once the NaN are dropped.
  const std::vector<Vec3> mostlyNan = { Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0),
    Vec3(nan, nan, nan), Vec3(0, 0, nan) };
  const PointSetResult failed = SurfaceFromPoints(mostlyNan, Options(PointSetMethod::ConvexHull));
  EXPECT_FALSE(failed.ok);
  EXPECT_NE(failed.error.find("got 3 (of 5)"), std::string::npos) << failed.error;
  EXPECT_TRUE(HasWarning(failed, "NaN"));
}

TEST(PointSetSurfaceBadInput, DuplicatesDropped)
{
  const std::vector<Vec3> corners = BoxCorners(Vec3(-1, -1, -1), Vec3(1, 1, 1));
  std::vector<Vec3> points;
  for (int copy = 0; copy < 3; ++copy)
  {
    points.insert(points.end(), corners.begin(), corners.end());
  }
  for (PointSetMethod method : { PointSetMethod::ConvexHull, PointSetMethod::AdvancingFront })
  {
    const PointSetResult result = SurfaceFromPoints(points, Options(method));
    ASSERT_TRUE(result.ok) << result.error;
    EXPECT_TRUE(HasWarning(result, "dropped 16 duplicate points"));
    EXPECT_TRUE(result.closed);
    EXPECT_EQ(result.mesh.NumberOfPoints(), 8u);
    EXPECT_EQ(result.mesh.NumberOfTriangles(), 12u);
    EXPECT_NEAR(SignedVolume(result.mesh), 8.0, 1e-12);
    ExpectPointsFromInput(result, points);
    for (int id : result.pointIds)
    {
      EXPECT_LT(id, 8) << "the first occurrence is kept";
    }
  }

  // Four copies of a triangle are three distinct points.
  std::vector<Vec3> triangle;
  for (int copy = 0; copy < 4; ++copy)
  {
    triangle.insert(triangle.end(), { Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0) });
  }
  const PointSetResult failed = SurfaceFromPoints(triangle, Options(PointSetMethod::ConvexHull));
  EXPECT_FALSE(failed.ok);
  EXPECT_NE(failed.error.find("at least 4"), std::string::npos) << failed.error;
  EXPECT_TRUE(HasWarning(failed, "dropped 9 duplicate points"));
}

TEST(PointSetSurfaceBadInput, HugeCoordinates)
{
  // Finite, but their extent overflows: an error rather than NaN geometry.
  const std::vector<Vec3> points = { Vec3(1e300, 0, 0), Vec3(-1e300, 0, 0), Vec3(0, 1e300, 0),
    Vec3(0, 0, 1e300) };
  const PointSetResult result = SurfaceFromPoints(points, Options(PointSetMethod::ConvexHull));
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.error.find("too large"), std::string::npos) << result.error;
  EXPECT_TRUE(result.mesh.Empty());
}

TEST(PointSetSurfaceBadInput, BadOptions)
{
  const std::vector<Vec3> points = SpherePoints(200, Vec3::Zero(), 1.0, 1);
  PointSetOptions options = Options(PointSetMethod::AdvancingFront);
  options.radiusRatioBound = std::numeric_limits<double>::quiet_NaN();
  PointSetResult result = SurfaceFromPoints(points, options);
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.error.find("radiusRatioBound"), std::string::npos) << result.error;

  options = Options(PointSetMethod::AdvancingFront);
  options.beta = -1.0;
  result = SurfaceFromPoints(points, options);
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.error.find("beta"), std::string::npos) << result.error;

  result = SurfaceFromPoints(points, Options(static_cast<PointSetMethod>(7)));
  EXPECT_FALSE(result.ok);
  EXPECT_NE(result.error.find("unknown point set method"), std::string::npos) << result.error;
}

} // namespace
