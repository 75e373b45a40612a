// Tests of RemeshToArea, TransferPointData and the mesh metrics: a box at several target areas
// (size statistics, distance to the input, sharp edges kept, closed), a sphere carrying a linear
// attribute, the Stanford bunny (when the shared data are present), each strategy, invalid
// options and progress.
#include "MeshMetrics.h"
#include "MeshPrepTestUtilities.h"
#include "MeshRepair.h"
#include "Remeshing.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>

namespace
{
using catar::Vec3;
using namespace catar::mesh;
using namespace catar_test;

constexpr double kSx = 0.2;
constexpr double kSy = 0.1;
constexpr double kSz = 0.05;
constexpr double kBoxArea = 2 * (kSx * kSy + kSx * kSz + kSy * kSz); // 0.07
constexpr double kBoxEdges = 4 * (kSx + kSy + kSz);                  // 1.4
constexpr double kFeatureAngle = 60.0;

/// A linear function of position, as two texture coordinates.
double TexCoord(const Vec3& p, int k)
{
  return k == 0 ? 0.5 + 4.0 * p.x() + 2.0 * p.y() : 0.5 - 3.0 * p.z() + p.y();
}
/// The largest gradient norm of TexCoord's components.
const double kTexCoordGradient = std::sqrt(20.0);

/// The largest difference between the "TCoords" attribute of `mesh` and TexCoord.
double TexCoordError(const TriangleMesh& mesh)
{
  const PointAttribute* attribute = FindAttribute(mesh, "TCoords");
  if (!attribute || attribute->components != 2 ||
    attribute->values.size() != 2 * mesh.NumberOfPoints())
  {
    return std::numeric_limits<double>::infinity();
  }
  double error = 0.0;
  for (std::size_t i = 0; i < mesh.NumberOfPoints(); ++i)
  {
    for (int k = 0; k < 2; ++k)
    {
      error = std::max(error, std::abs(attribute->values[2 * i + k] - TexCoord(mesh.points[i], k)));
    }
  }
  return error;
}

double Seconds(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// One line of measured numbers in the test log.
void Print(const std::string& what, const RemeshResult& result, const AreaStatistics& s,
  double target, double hausdorff, double length, double seconds)
{
  std::cout << "[ stats    ] " << what << ": " << s.count << " triangles (" << result.steps
            << "), mean/target " << s.mean / target << ", p95/target " << s.p95 / target
            << ", max/target " << s.max / target << ", Hausdorff/L " << hausdorff / length << ", "
            << seconds << " s" << std::endl;
}

// ---------------------------------------------------------------------------------------------
// Metrics

TEST(MeshMetrics, BoxAreaStatistics)
{
  // Triangle areas: 4 x 0.0025 (x = const faces), 4 x 0.005 (y), 4 x 0.01 (z).
  const AreaStatistics s = TriangleAreaStatistics(MakeBox(kSx, kSy, kSz));
  EXPECT_EQ(s.count, 12u);
  EXPECT_NEAR(s.total, kBoxArea, 1e-15);
  EXPECT_NEAR(s.mean, kBoxArea / 12, 1e-15);
  EXPECT_NEAR(s.median, 0.005, 1e-15);
  EXPECT_NEAR(s.p95, 0.01, 1e-15);
  EXPECT_NEAR(s.min, 0.0025, 1e-15);
  EXPECT_NEAR(s.max, 0.01, 1e-15);
  EXPECT_EQ(TriangleAreaStatistics(TriangleMesh()).count, 0u);
}

TEST(MeshMetrics, SharpAndBoundaryEdgeLength)
{
  const TriangleMesh box = MakeBox(kSx, kSy, kSz);
  EXPECT_NEAR(SharpEdgeLength(box, kFeatureAngle), kBoxEdges, 1e-14);
  EXPECT_EQ(SharpEdgeLength(box, 95.0), 0.0); // the box bends by 90 degrees only
  EXPECT_EQ(BoundaryEdgeLength(box), 0.0);
  TriangleMesh open = box;
  open.triangles.erase(open.triangles.begin() + 2, open.triangles.begin() + 4); // no top
  EXPECT_NEAR(BoundaryEdgeLength(open), 2 * (kSx + kSy), 1e-14);
  EXPECT_NEAR(SharpEdgeLength(open, kFeatureAngle), 2 * (kSx + kSy) + 4 * kSz, 1e-14);
}

TEST(MeshMetrics, DistancesOfShiftedBox)
{
  // Shifting by d along x moves every surface point and every edge point by at most d, and the
  // faces x = const and the corners by exactly d.
  const TriangleMesh box = MakeBox(kSx, kSy, kSz);
  TriangleMesh shifted = box;
  const double d = 0.003;
  for (Vec3& p : shifted.points)
  {
    p.x() += d;
  }
  EXPECT_NEAR(HausdorffDistance(box, shifted, 0.01), d, 1e-12);
  EXPECT_NEAR(HausdorffDistance(box, box, 0.01), 0.0, 1e-15);
  EXPECT_NEAR(SharpEdgeDeviation(box, shifted, kFeatureAngle, 0.01), d, 1e-12);
  EXPECT_NEAR(SharpEdgeDeviation(box, box, kFeatureAngle, 0.01), 0.0, 1e-15);
  // An icosphere has no edge sharper than 60 degrees: nothing to keep.
  EXPECT_EQ(SharpEdgeDeviation(MakeSphere(0.05, 1), box, kFeatureAngle, 0.01), 0.0);
  EXPECT_TRUE(std::isinf(SharpEdgeDeviation(box, MakeSphere(0.05, 1), kFeatureAngle, 0.01)));
  EXPECT_TRUE(std::isinf(HausdorffDistance(box, TriangleMesh(), 0.01)));
}

// ---------------------------------------------------------------------------------------------
// Isotropic remeshing of a box

class RemeshBox : public ::testing::TestWithParam<double>
{
};

TEST_P(RemeshBox, MeetsTargetAreaAndKeepsEdges)
{
  const double target = GetParam();
  const double length = EdgeLengthForArea(target);
  const TriangleMesh box = MakeBox(kSx, kSy, kSz);
  RemeshOptions options;
  options.targetArea = target;
  const auto start = std::chrono::steady_clock::now();
  const RemeshResult result = RemeshToArea(box, options);
  const double seconds = Seconds(start);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.steps, "isotropic");
  EXPECT_TRUE(result.warnings.empty());

  const AreaStatistics s = TriangleAreaStatistics(result.mesh);
  const double hausdorff = HausdorffDistance(box, result.mesh, 0.25 * length);
  Print("box " + std::to_string(target), result, s, target, hausdorff, length, seconds);
  EXPECT_NEAR(s.mean, target, 0.1 * target);
  EXPECT_LT(s.p95, 2.0 * target);
  EXPECT_NEAR(s.total, kBoxArea, 1e-12);
  // The faces are flat and the corners pinned, so the remeshed box is the box up to rounding:
  // the bound is 1e-6 of the target edge length (far below the 0.1 allowed for curved input).
  EXPECT_LT(hausdorff, 1e-6 * length);
  // Every sharp edge is kept, and no new one appears.
  EXPECT_LT(SharpEdgeDeviation(box, result.mesh, kFeatureAngle, 0.1 * length), 1e-6 * length);
  EXPECT_NEAR(SharpEdgeLength(result.mesh, kFeatureAngle), kBoxEdges, 1e-6 * kBoxEdges);
  EXPECT_EQ(CountBoundaryEdges(result.mesh), 0u);
  EXPECT_TRUE(ConsistentlyOriented(result.mesh));
  EXPECT_NEAR(SignedVolume(result.mesh), kSx * kSy * kSz, 1e-9 * kSx * kSy * kSz);
}

INSTANTIATE_TEST_SUITE_P(TargetAreas, RemeshBox, ::testing::Values(1e-4, 4e-5, 1e-5));

TEST(RemeshBox, OpenBoxKeepsItsBorder)
{
  // Without its top: the border loop stays where it is, its four corners included.
  TriangleMesh open = MakeBox(kSx, kSy, kSz);
  open.triangles.erase(open.triangles.begin() + 2, open.triangles.begin() + 4);
  const double target = 4e-5;
  RemeshOptions options;
  options.targetArea = target;
  const RemeshResult result = RemeshToArea(open, options);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_TRUE(HasWarning(result.warnings, "1 boundary loop"));
  const AreaStatistics s = TriangleAreaStatistics(result.mesh);
  EXPECT_NEAR(s.mean, target, 0.1 * target);
  EXPECT_NEAR(BoundaryEdgeLength(result.mesh), 2 * (kSx + kSy), 1e-9);
  EXPECT_NEAR(SharpEdgeLength(result.mesh, kFeatureAngle), 2 * (kSx + kSy) + 4 * kSz, 1e-9);
  std::size_t topCorners = 0;
  for (const Vec3& p : result.mesh.points)
  {
    topCorners +=
      p.z() == kSz && (p.x() == 0.0 || p.x() == kSx) && (p.y() == 0.0 || p.y() == kSy) ? 1 : 0;
  }
  EXPECT_EQ(topCorners, 4u);
  EXPECT_LT(HausdorffDistance(open, result.mesh, 0.01), 1e-9);
}

// ---------------------------------------------------------------------------------------------
// Curved surfaces and point data

TEST(RemeshSphere, CarriesLinearAttribute)
{
  // An icosphere of 1280 triangles (mean area 2.4e-5) remeshed finer. New points lie on the
  // input's facets, where barycentric interpolation of a linear function is exact.
  TriangleMesh sphere = MakeSphere(0.05, 3);
  AddPointAttribute(sphere, "TCoords", 2, TexCoord);
  const double target = 1e-5;
  const double length = EdgeLengthForArea(target);
  RemeshOptions options;
  options.targetArea = target;
  const RemeshResult result = RemeshToArea(sphere, options);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.steps, "isotropic");
  EXPECT_LT(TexCoordError(result.mesh), 1e-9);
  const AreaStatistics s = TriangleAreaStatistics(result.mesh);
  EXPECT_NEAR(s.mean, target, 0.1 * target);
  EXPECT_LT(s.p95, 2.0 * target);
  // New triangles span folds between the input's facets (about 0.15 rad each): their vertices
  // lie on the input, their interiors cut the folds. Stated bound: 0.1 of the edge length
  // (measured 0.06).
  EXPECT_LT(HausdorffDistance(sphere, result.mesh, 0.25 * length), 0.1 * length);
  EXPECT_EQ(CountBoundaryEdges(result.mesh), 0u);
  EXPECT_TRUE(ConsistentlyOriented(result.mesh));
  EXPECT_GT(SignedVolume(result.mesh), 0.0);
}

TEST(RemeshSphere, AutoDecimatesDenseInputFirst)
{
  // 20480 triangles (mean area 1.5e-6) to 4e-5: much denser than the target.
  TriangleMesh sphere = MakeSphere(0.05, 5);
  AddPointAttribute(sphere, "TCoords", 2, TexCoord);
  const double target = 4e-5;
  const double length = EdgeLengthForArea(target);
  RemeshOptions options;
  options.targetArea = target;
  const auto start = std::chrono::steady_clock::now();
  const RemeshResult result = RemeshToArea(sphere, options);
  const double seconds = Seconds(start);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.steps, "decimate, isotropic");
  const AreaStatistics s = TriangleAreaStatistics(result.mesh);
  const double hausdorff = HausdorffDistance(sphere, result.mesh, 0.25 * length);
  Print("sphere 20480 -> 4e-5", result, s, target, hausdorff, length, seconds);
  EXPECT_NEAR(s.mean, target, 0.1 * target);
  EXPECT_LT(s.p95, 2.0 * target);
  // A flat triangle of edge L inscribed in a sphere of radius R departs from it by about
  // L^2 / (6 R); here R = 5.2 L, and the isotropic pass projects onto the decimated surface, not
  // the input. Stated bound: 0.1 of the edge length (measured 0.075).
  EXPECT_LT(hausdorff, 0.1 * length);
  // Points lie on the decimated surface, within `hausdorff` of the input the attribute is
  // interpolated on: a linear function differs by at most its gradient times that.
  EXPECT_LT(TexCoordError(result.mesh), kTexCoordGradient * hausdorff + 1e-12);
  EXPECT_EQ(CountBoundaryEdges(result.mesh), 0u);
  EXPECT_TRUE(ConsistentlyOriented(result.mesh));
}

TEST(RemeshSphere, TransferPointDataInterpolatesOnTheSource)
{
  // Target points on the source's facets get the exact linear values; points off the surface
  // get those of their closest surface point.
  TriangleMesh source = MakeSphere(0.05, 2);
  AddPointAttribute(source, "TCoords", 2, TexCoord);
  TriangleMesh target = MakeBox(0.01, 0.01, 0.01); // inside the sphere: projected outward
  for (const auto& t : source.triangles)
  {
    target.points.push_back(
      (source.points[t[0]] + 2.0 * source.points[t[1]] + 3.0 * source.points[t[2]]) / 6.0);
  }
  TransferPointData(source, target);
  const PointAttribute* attribute = FindAttribute(target, "TCoords");
  ASSERT_NE(attribute, nullptr);
  ASSERT_EQ(attribute->values.size(), 2 * target.NumberOfPoints());
  for (std::size_t i = 8; i < target.NumberOfPoints(); ++i)
  {
    EXPECT_NEAR(attribute->values[2 * i], TexCoord(target.points[i], 0), 1e-12);
    EXPECT_NEAR(attribute->values[2 * i + 1], TexCoord(target.points[i], 1), 1e-12);
  }
  // The box corner (0.01, 0.01, 0.01) is 0.0327 from the sphere: its value comes from a point
  // of the surface, about 0.05 from the centre, not from the corner itself.
  EXPECT_GT(std::abs(attribute->values[14] - TexCoord(target.points[7], 0)), 0.05);
}

// ---------------------------------------------------------------------------------------------
// The Stanford bunny (shared data; skipped when absent)

class RemeshBunny : public ::testing::TestWithParam<double>
{
protected:
  static const TriangleMesh& Bunny()
  {
    static TriangleMesh bunny;
    static bool read = ReadObj(SharedDataPath("stanford-bunny.obj"), bunny);
    static_cast<void>(read);
    return bunny;
  }
};

TEST_P(RemeshBunny, MeetsTargetArea)
{
  const TriangleMesh& bunny = Bunny();
  if (bunny.Empty())
  {
    GTEST_SKIP() << "no " << SharedDataPath("stanford-bunny.obj");
  }
  const double target = GetParam();
  const double length = EdgeLengthForArea(target);
  RemeshOptions options;
  options.targetArea = target;
  const auto start = std::chrono::steady_clock::now();
  const RemeshResult result = RemeshToArea(bunny, options);
  const double seconds = Seconds(start);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.steps, "decimate, isotropic");
  // The scan's holes at the bottom are kept and reported.
  EXPECT_TRUE(HasWarning(result.warnings, "boundary loops"));
  EXPECT_GT(BoundaryEdgeLength(result.mesh), 0.0);

  const AreaStatistics s = TriangleAreaStatistics(result.mesh);
  const double hausdorff = HausdorffDistance(bunny, result.mesh, 0.25 * length);
  Print("bunny " + std::to_string(target), result, s, target, hausdorff, length, seconds);
  EXPECT_NEAR(s.mean, target, 0.1 * target);
  EXPECT_LT(s.p95, 2.0 * target);
  // Detail thinner than the target edge is lost: the farthest input points are at the tips of
  // the ears, thin sheets that the coarse surface cuts short (3 mm at target 1e-5, where the
  // edge is 4.8 mm). Stated bound: 0.75 of the target edge length (measured 0.60 at 1e-5, 0.42
  // at 4e-6); elsewhere the surface follows the scan far closer.
  EXPECT_LT(hausdorff, 0.75 * length);
  EXPECT_TRUE(ConsistentlyOriented(result.mesh));
}

INSTANTIATE_TEST_SUITE_P(TargetAreas, RemeshBunny, ::testing::Values(1e-5, 4e-6));

// ---------------------------------------------------------------------------------------------
// Strategies, options, progress

TEST(RemeshStrategy, DecimateReducesTriangles)
{
  TriangleMesh sphere = MakeSphere(0.05, 5); // 20480 triangles
  AddPointAttribute(sphere, "TCoords", 2, TexCoord);
  const double area = TriangleAreaStatistics(sphere).total;
  const double target = 2e-5;
  RemeshOptions options;
  options.targetArea = target;
  options.strategy = RemeshStrategy::Decimate;
  const RemeshResult result = RemeshToArea(sphere, options);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.steps, "decimate");
  const double expected = std::round(area / target);
  EXPECT_LE(static_cast<double>(result.mesh.NumberOfTriangles()), expected + 1);
  EXPECT_GE(static_cast<double>(result.mesh.NumberOfTriangles()), expected - 2);
  // Collapses keep input points: their data are exact.
  EXPECT_LT(TexCoordError(result.mesh), 1e-12);
  // Quadric collapses keep the shape within 0.1 of the target edge length (measured 0.06).
  EXPECT_LT(HausdorffDistance(sphere, result.mesh, 0.001), 0.1 * EdgeLengthForArea(target));
  EXPECT_EQ(CountBoundaryEdges(result.mesh), 0u);
  EXPECT_TRUE(ConsistentlyOriented(result.mesh));

  // Already coarser than the target: unchanged, with a warning.
  options.targetArea = 1e-7;
  const RemeshResult unchanged = RemeshToArea(sphere, options);
  ASSERT_TRUE(unchanged.ok) << unchanged.error;
  EXPECT_EQ(unchanged.mesh.NumberOfTriangles(), sphere.NumberOfTriangles());
  EXPECT_EQ(unchanged.steps, "");
  EXPECT_TRUE(HasWarning(unchanged.warnings, "not decimated"));
}

TEST(RemeshStrategy, SubdivideIncreasesTriangles)
{
  // Mean area 0.07 / 12 = 5.8e-3 -> 1.5e-3 -> 3.6e-4 -> 9.1e-5 <= 1e-4: three levels.
  TriangleMesh box = MakeBox(kSx, kSy, kSz);
  AddPointAttribute(box, "TCoords", 2, TexCoord);
  RemeshOptions options;
  options.targetArea = 1e-4;
  options.strategy = RemeshStrategy::Subdivide;
  const RemeshResult result = RemeshToArea(box, options);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.steps, "subdivide x3");
  EXPECT_EQ(result.mesh.NumberOfTriangles(), 12u * 64u);
  EXPECT_EQ(result.mesh.NumberOfPoints(), 386u); // 2 + 12 x 64 / 2 (closed, genus 0)
  EXPECT_NEAR(TriangleAreaStatistics(result.mesh).mean, kBoxArea / 768, 1e-15);
  EXPECT_LT(HausdorffDistance(box, result.mesh, 0.01), 1e-15);
  EXPECT_LT(TexCoordError(result.mesh), 1e-14);
  EXPECT_EQ(CountBoundaryEdges(result.mesh), 0u);
  EXPECT_TRUE(ConsistentlyOriented(result.mesh));
}

TEST(RemeshStrategy, IsotropicAloneOnDenseInput)
{
  TriangleMesh sphere = MakeSphere(0.05, 4); // 5120 triangles, mean area 6.1e-6
  const double target = 4e-5;
  RemeshOptions options;
  options.targetArea = target;
  options.strategy = RemeshStrategy::Isotropic;
  const RemeshResult result = RemeshToArea(sphere, options);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_EQ(result.steps, "isotropic");
  EXPECT_NEAR(TriangleAreaStatistics(result.mesh).mean, target, 0.1 * target);
}

TEST(RemeshOptions, InvalidOptionsAreErrors)
{
  const TriangleMesh box = MakeBox(kSx, kSy, kSz);
  const auto error = [&](const RemeshOptions& options) {
    const RemeshResult result = RemeshToArea(box, options);
    EXPECT_FALSE(result.ok);
    EXPECT_TRUE(result.mesh.Empty());
    return result.error;
  };
  RemeshOptions options;
  EXPECT_EQ(error(options), "invalid options: targetArea must be a positive finite number (got 0)");
  options.targetArea = -1e-4;
  EXPECT_EQ(
    error(options), "invalid options: targetArea must be a positive finite number (got -0.0001)");
  options.targetArea = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(error(options).find("invalid options: targetArea"), 0u);
  options.targetArea = std::numeric_limits<double>::infinity();
  EXPECT_EQ(error(options).find("invalid options: targetArea"), 0u);
  options.targetArea = 1e-4;
  options.iterations = 0;
  EXPECT_EQ(error(options), "invalid options: iterations must be at least 1 (got 0)");
  options.iterations = 3;
  options.featureAngle = 200.0;
  EXPECT_EQ(
    error(options), "invalid options: featureAngle must be between 0 and 180 degrees (got 200)");
  options.featureAngle = 60.0;
  options.targetArea = 1e-12; // 7e10 triangles
  EXPECT_EQ(error(options).find("targetArea 1e-12 is too small: about 7e+10 triangles"), 0u);
  options.targetArea = 1e-4;
  EXPECT_EQ(
    RemeshToArea(TriangleMesh(), options).error, "cannot remesh: the mesh has no triangles");
}

TEST(RemeshOptions, RepairsInputFirst)
{
  // The box with one triangle flipped and one duplicated remeshes like the box.
  TriangleMesh box = MakeBox(kSx, kSy, kSz);
  std::swap(box.triangles[4][1], box.triangles[4][2]);
  box.triangles.push_back(box.triangles[0]);
  RemeshOptions options;
  options.targetArea = 1e-4;
  const RemeshResult result = RemeshToArea(box, options);
  ASSERT_TRUE(result.ok) << result.error;
  EXPECT_TRUE(HasWarning(result.warnings, "1 duplicate triangle removed"));
  EXPECT_TRUE(HasWarning(result.warnings, "1 triangle flipped"));
  EXPECT_EQ(CountBoundaryEdges(result.mesh), 0u);
  EXPECT_NEAR(SignedVolume(result.mesh), kSx * kSy * kSz, 1e-12);
}

TEST(RemeshOptions, ReportsProgress)
{
  std::vector<double> fractions;
  RemeshOptions options;
  options.targetArea = 4e-5;
  options.progress = [](double fraction, void* data) {
    static_cast<std::vector<double>*>(data)->push_back(fraction);
  };
  options.progressData = &fractions;
  const RemeshResult result = RemeshToArea(MakeSphere(0.05, 5), options); // decimates first
  ASSERT_TRUE(result.ok) << result.error;
  ASSERT_GE(fractions.size(), 10u); // decimation reports as it goes
  EXPECT_EQ(fractions.front(), 0.0);
  EXPECT_EQ(fractions.back(), 1.0);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
}

} // namespace
