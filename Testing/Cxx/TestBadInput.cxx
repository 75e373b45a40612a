// Bad input through the API ends with an error that says what is wrong, or a defined result:
// never a read out of bounds, a NaN that flows on, or a write reported done that was not.
#include "TestUtilities.h"

#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricCompositor.h"
#include "vtkCatadioptricEnvironmentSource.h"
#include "vtkCatadioptricImageSupport.h"
#include "vtkCatadioptricLighting.h"
#include "vtkCatadioptricMeshCheck.h"
#include "vtkCatadioptricOccluders.h"
#include "vtkCatadioptricPainterSort.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCatadioptricRayTracer.h"
#include "vtkCatadioptricRemesher.h"
#include "vtkCatadioptricSceneRenderer.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"
#include "vtkUnsignedCharArray.h"

#include <gtest/gtest.h>

#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>

namespace
{
using catar_test::DemoCamera;
using catar_test::ErrorCounter;

bool Contains(const std::string& text, const std::string& part)
{
  return text.find(part) != std::string::npos;
}

// A sphere seen in the demo camera's mirror (behind the camera, as the demo's objects), with
// point normals and a per-cell colour array.
vtkSmartPointer<vtkPolyData> Sphere()
{
  vtkNew<vtkSphereSource> s;
  s->SetCenter(0.0, -0.3, 1.0);
  s->SetRadius(0.05);
  s->SetThetaResolution(16);
  s->SetPhiResolution(8);
  s->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(s->GetOutput());
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(4);
  colors->SetNumberOfTuples(mesh->GetNumberOfCells());
  colors->FillValue(200);
  mesh->GetCellData()->AddArray(colors);
  return mesh;
}

// Sphere() with one more triangle whose last point id is `id`.
vtkSmartPointer<vtkPolyData> SphereWithBadId(vtkIdType id)
{
  vtkSmartPointer<vtkPolyData> mesh = Sphere();
  vtkNew<vtkCellArray> polys;
  polys->DeepCopy(mesh->GetPolys());
  const vtkIdType tri[3] = { 0, 1, id };
  polys->InsertNextCell(3, tri);
  mesh->SetPolys(polys);
  vtkUnsignedCharArray::SafeDownCast(mesh->GetCellData()->GetArray("Colors"))
    ->InsertNextTuple4(1, 2, 3, 4);
  return mesh;
}

// The sphere projected by the demo camera (and sorted), ready for the sinks.
vtkSmartPointer<vtkPolyData> Projected(vtkPolyData* mesh)
{
  vtkNew<vtkCatadioptricProjection> proj;
  proj->SetCamera(DemoCamera());
  proj->SetInputData(mesh);
  proj->Update();
  auto out = vtkSmartPointer<vtkPolyData>::New();
  out->DeepCopy(proj->GetOutput());
  return out;
}
} // namespace

TEST(BadInput, CellsNamingMissingPointsAreRefusedByEveryFilter)
{
  for (vtkIdType id : { vtkIdType(-1), vtkIdType(-1000000), vtkIdType(1000), vtkIdType(1) << 40 })
  {
    SCOPED_TRACE(id);
    vtkSmartPointer<vtkPolyData> bad = SphereWithBadId(id);
    std::string error;
    EXPECT_FALSE(vtkCatadioptricMeshCheck::Check(bad, error));
    EXPECT_TRUE(Contains(error, "names point " + std::to_string(id))) << error;

    vtkNew<vtkCatadioptricProjection> proj;
    vtkNew<ErrorCounter> projErrors;
    projErrors->Watch(proj);
    proj->SetCamera(DemoCamera());
    proj->SetInputData(bad);
    proj->Update();
    EXPECT_EQ(projErrors->Count, 1);
    EXPECT_TRUE(Contains(projErrors->Last, "names point")) << projErrors->Last;

    // Downstream filters fed a mesh that carries the projection's arrays but a bad cell.
    vtkSmartPointer<vtkPolyData> projected = Projected(Sphere());
    vtkSmartPointer<vtkPolyData> tampered = vtkSmartPointer<vtkPolyData>::New();
    tampered->DeepCopy(projected);
    tampered->SetPolys(bad->GetPolys());
    for (const char* name : { "CentroidDepth", "CentroidMirrorPoint", "Visible", "Colors" })
    {
      vtkDataArray* a = tampered->GetCellData()->GetArray(name);
      ASSERT_NE(a, nullptr) << name;
      a->InsertNextTuple(a->GetTuple(0));
    }
    vtkNew<vtkLight> light;
    light->SetPosition(0, 0, 2);
    vtkNew<vtkCatadioptricLighting> lighting;
    lighting->AddLight(light);
    vtkNew<vtkCatadioptricPainterSort> sort;
    vtkNew<vtkCatadioptricCompositor> compositor;
    vtkNew<vtkCatadioptricRayTracer> tracer;
    tracer->SetCamera(DemoCamera());
    lighting->SetInputData(tampered);
    sort->SetInputData(tampered);
    compositor->AddMeshData(tampered);
    tracer->AddMeshData(tampered);
    for (vtkAlgorithm* filter :
      std::initializer_list<vtkAlgorithm*>{ lighting, sort, compositor, tracer })
    {
      vtkNew<ErrorCounter> errors;
      errors->Watch(filter);
      filter->Update();
      EXPECT_EQ(errors->Count, 1) << filter->GetClassName();
      EXPECT_TRUE(Contains(errors->Last, "names point"))
        << filter->GetClassName() << ": " << errors->Last;
    }
  }
}

TEST(BadInput, OccludersNamingMissingPointsAreRefused)
{
  // The occluders are read only to build the shadows' ray scene: checked there, through the
  // occluder port and through shared occluders alike.
  vtkSmartPointer<vtkPolyData> projected = Projected(Sphere());
  vtkSmartPointer<vtkPolyData> bad = SphereWithBadId(-1);
  for (bool shared : { false, true })
  {
    vtkNew<vtkLight> light;
    light->SetPosition(0, 0, 2);
    vtkNew<vtkCatadioptricLighting> lighting;
    lighting->AddLight(light);
    lighting->SetShadows(true);
    lighting->SetInputData(projected);
    vtkNew<vtkCatadioptricOccluders> occluders;
    if (shared)
    {
      occluders->AddMesh(projected);
      occluders->AddMesh(bad);
      lighting->SetOccluders(occluders);
    }
    else
    {
      lighting->AddOccluderData(bad);
    }
    vtkNew<ErrorCounter> errors;
    errors->Watch(lighting);
    vtkNew<ErrorCounter> occluderErrors;
    occluderErrors->Watch(occluders);
    lighting->Update();
    EXPECT_EQ(errors->Count, 1) << shared;
    const std::string& message = shared ? occluderErrors->Last : errors->Last;
    EXPECT_TRUE(Contains(message, "an occluder mesh: cell")) << message;
  }
}

TEST(BadInput, IdsAppendedAfterACheckAreCheckedAgain)
{
  vtkSmartPointer<vtkPolyData> mesh = Sphere();
  std::string error;
  ASSERT_TRUE(vtkCatadioptricMeshCheck::Check(mesh, error)) << error;
  // Appended through the legacy API, which need not touch the connectivity's MTime.
  const vtkIdType tri[3] = { 0, 1, 5000 };
  mesh->GetPolys()->InsertNextCell(3, tri);
  mesh->GetCellData()->GetArray("Colors")->InsertNextTuple4(1, 2, 3, 4);
  EXPECT_FALSE(vtkCatadioptricMeshCheck::Check(mesh, error));
  EXPECT_TRUE(Contains(error, "names point 5000")) << error;
}

TEST(BadInput, ArraysShorterThanTheirPointsOrCellsAreRefused)
{
  // Normals (point data) one short.
  vtkSmartPointer<vtkPolyData> mesh = Sphere();
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(mesh->GetNumberOfPoints() - 1);
  normals->FillValue(1.0f);
  mesh->GetPointData()->SetNormals(normals);
  vtkNew<vtkCatadioptricProjection> proj;
  vtkNew<ErrorCounter> errors;
  errors->Watch(proj);
  proj->SetCamera(DemoCamera());
  proj->SetInputData(mesh);
  proj->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_TRUE(Contains(errors->Last, "point array 'Normals'")) << errors->Last;

  // Colours (cell data) short, straight into the compositor.
  vtkSmartPointer<vtkPolyData> projected = Projected(Sphere());
  projected->GetCellData()->GetArray("Colors")->SetNumberOfTuples(3);
  vtkNew<vtkCatadioptricCompositor> compositor;
  vtkNew<ErrorCounter> compositorErrors;
  compositorErrors->Watch(compositor);
  compositor->SetColorArrayName("Colors");
  compositor->AddMeshData(projected);
  compositor->Update();
  EXPECT_EQ(compositorErrors->Count, 1);
  EXPECT_TRUE(Contains(compositorErrors->Last, "cell array 'Colors' has 3 tuples"))
    << compositorErrors->Last;

  // A frame whose scalars are shorter than its extent (as Python can set them): refused by both
  // sinks; it was read past the array's end.
  vtkSmartPointer<vtkCatadioptricCamera> camera = DemoCamera();
  const int w = camera->GetImageWidth(), h = camera->GetImageHeight();
  vtkNew<vtkImageData> frame;
  frame->SetDimensions(w, h, 1);
  vtkNew<vtkUnsignedCharArray> pixels;
  pixels->SetNumberOfComponents(3);
  pixels->SetNumberOfTuples(10);
  pixels->FillValue(7);
  frame->GetPointData()->SetScalars(pixels);
  vtkNew<vtkCatadioptricCompositor> onFrame;
  vtkNew<ErrorCounter> frameErrors;
  frameErrors->Watch(onFrame);
  onFrame->SetInputData(0, frame);
  onFrame->AddMeshData(Projected(Sphere()));
  onFrame->Update();
  EXPECT_EQ(frameErrors->Count, 1);
  EXPECT_TRUE(Contains(frameErrors->Last, "scalars hold 10 pixels")) << frameErrors->Last;
  vtkNew<vtkCatadioptricRayTracer> tracer;
  vtkNew<ErrorCounter> tracerErrors;
  tracerErrors->Watch(tracer);
  tracer->SetCamera(camera);
  tracer->SetInputData(0, frame);
  tracer->AddMeshData(Projected(Sphere()));
  tracer->Update();
  EXPECT_GE(tracerErrors->Count, 1);
  EXPECT_TRUE(Contains(tracerErrors->Last, "scalars hold 10 pixels")) << tracerErrors->Last;
}

TEST(BadInput, EmptyOrNonIntegerTextureIndexIsRefused)
{
  vtkSmartPointer<vtkPolyData> projected = Projected(Sphere());
  vtkNew<vtkFloatArray> tc;
  tc->SetName("TCoords");
  tc->SetNumberOfComponents(2);
  tc->SetNumberOfTuples(projected->GetNumberOfPoints());
  tc->FillValue(0.5f);
  projected->GetPointData()->SetTCoords(tc);
  vtkNew<vtkImageData> texture;
  texture->SetDimensions(4, 4, 1);
  texture->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
  for (double value : { std::numeric_limits<double>::quiet_NaN(), 1e30, 0.5, -1.0 })
  {
    for (bool empty : { true, false })
    {
      vtkNew<vtkDoubleArray> index;
      index->SetName("TextureIndex");
      if (!empty)
      {
        index->InsertNextValue(value);
      }
      projected->GetFieldData()->AddArray(index);
      vtkNew<vtkCatadioptricCompositor> compositor;
      vtkNew<ErrorCounter> errors;
      errors->Watch(compositor);
      compositor->AddMeshData(projected);
      compositor->AddTextureData(texture);
      compositor->Update();
      const bool fine = !empty && value == -1.0;
      EXPECT_EQ(errors->Count, fine ? 0 : 1) << value << " empty " << empty;
      if (!fine)
      {
        EXPECT_TRUE(Contains(errors->Last, "TextureIndex")) << errors->Last;
      }
    }
  }
}

TEST(BadInput, RemesherRepairsBadIdsAndNaNPointsOfAMeshWithCellData)
{
  // Every scene object carries cell data; the transfer must locate only the repairable cells.
  vtkSmartPointer<vtkPolyData> mesh = SphereWithBadId(1000);
  mesh->GetPoints()->SetPoint(3, std::nan(""), 0.0, 1.0);
  vtkNew<vtkCatadioptricRemesher> remesher;
  remesher->SetInputData(mesh);
  remesher->SetModeToTargetArea();
  remesher->SetTargetArea(2e-4);
  vtkNew<ErrorCounter> errors;
  errors->Watch(remesher);
  remesher->Update();
  EXPECT_EQ(errors->Count, 0) << errors->Last;
  vtkPolyData* out = remesher->GetOutput();
  ASSERT_GT(out->GetNumberOfPolys(), 0);
  vtkDataArray* colors = out->GetCellData()->GetArray("Colors");
  ASSERT_NE(colors, nullptr);
  EXPECT_EQ(colors->GetNumberOfTuples(), out->GetNumberOfCells());
  // The appended bad cell's colour (1, 2, 3, 4) is never the one found.
  for (vtkIdType c = 0; c < colors->GetNumberOfTuples(); ++c)
  {
    EXPECT_EQ(colors->GetComponent(c, 0), 200.0) << c;
  }
  std::string error;
  EXPECT_TRUE(vtkCatadioptricMeshCheck::Check(out, error)) << error;
}

TEST(BadInput, NaNLightsAndMaterialsAreRefused)
{
  vtkSmartPointer<vtkPolyData> projected = Projected(Sphere());
  for (int what = 0; what < 3; ++what)
  {
    vtkNew<vtkLight> light;
    light->SetPosition(0, 0, 2);
    vtkNew<vtkCatadioptricLighting> lighting;
    lighting->AddLight(light);
    lighting->SetInputData(projected);
    const double nan = std::numeric_limits<double>::quiet_NaN();
    if (what == 0)
    {
      light->SetDiffuseColor(nan, 1, 1);
    }
    else if (what == 1)
    {
      lighting->GetProperty()->SetSpecularPower(nan);
    }
    else
    {
      lighting->SetGlobalAmbient(nan, 0, 0);
    }
    vtkNew<ErrorCounter> errors;
    errors->Watch(lighting);
    lighting->Update();
    EXPECT_EQ(errors->Count, 1) << what;
    EXPECT_TRUE(Contains(errors->Last, "NaN or infinite")) << errors->Last;
  }
}

TEST(BadInput, DegenerateNormalsTakeTheMeshsOwn)
{
  // Gouraud with all-zero normals colours every vertex as without normals (the filter's own
  // vertex normals), not as a flat ambient.
  vtkSmartPointer<vtkPolyData> plain = Projected(Sphere());
  plain->GetPointData()->SetNormals(nullptr); // the sphere source's own
  plain->GetPointData()->RemoveArray("Normals");
  vtkSmartPointer<vtkPolyData> zeros = vtkSmartPointer<vtkPolyData>::New();
  zeros->DeepCopy(plain);
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(zeros->GetNumberOfPoints());
  normals->FillValue(0.0f);
  normals->SetComponent(0, 0, std::nanf(""));
  zeros->GetPointData()->SetNormals(normals);
  vtkUnsignedCharArray* out[2];
  vtkNew<vtkCatadioptricLighting> lit[2];
  vtkNew<vtkLight> light;
  light->SetPosition(0.3, -0.1, 1.4);
  light->SetFocalPoint(0.0, -0.3, 1.0);
  for (int k = 0; k < 2; ++k)
  {
    lit[k]->AddLight(light);
    lit[k]->SetShadingModeToGouraud();
    lit[k]->SetShadows(false);
    lit[k]->SetInputData(k == 0 ? plain : zeros);
    lit[k]->Update();
    out[k] =
      vtkUnsignedCharArray::SafeDownCast(lit[k]->GetOutput()->GetPointData()->GetArray("Colors"));
    ASSERT_NE(out[k], nullptr);
  }
  ASSERT_EQ(out[0]->GetNumberOfValues(), out[1]->GetNumberOfValues());
  int distinct = 0;
  for (vtkIdType i = 0; i < out[0]->GetNumberOfValues(); ++i)
  {
    EXPECT_EQ(out[0]->GetValue(i), out[1]->GetValue(i)) << i;
    distinct += out[0]->GetValue(i) != out[0]->GetValue(i % 4);
  }
  EXPECT_GT(distinct, 0); // shaded, not one flat colour
}

// Image inputs that are not files (a FIFO nobody writes, a device that never ends) are refused at
// once: the FIFO blocked the reader, /dev/zero was read without end.
TEST(BadInput, ImagesThatAreNotFilesAreRefused)
{
  const std::string fifo = std::string(CATAR_TEST_OUTPUT_DIR) + "/bad-input-fifo.png";
  std::remove(fifo.c_str());
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& path : { fifo, std::string("/dev/zero"), std::string("/tmp") })
  {
    std::string error;
    EXPECT_EQ(vtkCatadioptricImageSupport::ReadImageFile(path, error), nullptr) << path;
    EXPECT_TRUE(Contains(error, "is not a regular file")) << error;
  }
  std::remove(fifo.c_str());
}

TEST(BadInput, FailedWritesFail)
{
  vtkSmartPointer<vtkCatadioptricCamera> camera = DemoCamera();
  EXPECT_FALSE(camera->Save("/dev/full"));
  EXPECT_TRUE(Contains(camera->GetLastError(), "writing failed")) << camera->GetLastError();
  EXPECT_FALSE(camera->Save("/nonexistent-folder/camera.yaml"));

  vtkNew<vtkCatadioptricSceneRenderer> renderer;
  vtkNew<ErrorCounter> errors;
  errors->Watch(renderer);
  ASSERT_TRUE(renderer->Render()) << renderer->GetLastError();
  EXPECT_FALSE(renderer->WritePNG(nullptr));
  EXPECT_TRUE(Contains(renderer->GetLastError(), "no output file name"))
    << renderer->GetLastError();
  EXPECT_FALSE(renderer->WritePNG(""));
  EXPECT_FALSE(renderer->WritePNG("/dev/full"));
  EXPECT_TRUE(Contains(renderer->GetLastError(), "writing failed")) << renderer->GetLastError();
  EXPECT_EQ(errors->Count, 3);
}

TEST(BadInput, NaNAndHugeValuesAreRefusedWhereTheyEnter)
{
  // An image size read back from field data.
  vtkSmartPointer<vtkCatadioptricCamera> camera = DemoCamera();
  vtkNew<vtkFieldData> fd;
  camera->WriteToFieldData(fd);
  for (double bad : { std::numeric_limits<double>::quiet_NaN(), 1e300, -5.0 })
  {
    vtkDataArray* intrinsics = fd->GetArray("CameraIntrinsics");
    ASSERT_NE(intrinsics, nullptr);
    const double width = intrinsics->GetComponent(5, 0);
    intrinsics->SetComponent(5, 0, bad);
    vtkNew<vtkCatadioptricCamera> read;
    EXPECT_FALSE(read->ReadFromFieldData(fd)) << bad;
    intrinsics->SetComponent(5, 0, width);
  }
  // The compositor's ImageSize beyond the limit.
  vtkNew<vtkCatadioptricCompositor> compositor;
  vtkNew<ErrorCounter> errors;
  errors->Watch(compositor);
  compositor->SetImageSize(99999, 99999);
  compositor->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_TRUE(Contains(errors->Last, "over the limit")) << errors->Last;
  // Panorama rotation.
  vtkNew<vtkCatadioptricEnvironmentSource> env;
  vtkNew<ErrorCounter> envErrors;
  envErrors->Watch(env);
  env->SetPanoramaRotation(30.0);
  env->SetPanoramaRotation(std::numeric_limits<double>::quiet_NaN());
  EXPECT_EQ(env->GetPanoramaRotation(), 30.0);
  EXPECT_EQ(envErrors->Count, 1);
}
