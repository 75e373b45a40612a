// vtkCatadioptricRemesher and vtkCatadioptricPointSetSurface: VTK arrays in and out, field data,
// the pixel tolerance re-measured through the VTK camera, repairs and errors; and remeshing in
// scene files.
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricPointSetSurface.h"
#include "vtkCatadioptricRemesher.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkMath.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStringArray.h"
#include "vtkTessellatedBoxSource.h"
#include "vtkUnsignedCharArray.h"
#include "vtksys/SystemTools.hxx"

#include "TestUtilities.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <fstream>
#include <random>
#include <set>
#include <string>

namespace
{
double Field(vtkPolyData* mesh, const char* name)
{
  vtkDataArray* a = mesh->GetFieldData()->GetArray(name);
  return a ? a->GetComponent(0, 0) : std::nan("");
}

double TriangleArea(vtkPolyData* mesh, vtkIdType cell)
{
  vtkNew<vtkIdList> ids;
  mesh->GetCellPoints(cell, ids);
  double p[3][3];
  for (int k = 0; k < 3; ++k)
  {
    mesh->GetPoint(ids->GetId(k), p[k]);
  }
  double a[3], b[3], c[3];
  vtkMath::Subtract(p[1], p[0], a);
  vtkMath::Subtract(p[2], p[0], b);
  vtkMath::Cross(a, b, c);
  return 0.5 * vtkMath::Norm(c);
}

// A box of the given size centred at `centre`, 2 x 2 quads per face, one colour per face (cell
// data "Colors") and a point array "Height" = z (linear, so interpolation reproduces it exactly).
vtkSmartPointer<vtkPolyData> ColouredBox(const double size[3], const double centre[3])
{
  vtkNew<vtkTessellatedBoxSource> box;
  box->SetBounds(centre[0] - size[0] / 2, centre[0] + size[0] / 2, centre[1] - size[1] / 2,
    centre[1] + size[1] / 2, centre[2] - size[2] / 2, centre[2] + size[2] / 2);
  box->SetLevel(1);
  box->QuadsOn();
  box->DuplicateSharedPointsOff();
  box->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(box->GetOutput());
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    // The face's colour from its normal axis and side.
    mesh->GetCellPoints(c, ids);
    double p[3][3];
    for (int k = 0; k < 3; ++k)
    {
      mesh->GetPoint(ids->GetId(k), p[k]);
    }
    double a[3], b[3], n[3];
    vtkMath::Subtract(p[1], p[0], a);
    vtkMath::Subtract(p[2], p[0], b);
    vtkMath::Cross(a, b, n);
    int axis = 0;
    for (int j = 1; j < 3; ++j)
    {
      axis = std::abs(n[j]) > std::abs(n[axis]) ? j : axis;
    }
    const unsigned char side = p[0][axis] > centre[axis] ? 1 : 0;
    colors->InsertNextTuple3(40 * (2 * axis + side), 100, 200);
  }
  mesh->GetCellData()->AddArray(colors);
  vtkNew<vtkFloatArray> height;
  height->SetName("Height");
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    height->InsertNextValue(static_cast<float>(mesh->GetPoint(i)[2]));
  }
  mesh->GetPointData()->AddArray(height);
  return mesh;
}

using catar_test::DemoCamera;

// Largest bend of the mesh's edges seen by the camera, measured here with the VTK camera: the
// distance from the exact image of each edge's midpoint to the segment between the images of its
// ends. Edges with an end or the midpoint not projecting, or both ends outside the image, are
// skipped (as EdgeBendPixels does).
double MeasuredMaximumBend(vtkPolyData* mesh, vtkCatadioptricCamera* camera, int& visibleEdges)
{
  std::set<std::pair<vtkIdType, vtkIdType>> edges;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    mesh->GetCellPoints(c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      vtkIdType a = ids->GetId(k), b = ids->GetId((k + 1) % ids->GetNumberOfIds());
      edges.insert({ std::min(a, b), std::max(a, b) });
    }
  }
  double worst = 0.0;
  visibleEdges = 0;
  for (const auto& e : edges)
  {
    double pa[3], pb[3], pm[3], ia[2], ib[2], im[2], mirror[3];
    mesh->GetPoint(e.first, pa);
    mesh->GetPoint(e.second, pb);
    for (int j = 0; j < 3; ++j)
    {
      pm[j] = 0.5 * (pa[j] + pb[j]);
    }
    const int sa = camera->ProjectWorldPoint(pa, ia, mirror);
    const int sb = camera->ProjectWorldPoint(pb, ib, mirror);
    const int sm = camera->ProjectWorldPoint(pm, im, mirror);
    auto projects = [](int s) {
      return s == vtkCatadioptricCamera::VALID || s == vtkCatadioptricCamera::OUTSIDE_IMAGE;
    };
    if (!projects(sa) || !projects(sb) || !projects(sm) ||
      (sa != vtkCatadioptricCamera::VALID && sb != vtkCatadioptricCamera::VALID))
    {
      continue;
    }
    ++visibleEdges;
    const double d[2] = { ib[0] - ia[0], ib[1] - ia[1] };
    const double len2 = d[0] * d[0] + d[1] * d[1];
    double t = len2 > 0 ? ((im[0] - ia[0]) * d[0] + (im[1] - ia[1]) * d[1]) / len2 : 0.0;
    t = std::clamp(t, 0.0, 1.0);
    worst = std::max(worst, std::hypot(im[0] - ia[0] - t * d[0], im[1] - ia[1] - t * d[1]));
  }
  return worst;
}
} // namespace

TEST(vtkCatadioptricRemesher, TargetAreaKeepsArraysAndReports)
{
  const double size[3] = { 0.2, 0.1, 0.05 }, centre[3] = { 0.0, -0.25, 0.9 };
  auto box = ColouredBox(size, centre);
  vtkNew<catar_test::ErrorCounter> errors;
  for (double target : { 1e-4, 2.5e-5 })
  {
    vtkNew<vtkCatadioptricRemesher> remesher;
    errors->Watch(remesher);
    remesher->SetInputData(box);
    remesher->SetTargetArea(target);
    remesher->Update();
    ASSERT_EQ(errors->Count, 0) << errors->Last;
    vtkPolyData* out = remesher->GetOutput();
    const vtkIdType n = out->GetNumberOfPolys();
    ASSERT_GT(n, 0);
    // Total area is kept, so the mean is total / count; check it against the target.
    double total = 0.0;
    for (vtkIdType c = 0; c < n; ++c)
    {
      total += TriangleArea(out, c);
    }
    const double boxArea = 2 * (size[0] * size[1] + size[1] * size[2] + size[0] * size[2]);
    EXPECT_NEAR(total, boxArea, 1e-6 * boxArea); // float points
    EXPECT_NEAR(total / n, target, 0.1 * target) << n << " triangles";
    EXPECT_NEAR(Field(out, "MeanTriangleArea"), total / n, 1e-12);
    EXPECT_EQ(Field(out, "OutputTriangles"), n);
    EXPECT_EQ(Field(out, "InputTriangles"), 2 * box->GetNumberOfCells());
    ASSERT_NE(out->GetFieldData()->GetAbstractArray("RemeshSteps"), nullptr);
    // Cell colours follow the faces: each new triangle has the colour of the face it lies on.
    vtkDataArray* colors = out->GetCellData()->GetArray("Colors");
    ASSERT_NE(colors, nullptr);
    ASSERT_EQ(colors->GetNumberOfTuples(), n);
    vtkNew<vtkIdList> ids;
    for (vtkIdType c = 0; c < n; ++c)
    {
      out->GetCellPoints(c, ids);
      double q[3] = { 0, 0, 0 };
      for (int k = 0; k < 3; ++k)
      {
        const double* p = out->GetPoint(ids->GetId(k));
        for (int j = 0; j < 3; ++j)
        {
          q[j] += p[j] / 3;
        }
      }
      // The face: the axis where the centroid touches the box's side.
      int face = -1;
      for (int axis = 0; axis < 3; ++axis)
      {
        for (int side = 0; side < 2; ++side)
        {
          if (std::abs(q[axis] - (centre[axis] + (side ? 0.5 : -0.5) * size[axis])) < 1e-7)
          {
            face = 2 * axis + side;
          }
        }
      }
      ASSERT_GE(face, 0) << "triangle " << c << " is not on a face";
      EXPECT_EQ(colors->GetComponent(c, 0), 40 * face) << "triangle " << c;
    }
    // A point array linear in position is reproduced at every new point.
    vtkDataArray* height = out->GetPointData()->GetArray("Height");
    ASSERT_NE(height, nullptr);
    EXPECT_EQ(height->GetDataType(), VTK_FLOAT);
    for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
    {
      EXPECT_NEAR(height->GetComponent(i, 0), out->GetPoint(i)[2], 1e-6);
    }
  }
}

TEST(vtkCatadioptricRemesher, PixelToleranceHoldsThroughTheCamera)
{
  auto camera = DemoCamera();
  // Two placements: the demo's parallelepiped, and a 20 cm cube nearer the mirror's axis.
  const std::array<std::array<double, 6>, 2> placements = { {
    { 0.3, 0.12, 0.09, 0.14, -0.22, 0.87 },
    { 0.2, 0.2, 0.2, 0.0, -0.35, 0.6 },
  } };
  for (const auto& pl : placements)
  {
    auto box = ColouredBox(pl.data(), pl.data() + 3);
    std::vector<double> bounds;
    for (double tolerance : { 1.0, 0.3 })
    {
      vtkNew<vtkCatadioptricRemesher> remesher;
      vtkNew<catar_test::ErrorCounter> errors;
      errors->Watch(remesher);
      remesher->SetInputData(box);
      remesher->SetModeToPixelTolerance();
      remesher->SetPixelTolerance(tolerance);
      remesher->SetCamera(camera);
      remesher->Update();
      ASSERT_EQ(errors->Count, 0) << errors->Last;
      vtkPolyData* out = remesher->GetOutput();
      int visible = 0;
      const double measured = MeasuredMaximumBend(out, camera, visible);
      EXPECT_GT(visible, 10);
      EXPECT_LE(measured, tolerance * (1 + 1e-9));
      EXPECT_NEAR(Field(out, "MaximumEdgeBend"), measured, 1e-6);
      EXPECT_EQ(Field(out, "VisibleEdges"), visible);
      // The default geometric bound follows the tolerance: 1 px allows more than 0.3 px.
      EXPECT_GT(Field(out, "GeometricErrorBound"), 0.0);
      bounds.push_back(Field(out, "GeometricErrorBound"));
      // The straight box edges of the input bend more than the tolerance: it had to refine.
      int inputVisible = 0;
      EXPECT_GT(MeasuredMaximumBend(box, camera, inputVisible), tolerance);
    }
    ASSERT_EQ(bounds.size(), 2u);
    EXPECT_NEAR(bounds[1], 0.3 * bounds[0], 1e-12);
  }
}

// Long work can be stopped: an observer of the progress events sets AbortExecute (as ParaView's
// abort button does); the remesher stops at its next step, leaves an empty output and reports no
// error; the next update runs whole. Both modes.
namespace
{
class AbortAfter : public vtkCommand
{
public:
  static AbortAfter* New() { return new AbortAfter; }
  void Execute(vtkObject* caller, unsigned long, void* callData) override
  {
    const double fraction = *static_cast<double*>(callData);
    if (fraction < 1.0) // the executive reports 1 at the end, whatever happened
    {
      this->Last = std::max(this->Last, fraction);
    }
    if (this->Enabled && fraction > this->Threshold)
    {
      static_cast<vtkAlgorithm*>(caller)->AbortExecuteOn();
    }
  }
  bool Enabled = true;
  double Threshold = 0.15;
  double Last = 0.0;
};
} // namespace

TEST(vtkCatadioptricRemesher, ProgressAndAbort)
{
  const double size[3] = { 0.2, 0.1, 0.05 }, centre[3] = { 0.0, -0.25, 0.9 };
  auto box = ColouredBox(size, centre);
  for (bool pixels : { false, true })
  {
    vtkNew<vtkCatadioptricRemesher> remesher;
    remesher->SetInputData(box);
    if (pixels)
    {
      remesher->SetModeToPixelTolerance();
      remesher->SetPixelTolerance(0.3);
      remesher->SetCamera(DemoCamera());
    }
    else
    {
      remesher->SetTargetArea(2.5e-5);
    }
    vtkNew<AbortAfter> abort;
    remesher->AddObserver(vtkCommand::ProgressEvent, abort);
    vtkNew<catar_test::ErrorCounter> errors;
    errors->Watch(remesher);
    remesher->Update();
    EXPECT_EQ(errors->Count, 0) << errors->Last;
    EXPECT_EQ(remesher->GetOutput()->GetNumberOfPolys(), 0) << "pixels " << pixels;
    EXPECT_LT(abort->Last, 0.9) << "it went on after the abort";
    abort->Enabled = false;
    abort->Last = 0.0;
    remesher->Modified();
    remesher->Update();
    EXPECT_EQ(errors->Count, 0) << errors->Last;
    EXPECT_GT(remesher->GetOutput()->GetNumberOfPolys(), 2 * box->GetNumberOfCells());
    EXPECT_GE(abort->Last, 0.9); // the whole way this time
  }
}

// The same for the surface from points: progress between its stages, an abort honoured at the
// next one (empty output, no error), then a whole run. Both methods.
TEST(vtkCatadioptricPointSetSurface, ProgressAndAbort)
{
  // Points on a sphere, enough for the advancing front.
  vtkNew<vtkPoints> points;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int i = 0; i < 2000; ++i)
  {
    double p[3] = { g(rng), g(rng), g(rng) };
    vtkMath::Normalize(p);
    points->InsertNextPoint(p);
  }
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(points);
  for (int method : { vtkCatadioptricPointSetSurface::CONVEX_HULL,
         vtkCatadioptricPointSetSurface::ADVANCING_FRONT })
  {
    vtkNew<vtkCatadioptricPointSetSurface> surface;
    surface->SetInputData(cloud);
    surface->SetMethod(method);
    vtkNew<AbortAfter> abort;
    abort->Threshold = 0.05;
    surface->AddObserver(vtkCommand::ProgressEvent, abort);
    vtkNew<catar_test::ErrorCounter> errors;
    errors->Watch(surface);
    surface->Update();
    EXPECT_EQ(errors->Count, 0) << errors->Last;
    EXPECT_EQ(surface->GetOutput()->GetNumberOfPolys(), 0) << "method " << method;
    EXPECT_LT(abort->Last, 0.5) << "it went on after the abort";
    abort->Enabled = false;
    abort->Last = 0.0;
    surface->Modified();
    surface->Update();
    EXPECT_EQ(errors->Count, 0) << errors->Last;
    EXPECT_GT(surface->GetOutput()->GetNumberOfPolys(), 1000) << "method " << method;
    EXPECT_GE(abort->Last, 0.9); // the whole way this time
  }
}

TEST(vtkCatadioptricRemesher, BadInputIsRepairedOrRefused)
{
  vtkNew<catar_test::ErrorCounter> errors;
  vtkNew<catar_test::WarningCounter> warnings;
  // Empty input: an error, no crash.
  {
    vtkNew<vtkPolyData> empty;
    vtkNew<vtkCatadioptricRemesher> remesher;
    errors->Watch(remesher);
    remesher->SetInputData(empty);
    remesher->Update();
    EXPECT_EQ(errors->Count, 1);
    EXPECT_NE(errors->Last.find("no polygons"), std::string::npos) << errors->Last;
  }
  // Quads, a NaN point with its triangle, a duplicate triangle and a line: repaired with
  // warnings; the line is ignored.
  {
    vtkNew<vtkPoints> pts;
    for (int j = 0; j <= 4; ++j)
    {
      for (int i = 0; i <= 4; ++i)
      {
        pts->InsertNextPoint(0.02 * i, 0.02 * j, 0.0);
      }
    }
    const vtkIdType nan = pts->InsertNextPoint(std::nan(""), 0.0, 0.0);
    vtkNew<vtkCellArray> polys;
    for (int j = 0; j < 4; ++j)
    {
      for (int i = 0; i < 4; ++i)
      {
        const vtkIdType q[4] = { 5 * j + i, 5 * j + i + 1, 5 * (j + 1) + i + 1, 5 * (j + 1) + i };
        polys->InsertNextCell(4, q);
      }
    }
    const vtkIdType bad[3] = { 0, 1, nan };
    polys->InsertNextCell(3, bad);
    const vtkIdType dup[4] = { 0, 1, 6, 5 };
    polys->InsertNextCell(4, dup);
    vtkNew<vtkCellArray> lines;
    const vtkIdType line[2] = { 0, 24 };
    lines->InsertNextCell(2, line);
    vtkNew<vtkPolyData> plate;
    plate->SetPoints(pts);
    plate->SetPolys(polys);
    plate->SetLines(lines);
    vtkNew<vtkCatadioptricRemesher> remesher;
    errors->Watch(remesher);
    warnings->Watch(remesher);
    remesher->SetInputData(plate);
    remesher->SetTargetArea(2e-5);
    remesher->Update();
    EXPECT_EQ(errors->Count, 1) << errors->Last;
    EXPECT_NE(warnings->All.find("line cells ignored"), std::string::npos) << warnings->All;
    EXPECT_GE(warnings->Count, 3) << warnings->All; // line, NaN, duplicate (and quads)
    vtkPolyData* out = remesher->GetOutput();
    EXPECT_GT(out->GetNumberOfPolys(), 0);
    EXPECT_EQ(out->GetNumberOfLines(), 0);
    double bounds[6];
    out->GetBounds(bounds);
    EXPECT_NEAR(bounds[0], 0.0, 1e-7); // the plate's boundary is kept (float points)
    EXPECT_NEAR(bounds[1], 0.08, 1e-7);
    EXPECT_NEAR(bounds[3], 0.08, 1e-7);
    for (int i = 0; i < 6; ++i)
    {
      EXPECT_TRUE(std::isfinite(bounds[i]));
    }
  }
  // Pixel mode without a camera object or file takes the panel camera (the demo camera); a bad
  // panel value there is a clear error that names it.
  {
    vtkNew<vtkCatadioptricRemesher> remesher;
    errors->Watch(remesher);
    const double size[3] = { 0.1, 0.1, 0.1 }, centre[3] = { 0, 0, 1 };
    remesher->SetInputData(ColouredBox(size, centre));
    remesher->SetModeToPixelTolerance();
    remesher->SetPrincipalPoint(std::nan(""), 0.0);
    remesher->Update();
    EXPECT_EQ(errors->Count, 2);
    EXPECT_NE(errors->Last.find(": Principal Point"), std::string::npos) << errors->Last;
  }
}

TEST(vtkCatadioptricPointSetSurface, ConvexHullOfTheParallelepipedCorners)
{
  // The paper's parallelepiped given by its 8 corners (plus an interior point), rotated.
  vtkNew<vtkPoints> pts;
  for (int k = 0; k < 8; ++k)
  {
    pts->InsertNextPoint((k & 1) ? 0.15 : -0.15, (k & 2) ? 0.06 : -0.06, (k & 4) ? 0.045 : -0.045);
  }
  pts->InsertNextPoint(0.01, 0.0, 0.0);
  vtkNew<vtkPolyData> cloud;
  cloud->SetPoints(pts);
  vtkNew<vtkCatadioptricPointSetSurface> surface;
  surface->SetInputData(cloud);
  surface->Update();
  vtkPolyData* out = surface->GetOutput();
  ASSERT_EQ(out->GetNumberOfPolys(), 12);
  // Outward orientation: the signed volume (divergence theorem) is the box volume.
  double volume = 0.0;
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    out->GetCellPoints(c, ids);
    double p[3][3], cr[3];
    for (int k = 0; k < 3; ++k)
    {
      out->GetPoint(ids->GetId(k), p[k]);
    }
    vtkMath::Cross(p[1], p[2], cr);
    volume += vtkMath::Dot(p[0], cr) / 6.0;
  }
  EXPECT_NEAR(volume, 0.3 * 0.12 * 0.09, 1e-6 * 0.3 * 0.12 * 0.09); // float points
  // Too few points: a clear error.
  vtkNew<vtkPoints> three;
  three->InsertNextPoint(0, 0, 0);
  three->InsertNextPoint(1, 0, 0);
  three->InsertNextPoint(0, 1, 0);
  vtkNew<vtkPolyData> small;
  small->SetPoints(three);
  vtkNew<catar_test::ErrorCounter> errors;
  vtkNew<vtkCatadioptricPointSetSurface> bad;
  errors->Watch(bad);
  bad->SetInputData(small);
  bad->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Last.find("3 points"), std::string::npos) << errors->Last;
}

TEST(SceneRemeshing, SceneKeysAndOverrides)
{
  vtksys::SystemTools::MakeDirectory(CATAR_TEST_OUTPUT_DIR);
  const std::string path = std::string(CATAR_TEST_OUTPUT_DIR) + "/remesh-scene.yaml";
  std::ofstream(path) << "%YAML:1.0\n---\ncamera: " << CATAR_SOURCE_DIR
                      << "/Data/calibration/demo-camera.yaml\n"
                         "output: { width: 332, height: 262 }\n"
                         "background: { type: color, color: [ 0, 0, 0 ] }\n"
                         "remesh: { target_area: 1e-4 }\n"
                         "objects:\n"
                         "  - { name: a, type: box, size: [ 0.2, 0.1, 0.1 ], resolution: 2,\n"
                         "      translate: [ 0.1, -0.25, 0.9 ] }\n"
                         "  - { name: b, type: box, size: [ 0.1, 0.1, 0.1 ], resolution: 2,\n"
                         "      translate: [ -0.1, -0.25, 0.9 ], remesh: none }\n";
  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  renderer->SetSceneFileName(path.c_str());
  ASSERT_TRUE(renderer->Render()) << renderer->GetLastError();
  // Box a: area 0.1 m^2 / 1e-4 = about 1000 triangles; box b keeps its 6 x 2 x 2 x 2 = 48.
  const std::string report = renderer->GetMeshReport();
  EXPECT_NE(report.find("a: "), std::string::npos) << report;
  EXPECT_EQ(report.find("b: "), std::string::npos) << report;
  const vtkIdType withScene = renderer->GetNumberOfTriangles();
  EXPECT_GT(withScene, 48 + 900);
  EXPECT_LT(withScene, 48 + 1100);
  // The renderer's override applies to every object, 'remesh: none' included.
  renderer->SetRemeshPixelTolerance(0.5);
  ASSERT_TRUE(renderer->LoadScene()) << renderer->GetLastError();
  const std::string pixels = renderer->GetMeshReport();
  EXPECT_NE(pixels.find("a: "), std::string::npos) << pixels;
  EXPECT_NE(pixels.find("b: "), std::string::npos) << pixels;
  EXPECT_NE(pixels.find("largest edge bend"), std::string::npos) << pixels;
  ASSERT_TRUE(renderer->Render()) << renderer->GetLastError();
}
