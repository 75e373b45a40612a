// Triangles that cross the visibility boundary (issue: they vanished whole): a box straddling
// the region the sphere hides, drawn by the fast path with and without per-frame tessellation,
// against the reference ray tracer.
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricCompositor.h"
#include "vtkCatadioptricPainterSort.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCatadioptricRayTracer.h"
#include "vtkCatadioptricRemesher.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCubeSource.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkTriangleFilter.h"

#include "TestUtilities.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

namespace
{
struct Silhouettes
{
  long intersection = 0, union_ = 0;
  double IoU() const { return union_ ? double(intersection) / double(union_) : 0.0; }
};

Silhouettes Compare(vtkCatadioptricCamera* camera, vtkAlgorithmOutput* mesh, double boundary,
  vtkIdType& split, double adaptive = 0.0)
{
  vtkNew<vtkCatadioptricProjection> projection;
  projection->SetInputConnection(mesh);
  projection->SetCamera(camera);
  projection->SetBoundaryTolerance(boundary);
  projection->SetAdaptiveTolerance(adaptive);
  vtkNew<vtkCatadioptricPainterSort> sort;
  sort->SetInputConnection(projection->GetOutputPort());
  vtkNew<vtkCatadioptricCompositor> compositor;
  compositor->AddMeshConnection(sort->GetOutputPort());
  compositor->SetColorArrayName("");
  compositor->SetColor(1, 1, 1);
  compositor->Update();
  split = projection->GetNumberOfSplitTriangles();
  vtkNew<vtkCatadioptricRayTracer> tracer;
  tracer->SetCamera(camera);
  tracer->AddMeshConnection(mesh);
  tracer->SetColorArrayName("");
  tracer->SetColor(1, 1, 1);
  tracer->Update();
  vtkImageData* fast = compositor->GetOutput();
  vtkImageData* exact = tracer->GetOutput();
  Silhouettes s;
  const vtkIdType n = fast->GetNumberOfPoints();
  const auto* a = static_cast<const unsigned char*>(fast->GetScalarPointer());
  const auto* b = static_cast<const unsigned char*>(exact->GetScalarPointer());
  for (vtkIdType i = 0; i < n; ++i)
  {
    const bool ia = a[4 * i] != 0, ib = b[4 * i] != 0;
    s.intersection += ia && ib;
    s.union_ += ia || ib;
  }
  return s;
}
} // namespace

TEST(VisibilityBoundary, TrianglesAcrossItAreDrawnUpToIt)
{
  auto camera = catar_test::DemoCamera();
  // World: the camera at (0, -0.14, 1) looks along +y at the mirror (centre (0, 0, 1)); the box
  // reaches from beside the mirror into the region behind it, which the mirror hides.
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(0.02, 0.2, 0.05, 0.25, 0.9, 1.1);
  vtkNew<vtkTriangleFilter> triangles;
  triangles->SetInputConnection(cube->GetOutputPort());
  vtkNew<vtkCatadioptricRemesher> remesher;
  remesher->SetInputConnection(triangles->GetOutputPort());
  remesher->SetTargetArea(4e-4);
  // Edges drawn within 0.25 px (adaptive), the crossing triangles dropped or cut at the boundary.
  vtkIdType splitOff = 0, splitOn = 0;
  const Silhouettes off = Compare(camera, remesher->GetOutputPort(), 0.0, splitOff, 0.25);
  const Silhouettes on = Compare(camera, remesher->GetOutputPort(), 0.25, splitOn, 0.25);
  std::cout << "[ boundary ] box across the hidden region, edges within 0.25 px: IoU " << off.IoU()
            << " dropping the triangles that cross it, " << on.IoU() << " cutting them at it ("
            << splitOn << " triangles split), over " << on.union_ << " pixels" << std::endl;
  ASSERT_GT(on.union_, 200);
  EXPECT_GT(splitOn, splitOff);
  EXPECT_LT(off.IoU() + 0.005, on.IoU());
  EXPECT_GT(on.IoU(), 0.99);
}

// The pieces carry their triangle's data: a point array that is a linear function of position
// (and texture coordinates that are the position's x and y) interpolates exactly, so every new
// point holds that function of its own position; every piece holds its triangle's cell data.
TEST(VisibilityBoundary, PiecesCarryPointAndCellData)
{
  auto camera = catar_test::DemoCamera();
  // Two triangles across the hidden region behind the mirror (world: the mirror at (0, 0, 1)).
  vtkNew<vtkPoints> points;
  const double corners[4][3] = { { 0.02, 0.3, 1.0 }, { 0.2, -0.05, 0.95 }, { 0.15, 0.1, 1.15 },
    { 0.25, 0.25, 0.9 } };
  for (const auto& c : corners)
  {
    points->InsertNextPoint(c);
  }
  vtkNew<vtkCellArray> cells;
  const vtkIdType t0[3] = { 0, 1, 2 }, t1[3] = { 1, 3, 2 };
  cells->InsertNextCell(3, t0);
  cells->InsertNextCell(3, t1);
  vtkNew<vtkPolyData> mesh;
  mesh->SetPoints(points);
  mesh->SetPolys(cells);
  auto linear = [](const double* p) { return 1.0 + 2.0 * p[0] - 3.0 * p[1] + 0.5 * p[2]; };
  vtkNew<vtkDoubleArray> f;
  f->SetName("F");
  vtkNew<vtkFloatArray> tc;
  tc->SetName("TCoords");
  tc->SetNumberOfComponents(2);
  for (vtkIdType i = 0; i < 4; ++i)
  {
    f->InsertNextValue(linear(corners[i]));
    tc->InsertNextTuple2(corners[i][0], corners[i][1]);
  }
  mesh->GetPointData()->AddArray(f);
  mesh->GetPointData()->SetTCoords(tc);
  vtkNew<vtkIntArray> tag;
  tag->SetName("Tag");
  tag->InsertNextValue(10);
  tag->InsertNextValue(20);
  mesh->GetCellData()->AddArray(tag);
  vtkNew<vtkCatadioptricProjection> projection;
  projection->SetInputData(mesh);
  projection->SetCamera(camera);
  projection->SetBoundaryTolerance(0.5);
  projection->Update();
  vtkPolyData* out = projection->GetOutput();
  ASSERT_GT(projection->GetNumberOfSplitTriangles(), 0);
  ASSERT_GT(out->GetNumberOfPoints(), 4);
  vtkDataArray* fo = out->GetPointData()->GetArray("F");
  vtkDataArray* tco = out->GetPointData()->GetTCoords();
  ASSERT_NE(fo, nullptr);
  ASSERT_NE(tco, nullptr);
  double worst = 0.0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    worst = std::max(worst, std::abs(fo->GetComponent(i, 0) - linear(p)));
    worst = std::max(worst, std::abs(tco->GetComponent(i, 0) - p[0]));
    worst = std::max(worst, std::abs(tco->GetComponent(i, 1) - p[1]));
  }
  EXPECT_LT(worst, 1e-6); // texture coordinates are floats
  // Each piece's tag is that of an input triangle its centroid lies in.
  vtkDataArray* tags = out->GetCellData()->GetArray("Tag");
  ASSERT_NE(tags, nullptr);
  ASSERT_EQ(tags->GetNumberOfTuples(), out->GetNumberOfCells());
  auto inside = [&](const double* c, const vtkIdType* t) {
    // Barycentric coordinates in the triangle's plane.
    catar::Vec3 a(corners[t[0]]), b(corners[t[1]]), d(corners[t[2]]), p(c);
    const catar::Vec3 n = (b - a).cross(d - a);
    const double area = n.squaredNorm();
    const double u = ((d - b).cross(p - b)).dot(n) / area;
    const double v = ((a - d).cross(p - d)).dot(n) / area;
    return u > -1e-9 && v > -1e-9 && u + v < 1.0 + 1e-9;
  };
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    out->GetCellPoints(c, ids);
    double centroid[3] = { 0, 0, 0 };
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      double p[3];
      out->GetPoint(ids->GetId(k), p);
      for (int j = 0; j < 3; ++j)
      {
        centroid[j] += p[j] / ids->GetNumberOfIds();
      }
    }
    const int got = static_cast<int>(tags->GetComponent(c, 0));
    ASSERT_TRUE(got == 10 || got == 20) << "cell " << c;
    EXPECT_TRUE(inside(centroid, got == 10 ? t0 : t1)) << "cell " << c << " tagged " << got;
  }
}
