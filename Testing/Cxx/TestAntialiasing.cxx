// Anti-aliased compositing (vtkCatadioptricCompositor::Antialias): the edge pixels of objects
// composited over a frame, against the exact ray tracer with 8 x 8 samples per pixel.
#include "vtkAppendPolyData.h"
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricCompositor.h"
#include "vtkCatadioptricPainterSort.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCatadioptricRayTracer.h"
#include "vtkCubeSource.h"
#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"
#include "vtkTrivialProducer.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include "TestUtilities.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <vector>

namespace
{
const double kColor[3] = { 1.0, 0.85, 0.3 };

// A dark checkerboard of 7-pixel squares, RGB: the "photograph" the objects are composited onto.
vtkSmartPointer<vtkImageData> Frame(int width, int height)
{
  auto frame = vtkSmartPointer<vtkImageData>::New();
  frame->SetDimensions(width, height, 1);
  frame->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  auto* p = static_cast<unsigned char*>(frame->GetScalarPointer());
  for (int y = 0; y < height; ++y)
  {
    for (int x = 0; x < width; ++x)
    {
      const bool dark = ((x / 7) + (y / 7)) % 2 == 0;
      unsigned char* q = p + 3 * (static_cast<size_t>(y) * width + x);
      q[0] = dark ? 30 : 80;
      q[1] = dark ? 50 : 40;
      q[2] = dark ? 90 : 20;
    }
  }
  return frame;
}

struct Render
{
  std::vector<unsigned char> rgba;
  std::vector<long long> ids; // VisibleTriangle
  vtkIdType edgePixels = 0;
};

Render Fast(vtkCatadioptricCamera* camera, vtkAlgorithmOutput* mesh, vtkImageData* frame,
  int samples, bool depth = false, double opacity = 1.0, const char* colors = "")
{
  vtkNew<vtkCatadioptricProjection> projection;
  projection->SetInputConnection(mesh);
  projection->SetCamera(camera);
  projection->SetAdaptiveTolerance(0.1); // edges within 0.1 px: the error left is the sampling's
  vtkNew<vtkCatadioptricPainterSort> sort;
  sort->SetInputConnection(projection->GetOutputPort());
  vtkNew<vtkCatadioptricCompositor> compositor;
  compositor->SetFrameData(frame);
  compositor->AddMeshConnection(sort->GetOutputPort());
  compositor->SetColorArrayName(colors);
  compositor->SetColor(kColor[0], kColor[1], kColor[2]);
  compositor->SetOpacity(opacity);
  compositor->OutputVisibleTriangleOn();
  compositor->SetAntialias(samples > 1);
  compositor->SetAntialiasSamples(std::max(2, samples));
  compositor->SetVisibility(
    depth ? vtkCatadioptricCompositor::DEPTH_BUFFER : vtkCatadioptricCompositor::PAINTER);
  compositor->Update();
  Render r;
  vtkImageData* out = compositor->GetOutput();
  const auto* p = static_cast<const unsigned char*>(out->GetScalarPointer());
  r.rgba.assign(p, p + 4 * out->GetNumberOfPoints());
  r.edgePixels = compositor->GetNumberOfEdgePixels();
  auto* ids = vtkTypeInt64Array::SafeDownCast(out->GetPointData()->GetArray("VisibleTriangle"));
  r.ids.assign(ids->GetPointer(0), ids->GetPointer(0) + ids->GetNumberOfValues());
  return r;
}

std::vector<unsigned char> Exact(
  vtkCatadioptricCamera* camera, vtkAlgorithmOutput* mesh, vtkImageData* frame)
{
  vtkNew<vtkCatadioptricRayTracer> tracer;
  tracer->SetFrameData(frame);
  tracer->SetCamera(camera);
  tracer->AddMeshConnection(mesh);
  tracer->SetColorArrayName("");
  tracer->SetColor(kColor[0], kColor[1], kColor[2]);
  tracer->SetSamples(8);
  tracer->Update();
  const auto* p = static_cast<const unsigned char*>(tracer->GetOutput()->GetScalarPointer());
  return std::vector<unsigned char>(p, p + 4 * tracer->GetOutput()->GetNumberOfPoints());
}

// Mean and worst |fast - exact| (levels, R G B) over the pixels the exact image shows partly
// covered: neither the frame's pixel nor the object's colour.
struct EdgeError
{
  double mean = 0, worst = 0;
  long pixels = 0;
};

EdgeError Compare(const std::vector<unsigned char>& fast, const std::vector<unsigned char>& exact,
  vtkImageData* frame)
{
  const auto* f = static_cast<const unsigned char*>(frame->GetScalarPointer());
  const int object[3] = { int(std::lround(255 * kColor[0])), int(std::lround(255 * kColor[1])),
    int(std::lround(255 * kColor[2])) };
  EdgeError e;
  double sum = 0;
  const size_t n = exact.size() / 4;
  for (size_t i = 0; i < n; ++i)
  {
    int fromFrame = 0, fromObject = 0;
    for (int k = 0; k < 3; ++k)
    {
      fromFrame = std::max(fromFrame, std::abs(int(exact[4 * i + k]) - int(f[3 * i + k])));
      fromObject = std::max(fromObject, std::abs(int(exact[4 * i + k]) - object[k]));
    }
    if (fromFrame <= 2 || fromObject <= 2)
    {
      continue;
    }
    ++e.pixels;
    for (int k = 0; k < 3; ++k)
    {
      const double d = std::abs(int(fast[4 * i + k]) - int(exact[4 * i + k]));
      sum += d;
      e.worst = std::max(e.worst, d);
    }
  }
  e.mean = e.pixels ? sum / (3.0 * e.pixels) : 0.0;
  return e;
}

// A sphere of 48 x 24 facets in front of the mirror, whose silhouette runs across many pixels.
vtkSmartPointer<vtkSphereSource> Sphere()
{
  auto sphere = vtkSmartPointer<vtkSphereSource>::New();
  sphere->SetCenter(0.12, 0.2, 1.05);
  sphere->SetRadius(0.06);
  sphere->SetThetaResolution(48);
  sphere->SetPhiResolution(24);
  return sphere;
}

void CheckObject(const char* name, vtkAlgorithmOutput* mesh)
{
  vtkNew<vtkCatadioptricCamera> camera;
  catar_test::SetSmallDemoCamera(camera);
  auto frame = Frame(camera->GetImageWidth(), camera->GetImageHeight());
  const auto exact = Exact(camera, mesh, frame);
  const Render off = Fast(camera, mesh, frame, 1);
  const EdgeError e1 = Compare(off.rgba, exact, frame);
  ASSERT_GT(e1.pixels, 100) << name;
  std::cout << "[ antialias ] " << name << ", " << e1.pixels
            << " partly covered pixels (exact, 8 x 8 rays): off mean " << e1.mean << " worst "
            << e1.worst << " levels";
  EdgeError previous = e1;
  for (int s = 2; s <= 4; ++s)
  {
    const Render on = Fast(camera, mesh, frame, s);
    const EdgeError e = Compare(on.rgba, exact, frame);
    std::cout << "; " << s << " x " << s << " mean " << e.mean << " worst " << e.worst << " ("
              << on.edgePixels << " edge pixels)";
    // Each finer sampling is closer to the exact coverage.
    EXPECT_LT(e.mean, previous.mean) << name << ", " << s << " x " << s;
    previous = e;
    // Interior pixels keep their centre sample: only edge pixels change.
    long changed = 0;
    for (size_t i = 0; i < on.rgba.size(); i += 4)
    {
      changed += !std::equal(&on.rgba[i], &on.rgba[i] + 4, &off.rgba[i]);
    }
    EXPECT_GT(changed, 0) << name;
    EXPECT_LE(changed, on.edgePixels) << name;
    // The ids stay the centre sample's.
    EXPECT_TRUE(on.ids == off.ids) << name << ", " << s << " x " << s;
  }
  std::cout << std::endl;
  // 16 samples: a coverage step is 1/16 of the contrast (up to ~230 levels here).
  EXPECT_LT(previous.mean, e1.mean / 4) << name;
  EXPECT_LT(previous.mean, 12.0) << name;
}
} // namespace

TEST(Antialiasing, EdgesOverAFrameApproachTheExactCoverage)
{
  // A sphere and a box in front of the mirror (world: the mirror at (0, 0, 1), the camera behind
  // it along -y), each of whose silhouettes runs across many pixels.
  auto sphere = Sphere();
  CheckObject("sphere", sphere->GetOutputPort());
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(-0.2, -0.05, 0.15, 0.3, 0.9, 1.05);
  vtkNew<vtkTriangleFilter> box;
  box->SetInputConnection(cube->GetOutputPort());
  CheckObject("box", box->GetOutputPort());
}

TEST(Antialiasing, DepthBufferSamplesAgreeWithPainterOrder)
{
  // One convex object: painter order and the depth buffer see the same surface at every sample.
  vtkNew<vtkCatadioptricCamera> camera;
  catar_test::SetSmallDemoCamera(camera);
  auto frame = Frame(camera->GetImageWidth(), camera->GetImageHeight());
  auto sphere = Sphere();
  const Render painter = Fast(camera, sphere->GetOutputPort(), frame, 4, false);
  const Render depth = Fast(camera, sphere->GetOutputPort(), frame, 4, true);
  ASSERT_GT(depth.edgePixels, 100);
  long differ = 0;
  for (size_t i = 0; i < painter.rgba.size(); ++i)
  {
    differ += std::abs(int(painter.rgba[i]) - int(depth.rgba[i])) > 1;
  }
  EXPECT_EQ(differ, 0);
}

TEST(Antialiasing, NearestFirstMatchesDrawingInOrder)
{
  // Opaque triangles are sampled nearest first; an opacity a hair below 1 makes the compositor
  // draw every sample in painter order instead. A sphere in front of a box: silhouettes and an
  // occlusion edge.
  vtkNew<vtkCatadioptricCamera> camera;
  catar_test::SetSmallDemoCamera(camera);
  auto frame = Frame(camera->GetImageWidth(), camera->GetImageHeight());
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0.1, 0.2, 1.0);
  sphere->SetRadius(0.05);
  sphere->SetThetaResolution(32);
  sphere->SetPhiResolution(16);
  vtkNew<vtkCubeSource> cube;
  cube->SetBounds(0.05, 0.2, 0.25, 0.35, 0.9, 1.1);
  vtkNew<vtkAppendPolyData> both;
  both->AddInputConnection(sphere->GetOutputPort());
  vtkNew<vtkTriangleFilter> box;
  box->SetInputConnection(cube->GetOutputPort());
  both->AddInputConnection(box->GetOutputPort());
  // A colour per point, from its position: every triangle differs from those behind it.
  both->Update();
  vtkNew<vtkPolyData> mesh;
  mesh->ShallowCopy(both->GetOutput());
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    double p[3];
    mesh->GetPoint(i, p);
    colors->InsertNextTuple3(
      std::fmod(p[0] * 5000, 255), std::fmod(p[1] * 7000, 255), std::fmod(p[2] * 3000, 255));
  }
  mesh->GetPointData()->AddArray(colors);
  vtkNew<vtkTrivialProducer> producer;
  producer->SetOutput(mesh);
  const Render nearest = Fast(camera, producer->GetOutputPort(), frame, 4, false, 1.0, "Colors");
  const Render inOrder = Fast(camera, producer->GetOutputPort(), frame, 4, false, 0.9999, "Colors");
  ASSERT_GT(nearest.edgePixels, 100);
  long differ = 0;
  for (size_t i = 0; i < nearest.rgba.size(); i += 4)
  {
    for (int k = 0; k < 3; ++k)
    {
      differ += std::abs(int(nearest.rgba[i + k]) - int(inOrder.rgba[i + k])) > 1;
    }
  }
  EXPECT_EQ(differ, 0);
}
