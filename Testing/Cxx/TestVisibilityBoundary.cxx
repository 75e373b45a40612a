// Triangles that cross the visibility boundary (issue: they vanished whole): a box straddling
// the region the sphere hides, drawn by the fast path with and without per-frame tessellation,
// against the reference ray tracer.
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricCompositor.h"
#include "vtkCatadioptricPainterSort.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCatadioptricRayTracer.h"
#include "vtkCatadioptricRemesher.h"
#include "vtkCubeSource.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkTriangleFilter.h"

#include "TestUtilities.h"

#include <gtest/gtest.h>

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
