// Tests of RepairMesh: one bad-input kind per test, with the exact counts of the report, the
// warning line it must add, and the properties of the result (closed, consistently oriented,
// outward, point data still on their points).
#include "MeshPrepTestUtilities.h"
#include "MeshRepair.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace
{
using catar::Vec3;
using catar::mesh::RepairMesh;
using catar::mesh::RepairReport;
using catar::mesh::TriangleMesh;
using catar::mesh::Warnings;
using namespace catar_test;

constexpr double kSx = 0.2;
constexpr double kSy = 0.1;
constexpr double kSz = 0.05;

/// Repairs `mesh`, expecting success.
RepairReport Repair(TriangleMesh& mesh, Warnings& warnings)
{
  RepairReport report;
  std::string error;
  EXPECT_TRUE(RepairMesh(mesh, report, warnings, error)) << error;
  EXPECT_TRUE(error.empty());
  return report;
}

/// The report fields that are not expected to change, all zero.
void ExpectNothingElse(const RepairReport& r, const std::string& except)
{
  if (except != "invalidPoints")
  {
    EXPECT_EQ(r.invalidPoints, 0u);
  }
  if (except != "invalidTriangles")
  {
    EXPECT_EQ(r.invalidTriangles, 0u);
  }
  if (except != "mergedPoints")
  {
    EXPECT_EQ(r.mergedPoints, 0u);
  }
  if (except != "degenerateTriangles")
  {
    EXPECT_EQ(r.degenerateTriangles, 0u);
  }
  if (except != "duplicateTriangles")
  {
    EXPECT_EQ(r.duplicateTriangles, 0u);
  }
  if (except != "nonManifoldEdges")
  {
    EXPECT_EQ(r.nonManifoldEdges, 0u);
  }
  if (except != "nonManifoldVertices")
  {
    EXPECT_EQ(r.nonManifoldVertices, 0u);
  }
  if (except != "boundaryLoops")
  {
    EXPECT_EQ(r.boundaryLoops, 0u);
  }
  if (except != "reoriented")
  {
    EXPECT_FALSE(r.reoriented);
  }
}

/// A closed, consistently and outward oriented box of the test size.
void ExpectGoodBox(const TriangleMesh& mesh)
{
  EXPECT_EQ(CountBoundaryEdges(mesh), 0u);
  EXPECT_TRUE(ConsistentlyOriented(mesh));
  EXPECT_NEAR(SignedVolume(mesh), kSx * kSy * kSz, 1e-12);
}

TEST(MeshRepair, CleanBoxIsUnchanged)
{
  TriangleMesh mesh = MakeBox(kSx, kSy, kSz);
  const TriangleMesh input = mesh;
  Warnings warnings;
  const RepairReport report = Repair(mesh, warnings);
  ExpectNothingElse(report, "");
  EXPECT_EQ(report.unusedPoints, 0u);
  EXPECT_TRUE(warnings.empty());
  EXPECT_EQ(mesh.points, input.points);
  EXPECT_EQ(mesh.triangles, input.triangles);
}

TEST(MeshRepair, NaNPointAndItsTrianglesAreRemoved)
{
  TriangleMesh mesh = MakeBox(kSx, kSy, kSz);
  mesh.points.emplace_back(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0); // 8
  mesh.points.emplace_back(0.0, std::numeric_limits<double>::infinity(), 0.0);  // 9
  mesh.triangles.push_back({ { 0, 1, 8 } });
  mesh.triangles.push_back({ { 8, 2, 3 } });
  mesh.triangles.push_back({ { 4, 9, 5 } });
  Warnings warnings;
  const RepairReport report = Repair(mesh, warnings);
  EXPECT_EQ(report.invalidPoints, 2u);
  ExpectNothingElse(report, "invalidPoints");
  EXPECT_EQ(report.unusedPoints, 0u); // invalid points are counted as invalid only
  EXPECT_EQ(mesh.NumberOfPoints(), 8u);
  EXPECT_EQ(mesh.NumberOfTriangles(), 12u);
  EXPECT_TRUE(HasWarning(
    warnings, "2 points with NaN or infinite coordinates removed, with the 3 triangles"));
  ExpectGoodBox(mesh);
}

TEST(MeshRepair, InvalidIndicesAreRemoved)
{
  TriangleMesh mesh = MakeBox(kSx, kSy, kSz);
  mesh.triangles.push_back({ { 0, 1, 99 } });
  mesh.triangles.push_back({ { -1, 2, 3 } });
  mesh.triangles.push_back({ { 4, 4, 5 } });
  Warnings warnings;
  const RepairReport report = Repair(mesh, warnings);
  EXPECT_EQ(report.invalidTriangles, 3u);
  ExpectNothingElse(report, "invalidTriangles");
  EXPECT_EQ(mesh.NumberOfTriangles(), 12u);
  EXPECT_TRUE(
    HasWarning(warnings, "3 triangles with out-of-range or repeated point indices removed"));
  ExpectGoodBox(mesh);
}

TEST(MeshRepair, CoincidentPointsAreMerged)
{
  // The box with its own four points per face (24 points): 16 of them are copies.
  const TriangleMesh box = MakeBox(kSx, kSy, kSz);
  TriangleMesh mesh;
  for (std::size_t i = 0; i < box.triangles.size(); i += 2)
  {
    const auto& a = box.triangles[i];
    const auto& b = box.triangles[i + 1]; // (a0, a2, b2)
    const int base = static_cast<int>(mesh.points.size());
    for (int v : { a[0], a[1], a[2], b[2] })
    {
      mesh.points.push_back(box.points[v]);
    }
    mesh.triangles.push_back({ { base, base + 1, base + 2 } });
    mesh.triangles.push_back({ { base, base + 2, base + 3 } });
  }
  Warnings warnings;
  const RepairReport report = Repair(mesh, warnings);
  EXPECT_EQ(report.mergedPoints, 16u);
  ExpectNothingElse(report, "mergedPoints");
  EXPECT_EQ(report.unusedPoints, 0u);
  EXPECT_EQ(mesh.NumberOfPoints(), 8u);
  EXPECT_EQ(mesh.NumberOfTriangles(), 12u);
  EXPECT_TRUE(HasWarning(warnings, "16 coincident points merged"));
  ExpectGoodBox(mesh);
}

TEST(MeshRepair, NearlyCoincidentPointsAreMerged)
{
  // A copy of point 0 moved by 1e-12 (below 1e-10 of the diagonal) is merged; a point 1e-6 away
  // (in a separate triangle) is distinct.
  TriangleMesh mesh = MakeBox(kSx, kSy, kSz);
  mesh.points.push_back(mesh.points[0] + Vec3(1e-12, 0.0, 0.0)); // 8
  mesh.points.push_back(mesh.points[0] + Vec3(-1e-6, 0.0, 0.0)); // 9
  mesh.points.emplace_back(-0.1, 0.0, 0.0);                      // 10
  mesh.points.emplace_back(-0.1, -0.1, 0.0);                     // 11
  mesh.triangles[0][0] = 8;
  mesh.triangles.push_back({ { 9, 10, 11 } });
  Warnings warnings;
  const RepairReport report = Repair(mesh, warnings);
  EXPECT_EQ(report.mergedPoints, 1u);
  EXPECT_EQ(report.boundaryLoops, 1u); // the separate triangle
  EXPECT_EQ(mesh.NumberOfPoints(), 11u);
  EXPECT_EQ(mesh.NumberOfTriangles(), 13u);
  EXPECT_TRUE(HasWarning(warnings, "1 coincident point merged"));
}

TEST(MeshRepair, DegenerateTrianglesAreRemoved)
{
  TriangleMesh mesh = MakeBox(kSx, kSy, kSz);
  // Three collinear new points, and a zero-area triangle on the box's own collinear points
  // after merging (10 coincides with 0).
  mesh.points.emplace_back(0.3, 0.0, 0.0); // 8
  mesh.points.emplace_back(0.4, 0.1, 0.0); // 9
  mesh.points.emplace_back(0.0, 0.0, 0.0); // 10, a copy of 0
  mesh.points.emplace_back(0.5, 0.2, 0.0); // 11
  mesh.triangles.push_back({ { 8, 9, 11 } });
  mesh.triangles.push_back({ { 0, 10, 1 } });
  Warnings warnings;
  const RepairReport report = Repair(mesh, warnings);
  EXPECT_EQ(report.degenerateTriangles, 2u);
  EXPECT_EQ(report.mergedPoints, 1u);
  EXPECT_EQ(report.unusedPoints, 3u); // 8, 9, 11
  EXPECT_EQ(report.duplicateTriangles, 0u);
  EXPECT_EQ(report.boundaryLoops, 0u);
  EXPECT_EQ(mesh.NumberOfPoints(), 8u);
  EXPECT_EQ(mesh.NumberOfTriangles(), 12u);
  EXPECT_TRUE(HasWarning(warnings, "2 degenerate (zero-area) triangles removed"));
  EXPECT_TRUE(HasWarning(warnings, "3 unused points removed"));
  ExpectGoodBox(mesh);
}

TEST(MeshRepair, DegenerateCapOfTJunctionIsReplacedBySplit)
{
  // The front face (y = 0) has a point m in the middle of edge 0-1, the bottom face does not:
  // a T-junction, closed by the zero-area cap (0, 1, m). Removing the cap and splitting the
  // bottom triangle at m keeps the box closed.
  TriangleMesh mesh = MakeBox(kSx, kSy, kSz);
  mesh.points.push_back(0.5 * (mesh.points[0] + mesh.points[1])); // m = 8
  // Front face triangles (0, 1, 5), (0, 5, 4) are 4 and 5.
  mesh.triangles[4] = { { 0, 8, 4 } };
  mesh.triangles[5] = { { 8, 1, 5 } };
  mesh.triangles.push_back({ { 8, 5, 4 } });
  mesh.triangles.push_back({ { 0, 1, 8 } }); // the cap
  ASSERT_EQ(mesh.NumberOfTriangles(), 14u);
  Warnings warnings;
  const RepairReport report = Repair(mesh, warnings);
  EXPECT_EQ(report.degenerateTriangles, 1u);
  ExpectNothingElse(report, "degenerateTriangles");
  EXPECT_EQ(mesh.NumberOfPoints(), 9u);
  EXPECT_EQ(mesh.NumberOfTriangles(), 14u); // 13 after the cap, +1 from the split
  EXPECT_TRUE(HasWarning(warnings,
    "1 degenerate (zero-area) triangle removed; 1 neighbouring triangle split at the collinear"));
  ExpectGoodBox(mesh);
}

TEST(MeshRepair, DuplicateTrianglesAreRemoved)
{
  TriangleMesh mesh = MakeBox(kSx, kSy, kSz);
  mesh.triangles.push_back(mesh.triangles[0]);
  mesh.triangles.push_back(
    { { mesh.triangles[5][0], mesh.triangles[5][2], mesh.triangles[5][1] } }); // reversed copy
  mesh.triangles.push_back(
    { { mesh.triangles[7][1], mesh.triangles[7][2], mesh.triangles[7][0] } }); // rotated copy
  Warnings warnings;
  const RepairReport report = Repair(mesh, warnings);
  EXPECT_EQ(report.duplicateTriangles, 3u);
  ExpectNothingElse(report, "duplicateTriangles");
  EXPECT_EQ(mesh.NumberOfTriangles(), 12u);
  EXPECT_TRUE(HasWarning(warnings, "3 duplicate triangles removed"));
  ExpectGoodBox(mesh);
}

TEST(MeshRepair, NonManifoldEdgeLosesItsFin)
{
  // A fin on edge 0-1, listed first: the box's own triangles are the better connected ones
  // and stay.
  TriangleMesh mesh = MakeBox(kSx, kSy, kSz);
  mesh.points.emplace_back(0.1, -0.05, -0.05); // 8
  mesh.triangles.insert(mesh.triangles.begin(), { { 0, 8, 1 } });
  Warnings warnings;
  const RepairReport report = Repair(mesh, warnings);
  EXPECT_EQ(report.nonManifoldEdges, 1u);
  ExpectNothingElse(report, "nonManifoldEdges");
  EXPECT_EQ(report.unusedPoints, 1u);
  EXPECT_EQ(mesh.NumberOfPoints(), 8u);
  EXPECT_EQ(mesh.NumberOfTriangles(), 12u);
  EXPECT_TRUE(HasWarning(
    warnings, "1 non-manifold edge (more than two triangles) made manifold: 1 triangle removed"));
  ExpectGoodBox(mesh);
}

TEST(MeshRepair, PinchedVertexIsDuplicated)
{
  // Two boxes touching at one corner: box B's corner 0 is box A's corner 7 (as a separate,
  // coincident point, merged first).
  TriangleMesh mesh = MakeBox(kSx, kSy, kSz);
  const TriangleMesh b = MakeBox(kSx, kSy, kSz);
  for (const Vec3& p : b.points)
  {
    mesh.points.push_back(p + Vec3(kSx, kSy, kSz));
  }
  for (const auto& t : b.triangles)
  {
    mesh.triangles.push_back({ { t[0] + 8, t[1] + 8, t[2] + 8 } });
  }
  Warnings warnings;
  const RepairReport report = Repair(mesh, warnings);
  EXPECT_EQ(report.mergedPoints, 1u);
  EXPECT_EQ(report.nonManifoldVertices, 1u);
  EXPECT_EQ(report.nonManifoldEdges, 0u);
  EXPECT_EQ(report.unusedPoints, 0u);
  EXPECT_FALSE(report.reoriented);
  EXPECT_EQ(mesh.NumberOfPoints(), 16u);
  EXPECT_EQ(mesh.NumberOfTriangles(), 24u);
  EXPECT_TRUE(HasWarning(warnings, "1 non-manifold (pinched) vertex made manifold: 1 point"));
  EXPECT_EQ(CountBoundaryEdges(mesh), 0u);
  EXPECT_TRUE(ConsistentlyOriented(mesh));
  EXPECT_NEAR(SignedVolume(mesh), 2 * kSx * kSy * kSz, 1e-12);
}

TEST(MeshRepair, FlippedTrianglesAreReoriented)
{
  TriangleMesh mesh = MakeBox(kSx, kSy, kSz);
  std::swap(mesh.triangles[3][1], mesh.triangles[3][2]);
  std::swap(mesh.triangles[7][1], mesh.triangles[7][2]);
  ASSERT_FALSE(ConsistentlyOriented(mesh));
  Warnings warnings;
  const RepairReport report = Repair(mesh, warnings);
  EXPECT_TRUE(report.reoriented);
  ExpectNothingElse(report, "reoriented");
  EXPECT_TRUE(HasWarning(warnings, "2 triangles flipped for a consistent orientation"));
  ExpectGoodBox(mesh);
}

TEST(MeshRepair, InsideOutBoxIsTurnedOutward)
{
  TriangleMesh mesh = MakeBox(kSx, kSy, kSz);
  for (auto& t : mesh.triangles)
  {
    std::swap(t[1], t[2]);
  }
  ASSERT_LT(SignedVolume(mesh), 0.0);
  Warnings warnings;
  const RepairReport report = Repair(mesh, warnings);
  EXPECT_TRUE(report.reoriented);
  EXPECT_TRUE(HasWarning(warnings, "12 triangles flipped"));
  ExpectGoodBox(mesh);
}

TEST(MeshRepair, OpenBoxReportsItsBoundaryLoop)
{
  // Without its top (triangles 2 and 3) and with one side triangle flipped: an open surface
  // keeps the orientation most of its triangles had.
  TriangleMesh mesh = MakeBox(kSx, kSy, kSz);
  mesh.triangles.erase(mesh.triangles.begin() + 2, mesh.triangles.begin() + 4);
  const auto reference = mesh.triangles;
  std::swap(mesh.triangles[6][1], mesh.triangles[6][2]);
  Warnings warnings;
  const RepairReport report = Repair(mesh, warnings);
  EXPECT_EQ(report.boundaryLoops, 1u);
  EXPECT_TRUE(report.reoriented);
  EXPECT_EQ(report.unusedPoints, 0u);
  EXPECT_EQ(mesh.triangles, reference);
  EXPECT_EQ(CountBoundaryEdges(mesh), 4u);
  EXPECT_TRUE(HasWarning(warnings, "1 triangle flipped"));
  EXPECT_TRUE(HasWarning(warnings, "1 boundary loop (holes or open borders) kept"));
}

TEST(MeshRepair, MoebiusStripIsCutOpen)
{
  // A strip of 12 quads around a circle with half a twist: not orientable.
  TriangleMesh mesh;
  const int n = 12;
  for (int i = 0; i < n; ++i)
  {
    const double theta = 2.0 * M_PI * i / n;
    const Vec3 centre(0.1 * std::cos(theta), 0.1 * std::sin(theta), 0.0);
    const Vec3 radial(std::cos(theta), std::sin(theta), 0.0);
    const Vec3 across = 0.02 * (std::cos(theta / 2) * radial + std::sin(theta / 2) * Vec3::UnitZ());
    mesh.points.push_back(centre + across); // 2i
    mesh.points.push_back(centre - across); // 2i + 1
  }
  for (int i = 0; i < n; ++i)
  {
    const int a = 2 * i;
    const int b = 2 * i + 1;
    // After the last quad the strip comes back flipped: top meets bottom.
    const int c = i + 1 < n ? 2 * (i + 1) + 1 : 0;
    const int d = i + 1 < n ? 2 * (i + 1) : 1;
    mesh.triangles.push_back({ { a, b, c } });
    mesh.triangles.push_back({ { a, c, d } });
  }
  Warnings warnings;
  const RepairReport report = Repair(mesh, warnings);
  EXPECT_TRUE(HasWarning(warnings, "the surface is not orientable"));
  EXPECT_GT(mesh.NumberOfPoints(), 24u);
  EXPECT_EQ(mesh.NumberOfTriangles(), 24u);
  EXPECT_TRUE(ConsistentlyOriented(mesh));
  EXPECT_EQ(report.boundaryLoops, 1u);
}

TEST(MeshRepair, PointDataFollowTheirPoints)
{
  // Every kind of point change at once; the attribute is the point's own position.
  TriangleMesh mesh = MakeBox(kSx, kSy, kSz);
  mesh.points.emplace_back(std::numeric_limits<double>::quiet_NaN(), 0.0, 0.0); // 8, invalid
  mesh.points.emplace_back(1.0, 1.0, 1.0);                                      // 9, unused
  mesh.points.push_back(mesh.points[3]);                                        // 10, merged
  mesh.triangles.push_back({ { 0, 1, 8 } });
  mesh.triangles[0][2] = 10;
  const TriangleMesh b = MakeBox(kSx, kSy, kSz); // a second box pinched at corner 7
  for (const Vec3& p : b.points)
  {
    mesh.points.push_back(p + Vec3(kSx, kSy, kSz));
  }
  for (const auto& t : b.triangles)
  {
    mesh.triangles.push_back({ { t[0] + 11, t[1] + 11, t[2] + 11 } });
  }
  AddPointAttribute(mesh, "Position", 3, [](const Vec3& p, int k) { return p[k]; });
  Warnings warnings;
  const RepairReport report = Repair(mesh, warnings);
  EXPECT_EQ(report.invalidPoints, 1u);
  EXPECT_EQ(report.unusedPoints, 1u);
  EXPECT_EQ(report.mergedPoints, 2u);
  EXPECT_EQ(report.nonManifoldVertices, 1u);
  ASSERT_EQ(mesh.pointData.size(), 1u);
  const auto& values = mesh.pointData[0].values;
  ASSERT_EQ(values.size(), 3 * mesh.NumberOfPoints());
  for (std::size_t i = 0; i < mesh.NumberOfPoints(); ++i)
  {
    for (int k = 0; k < 3; ++k)
    {
      EXPECT_EQ(values[3 * i + k], mesh.points[i][k]) << "point " << i;
    }
  }
}

TEST(MeshRepair, MismatchedPointDataAreDropped)
{
  TriangleMesh mesh = MakeBox(kSx, kSy, kSz);
  AddPointAttribute(mesh, "Good", 2, [](const Vec3& p, int k) { return p[k]; });
  AddPointAttribute(mesh, "Short", 2, [](const Vec3& p, int k) { return p[k]; });
  mesh.pointData[1].values.pop_back();
  Warnings warnings;
  Repair(mesh, warnings);
  ASSERT_EQ(mesh.pointData.size(), 1u);
  EXPECT_EQ(mesh.pointData[0].name, "Good");
  EXPECT_TRUE(
    HasWarning(warnings, "point attribute 'Short' removed: it has 15 values for 8 points"));
}

TEST(MeshRepair, EmptyMeshIsAnError)
{
  TriangleMesh mesh;
  mesh.points.emplace_back(0.0, 0.0, 0.0);
  RepairReport report;
  Warnings warnings;
  std::string error;
  EXPECT_FALSE(RepairMesh(mesh, report, warnings, error));
  EXPECT_EQ(error, "the mesh has no triangles");
}

TEST(MeshRepair, AllDegenerateIsAnError)
{
  TriangleMesh mesh;
  mesh.points = { Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(0, 0, 0) };
  mesh.triangles = { { { 0, 1, 2 } }, { { 0, 3, 1 } }, { { 2, 1, 2 } } };
  RepairReport report;
  Warnings warnings;
  std::string error;
  EXPECT_FALSE(RepairMesh(mesh, report, warnings, error));
  EXPECT_EQ(
    error, "nothing is left after repair: all 3 triangles were invalid, degenerate or duplicates");
  EXPECT_EQ(report.degenerateTriangles, 2u);
  EXPECT_EQ(report.invalidTriangles, 1u);
  EXPECT_EQ(mesh.NumberOfTriangles(), 0u);
}

} // namespace
