// vtkCatadioptricRayTracer: the exact reference. Pixels are checked against values computed here
// independently (back projection, analytic ray-plane intersection, the lighting equation), the
// visible-triangle buffer against the faces a convex box shows, and the image against the fast
// path's (projection, painter sort, compositor) on a finely remeshed box.
#include "vtkAlgorithmOutput.h"
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricCompositor.h"
#include "vtkCatadioptricLighting.h"
#include "vtkCatadioptricLightingSupport.h"
#include "vtkCatadioptricPainterSort.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCatadioptricRayTracer.h"
#include "vtkCatadioptricRemesher.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkImageData.h"
#include "vtkIntArray.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"
#include "vtkTypeInt64Array.h"
#include "vtkUnsignedCharArray.h"

#include "Lighting.h"
#include "Projector.h"
#include "TestCameras.h"
#include "TestUtilities.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>

namespace
{
using catar_test::DemoCamera;

// An axis-aligned box as six quads with outward normals, one colour per face (cell data).
const std::array<std::array<unsigned char, 3>, 6> kFaceColors = { { { 220, 40, 40 },
  { 40, 200, 40 }, { 40, 40, 220 }, { 220, 220, 40 }, { 40, 220, 220 }, { 220, 40, 220 } } };

vtkSmartPointer<vtkPolyData> Box(const catar::Vec3& lo, const catar::Vec3& hi)
{
  vtkNew<vtkPoints> pts;
  for (int k = 0; k < 8; ++k)
  {
    pts->InsertNextPoint(k & 1 ? hi.x() : lo.x(), k & 2 ? hi.y() : lo.y(), k & 4 ? hi.z() : lo.z());
  }
  // -x, +x, -y, +y, -z, +z; counter-clockwise seen from outside.
  const vtkIdType faces[6][4] = { { 0, 4, 6, 2 }, { 1, 3, 7, 5 }, { 0, 1, 5, 4 }, { 2, 6, 7, 3 },
    { 0, 2, 3, 1 }, { 4, 5, 7, 6 } };
  vtkNew<vtkCellArray> polys;
  vtkNew<vtkUnsignedCharArray> colors;
  colors->SetName("Colors");
  colors->SetNumberOfComponents(3);
  for (int f = 0; f < 6; ++f)
  {
    polys->InsertNextCell(4, faces[f]);
    colors->InsertNextTuple3(kFaceColors[f][0], kFaceColors[f][1], kFaceColors[f][2]);
  }
  auto box = vtkSmartPointer<vtkPolyData>::New();
  box->SetPoints(pts);
  box->SetPolys(polys);
  box->GetCellData()->AddArray(colors);
  return box;
}

// A quad in the plane y = y0 facing +y (towards the mirror), x in [x0, x1], z in [z0, z1].
vtkSmartPointer<vtkPolyData> Wall(double y0, double x0, double x1, double z0, double z1)
{
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(x0, y0, z0);
  pts->InsertNextPoint(x0, y0, z1);
  pts->InsertNextPoint(x1, y0, z1);
  pts->InsertNextPoint(x1, y0, z0);
  vtkNew<vtkCellArray> polys;
  const vtkIdType quad[4] = { 0, 1, 2, 3 };
  polys->InsertNextCell(4, quad);
  auto wall = vtkSmartPointer<vtkPolyData>::New();
  wall->SetPoints(pts);
  wall->SetPolys(polys);
  return wall;
}

// Pixel (x, y) of a VTK image in OpenCV convention (y down).
const unsigned char* Pixel(vtkImageData* image, int x, int y)
{
  int dims[3];
  image->GetDimensions(dims);
  return static_cast<unsigned char*>(image->GetScalarPointer(x, dims[1] - 1 - y, 0));
}

long long VisibleTriangle(vtkImageData* image, int x, int y)
{
  int dims[3];
  image->GetDimensions(dims);
  auto* ids = vtkTypeInt64Array::SafeDownCast(image->GetPointData()->GetArray("VisibleTriangle"));
  return ids ? ids->GetValue(static_cast<vtkIdType>(dims[1] - 1 - y) * dims[0] + x) : -2;
}
} // namespace

TEST(vtkCatadioptricRayTracer, BoxFacesAndVisibleTriangles)
{
  auto camera = DemoCamera();
  const catar::Projector projector(camera->GetModel());
  const catar::Vec3 lo(-0.01, -0.37, 0.82), hi(0.29, -0.25, 0.91);
  vtkNew<vtkCatadioptricRayTracer> tracer;
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(tracer);
  tracer->SetCamera(camera);
  tracer->AddMeshData(Box(lo, hi));
  tracer->OutputVisibleTriangleOn();
  tracer->Update();
  ASSERT_EQ(errors->Count, 0) << errors->Last;
  vtkImageData* image = tracer->GetOutput();
  EXPECT_GT(tracer->GetNumberOfHits(), 1000);
  EXPECT_LT(tracer->GetNumberOfTracedRays(), tracer->GetNumberOfMirrorRays()); // bounds skip

  // Each face's centre: seen (its outward normal faces the mirror point) -> that face's id and
  // colour at its pixel; not seen -> another face.
  const catar::Vec3 normals[6] = { { -1, 0, 0 }, { 1, 0, 0 }, { 0, -1, 0 }, { 0, 1, 0 },
    { 0, 0, -1 }, { 0, 0, 1 } };
  int seen = 0;
  for (int f = 0; f < 6; ++f)
  {
    catar::Vec3 c = 0.5 * (lo + hi);
    const int axis = f / 2;
    c[axis] = f % 2 ? hi[axis] : lo[axis];
    const catar::ProjectedPoint p = projector.ProjectWorld(c);
    if (p.status != catar::ProjectionStatus::Valid)
    {
      continue;
    }
    const int x = static_cast<int>(std::lround(p.pixel.x()));
    const int y = static_cast<int>(std::lround(p.pixel.y()));
    const catar::Vec3 m = camera->GetModel().CameraToWorld(p.mirrorPoint);
    const long long id = VisibleTriangle(image, x, y);
    if ((m - c).dot(normals[f]) > 1e-9)
    {
      ++seen;
      EXPECT_EQ(id, f) << "face " << f;
      const unsigned char* rgba = Pixel(image, x, y);
      for (int k = 0; k < 3; ++k)
      {
        EXPECT_EQ(rgba[k], kFaceColors[f][k]) << "face " << f;
      }
    }
    else
    {
      EXPECT_NE(id, f) << "face " << f << " is turned away";
    }
  }
  EXPECT_GE(seen, 2);
  // Far from the box (a corner of the image): no triangle, background.
  EXPECT_EQ(VisibleTriangle(image, 0, 0), -1);
  EXPECT_EQ(Pixel(image, 0, 0)[0], 0);
}

namespace
{
// The fast path (projection, painter sort, compositor) and the reference ray tracer on the same
// mesh and camera: their silhouettes (non-black pixels) and colours compared.
struct Agreement
{
  long intersection = 0, union_ = 0, sameColour = 0;
  double IoU() const { return static_cast<double>(intersection) / static_cast<double>(union_); }
};

Agreement FastAgainstExact(vtkCatadioptricCamera* camera, vtkAlgorithmOutput* mesh)
{
  vtkNew<vtkCatadioptricProjection> projection;
  projection->SetInputConnection(mesh);
  projection->SetCamera(camera);
  vtkNew<vtkCatadioptricPainterSort> sort;
  sort->SetInputConnection(projection->GetOutputPort());
  vtkNew<vtkCatadioptricCompositor> compositor;
  compositor->AddMeshConnection(sort->GetOutputPort());
  compositor->Update();
  vtkNew<vtkCatadioptricRayTracer> tracer;
  tracer->SetCamera(camera);
  tracer->AddMeshConnection(mesh);
  tracer->Update();
  vtkImageData* fast = compositor->GetOutput();
  vtkImageData* exact = tracer->GetOutput();
  int dims[3], dims2[3];
  fast->GetDimensions(dims);
  exact->GetDimensions(dims2);
  Agreement result;
  EXPECT_EQ(dims[0], dims2[0]);
  EXPECT_EQ(dims[1], dims2[1]);
  if (dims[0] != dims2[0] || dims[1] != dims2[1])
  {
    return result;
  }
  for (int y = 0; y < dims[1]; ++y)
  {
    for (int x = 0; x < dims[0]; ++x)
    {
      const unsigned char* a = Pixel(fast, x, y);
      const unsigned char* b = Pixel(exact, x, y);
      const bool ia = a[0] || a[1] || a[2];
      const bool ib = b[0] || b[1] || b[2];
      result.intersection += ia && ib;
      result.union_ += ia || ib;
      result.sameColour += ia && ib && a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
    }
  }
  return result;
}
} // namespace

TEST(vtkCatadioptricRayTracer, AgreesWithTheFastPathOnAFineMesh)
{
  auto camera = DemoCamera();
  vtkNew<vtkCatadioptricRemesher> remesher;
  remesher->SetInputData(Box(catar::Vec3(-0.01, -0.37, 0.82), catar::Vec3(0.29, -0.25, 0.91)));
  remesher->SetTargetArea(2e-5);
  const Agreement a = FastAgainstExact(camera, remesher->GetOutputPort());
  ASSERT_GT(a.union_, 500);
  std::cout << "[ tracer   ] fine box: IoU " << a.IoU() << ", same colour "
            << static_cast<double>(a.sameColour) / static_cast<double>(a.intersection) << " of "
            << a.intersection << " pixels" << std::endl;
  EXPECT_GT(a.IoU(), 0.97);
  EXPECT_GT(a.sameColour, 0.97 * a.intersection);
}

// The same through a hyperbolic mirror tilted 4 degrees (the general quadric solver), the box
// remeshed until no edge bends more than a tenth of a pixel.
TEST(vtkCatadioptricRayTracer, AgreesWithTheFastPathThroughATiltedHyperboloid)
{
  vtkNew<vtkCatadioptricCamera> camera;
  camera->SetModel(catar_test::TiltedHyperboloidCameraModel());
  ASSERT_TRUE(camera->IsValid()) << camera->GetLastError();
  vtkNew<vtkCatadioptricRemesher> remesher;
  remesher->SetInputData(Box(catar::Vec3(-0.01, -0.37, 0.82), catar::Vec3(0.29, -0.25, 0.91)));
  remesher->SetModeToPixelTolerance();
  remesher->SetPixelTolerance(0.1);
  remesher->SetCamera(camera);
  const Agreement a = FastAgainstExact(camera, remesher->GetOutputPort());
  ASSERT_GT(a.union_, 2000);
  std::cout << "[ tracer   ] tilted hyperboloid, box remeshed to 0.1 px: "
            << remesher->GetOutput()->GetNumberOfPolys() << " triangles, IoU " << a.IoU()
            << " over " << a.union_ << " pixels" << std::endl;
  EXPECT_GE(a.IoU(), 0.995);
}

TEST(vtkCatadioptricRayTracer, LightingAndShadowsAreExact)
{
  auto camera = DemoCamera();
  const catar::CameraModel model = camera->GetModel();
  const catar::Projector projector(model);
  const double wallY = -0.5;
  auto wall = Wall(wallY, -0.4, 0.4, 0.6, 1.4);
  // A small occluder between the light and the wall.
  auto occluder = Wall(-0.4, -0.03, 0.03, 0.97, 1.03);
  vtkNew<vtkLight> light;
  light->SetPositional(true);
  light->SetConeAngle(180.0);
  light->SetPosition(0.1, -0.3, 1.2);
  light->SetFocalPoint(0.0, -0.5, 1.0);
  light->SetDiffuseColor(1.0, 0.9, 0.8);
  light->SetAmbientColor(0.0, 0.0, 0.0);
  const catar::Vec3 lightPosition(0.1, -0.3, 1.2);

  for (bool shadows : { false, true })
  {
    vtkNew<vtkCatadioptricLighting> lighting;
    lighting->AddLight(light);
    lighting->SetShadingModeToFlat();
    lighting->SetShadows(shadows);
    lighting->SetDiffuseColor(0.7, 0.7, 0.7);
    lighting->SetAmbient(0.1);
    lighting->SetDiffuse(1.0);
    lighting->SetSpecular(0.3);
    lighting->SetSpecularPower(10.0);
    vtkNew<vtkCatadioptricRayTracer> tracer;
    vtkNew<catar_test::ErrorCounter> errors;
    errors->Watch(tracer);
    tracer->SetCamera(camera);
    tracer->AddMeshData(wall);
    tracer->AddMeshData(occluder);
    tracer->SetMeshLighting(0, lighting);
    tracer->SetMeshLighting(1, lighting);
    tracer->OutputVisibleTriangleOn();
    tracer->Update();
    ASSERT_EQ(errors->Count, 0) << errors->Last;
    vtkImageData* image = tracer->GetOutput();

    // The lighting filter's parameters, as the fast path reads them.
    const catar::Material material = vtkCatadioptricLightingSupport::ConvertProperty(
      lighting->GetProperty(), lighting->GetEmission());
    const std::vector<catar::LightSource> sources =
      vtkCatadioptricLightingSupport::ConvertLights(lighting->GetLights());
    ASSERT_EQ(sources.size(), 1u);
    EXPECT_EQ(sources[0].kind, catar::LightSource::Kind::Point);
    const catar::Vec3 ambient(lighting->GetGlobalAmbient()[0], lighting->GetGlobalAmbient()[1],
      lighting->GetGlobalAmbient()[2]);

    // Points of the wall: one in the occluder's shadow, others lit.
    const catar::Vec3 occluderCentre(0.0, -0.4, 1.0);
    const double t = (wallY - lightPosition.y()) / (occluderCentre.y() - lightPosition.y());
    const catar::Vec3 shadowed = lightPosition + t * (occluderCentre - lightPosition);
    int checked = 0;
    for (const catar::Vec3& q : { shadowed, catar::Vec3(0.2, wallY, 1.2),
           catar::Vec3(-0.25, wallY, 0.9), catar::Vec3(0.1, wallY, 0.7) })
    {
      const catar::ProjectedPoint pq = projector.ProjectWorld(q);
      ASSERT_EQ(pq.status, catar::ProjectionStatus::Valid);
      const int x = static_cast<int>(std::lround(pq.pixel.x()));
      const int y = static_cast<int>(std::lround(pq.pixel.y()));
      ASSERT_EQ(VisibleTriangle(image, x, y), 0); // the wall, mesh 0, cell 0
      // The exact hit of this pixel's centre ray with the wall plane, computed here.
      const catar::BackProjectedRay ray = projector.BackProjectWorld(catar::Vec2(x, y));
      ASSERT_TRUE(catar::HasProjection(ray.status));
      const double s = (wallY - ray.mirrorPoint.y()) / ray.direction.y();
      const catar::Vec3 p = ray.mirrorPoint + s * ray.direction;
      // Is p in the occluder's shadow? Segment p -> light against the occluder's plane y = -0.4.
      const double u = (-0.4 - p.y()) / (lightPosition.y() - p.y());
      const catar::Vec3 o = p + u * (lightPosition - p);
      const bool inShadow = std::abs(o.x()) < 0.03 && std::abs(o.z() - 1.0) < 0.03;
      EXPECT_EQ(inShadow, (q - shadowed).norm() < 1e-12) << "point " << q.transpose();
      const unsigned char lit = shadows && inShadow ? 0 : 1;
      const catar::Vec3 expected = catar::Shade(
        p, catar::Vec3(0, 1, 0), ray.mirrorPoint, sources, material, ambient, &lit, false);
      const unsigned char* rgba = Pixel(image, x, y);
      for (int k = 0; k < 3; ++k)
      {
        EXPECT_NEAR(rgba[k], 255.0 * std::min(1.0, expected[k]), 1.0)
          << "channel " << k << " at " << q.transpose() << (shadows ? " with" : " without")
          << " shadows";
      }
      ++checked;
    }
    EXPECT_EQ(checked, 4);
    if (shadows)
    {
      EXPECT_GT(tracer->GetNumberOfShadowRays(), 0);
    }
  }
}

TEST(vtkCatadioptricRayTracer, BadInputGivesErrors)
{
  vtkNew<catar_test::ErrorCounter> errors;
  {
    vtkNew<vtkCatadioptricRayTracer> tracer; // no camera object or file: the panel camera's
    errors->Watch(tracer);
    tracer->AddMeshData(Wall(-0.5, -0.1, 0.1, 0.9, 1.1));
    tracer->Update();
    EXPECT_EQ(errors->Count, 0) << errors->Last;
    tracer->SetFocalLength(0, 1000); // a bad panel value: an error naming it
    tracer->Update();
    EXPECT_EQ(errors->Count, 1);
    EXPECT_NE(errors->Last.find(": Focal Length"), std::string::npos) << errors->Last;
  }
  {
    vtkNew<vtkCatadioptricRayTracer> tracer; // a texture index with no texture
    errors->Watch(tracer);
    tracer->SetCamera(DemoCamera());
    auto wall = Wall(-0.5, -0.1, 0.1, 0.9, 1.1);
    vtkNew<vtkFloatArray> tc;
    tc->SetName("TCoords");
    tc->SetNumberOfComponents(2);
    for (int i = 0; i < 4; ++i)
    {
      tc->InsertNextTuple2(i & 1, i >> 1);
    }
    wall->GetPointData()->SetTCoords(tc);
    vtkNew<vtkIntArray> index;
    index->SetName("TextureIndex");
    index->InsertNextValue(3);
    wall->GetFieldData()->AddArray(index);
    vtkNew<vtkImageData> texture;
    texture->SetDimensions(2, 2, 1);
    texture->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
    tracer->AddMeshData(wall);
    tracer->AddTextureData(texture);
    tracer->Update();
    EXPECT_EQ(errors->Count, 2);
    EXPECT_NE(errors->Last.find("texture 3"), std::string::npos) << errors->Last;
  }
  {
    vtkNew<vtkCatadioptricRayTracer> tracer; // a NaN point
    errors->Watch(tracer);
    tracer->SetCamera(DemoCamera());
    auto wall = Wall(-0.5, -0.1, 0.1, 0.9, 1.1);
    wall->GetPoints()->SetPoint(0, std::nan(""), 0, 0);
    tracer->AddMeshData(wall);
    tracer->Update();
    EXPECT_EQ(errors->Count, 3);
    EXPECT_NE(errors->Last.find("NaN"), std::string::npos) << errors->Last;
  }
}

// The lighting filter's output carries its lighting: the tracer given that output lights it as
// SetMeshLighting with the filter lights the raw mesh, pixel for pixel, for every shading mode;
// with UseInputLighting off it is drawn unlit; a malformed record is an error.
TEST(vtkCatadioptricRayTracer, LightingRecordLightsAsSetMeshLightingDoes)
{
  auto camera = DemoCamera();
  auto box = Box(catar::Vec3(-0.01, -0.37, 0.82), catar::Vec3(0.29, -0.25, 0.91));
  vtkNew<vtkCatadioptricProjection> projection;
  projection->SetCamera(camera);
  projection->SetInputData(box);
  vtkNew<vtkCatadioptricLighting> lighting;
  lighting->SetInputConnection(projection->GetOutputPort());
  lighting->AddSpotLight(0.3, -0.1, 1.1, 0.14, -0.31, 0.86, 40, 1.0, 0.9, 0.8);
  lighting->AddPointLight(-0.1, -0.2, 1.0, 0.6, 0.6, 1.0, 1.0, 0.5, 4.0);
  lighting->AddDirectionalLight(0.2, 0.3, 1.0, 0.3, 0.4, 0.3);
  lighting->SetGlobalAmbient(0.1, 0.15, 0.2);
  lighting->SetEmission(0.05, 0.0, 0.0);
  lighting->SetSpecular(0.4);
  lighting->SetSpecularPower(15);
  lighting->TwoSidedLightingOff();
  lighting->GetProperty()->SetAmbientColor(0.9, 1.0, 0.8);
  for (int mode : { vtkCatadioptricLighting::GOURAUD, vtkCatadioptricLighting::FLAT,
         vtkCatadioptricLighting::NONE })
  {
    lighting->SetShadingMode(mode);
    lighting->Update();
    vtkNew<catar_test::ErrorCounter> errors;
    vtkNew<vtkCatadioptricRayTracer> recorded; // the lighting filter's output, no SetMeshLighting
    errors->Watch(recorded);
    recorded->SetCamera(camera);
    recorded->AddMeshConnection(lighting->GetOutputPort());
    recorded->Update();
    vtkNew<vtkCatadioptricRayTracer> given; // the raw box, SetMeshLighting
    errors->Watch(given);
    given->SetCamera(camera);
    given->AddMeshData(box);
    given->SetMeshLighting(0, lighting);
    given->Update();
    ASSERT_EQ(errors->Count, 0) << errors->Last;
    vtkNew<vtkCatadioptricRayTracer> unlit; // the output, its lit Colors drawn as they are
    unlit->SetCamera(camera);
    unlit->AddMeshConnection(lighting->GetOutputPort());
    unlit->UseInputLightingOff();
    unlit->Update();

    int dims[3];
    recorded->GetOutput()->GetDimensions(dims);
    long object = 0, differ = 0, unlitDiffer = 0;
    for (int y = 0; y < dims[1]; ++y)
    {
      for (int x = 0; x < dims[0]; ++x)
      {
        const unsigned char* a = Pixel(recorded->GetOutput(), x, y);
        const unsigned char* b = Pixel(given->GetOutput(), x, y);
        const unsigned char* c = Pixel(unlit->GetOutput(), x, y);
        object += b[0] || b[1] || b[2];
        differ += !std::equal(a, a + 4, b);
        unlitDiffer += !std::equal(c, c + 4, b);
      }
    }
    std::cout << "[ tracer   ] lighting record, shading mode " << mode << ": " << object
              << " object pixels, " << differ << " differ from SetMeshLighting's, " << unlitDiffer
              << " unlit" << std::endl;
    EXPECT_GT(object, 2000);
    EXPECT_EQ(differ, 0) << "shading mode " << mode;
    if (mode != vtkCatadioptricLighting::NONE)
    {
      // The lighting filter's colours at vertices or centroids differ from the exact ones.
      EXPECT_GT(unlitDiffer, object / 4) << "shading mode " << mode;
    }
  }

  // A malformed record: an error that says so.
  vtkNew<vtkPolyData> bad;
  bad->ShallowCopy(lighting->GetOutput());
  vtkNew<vtkFieldData> fd;
  fd->DeepCopy(lighting->GetOutput()->GetFieldData());
  fd->RemoveArray("LightingLights");
  bad->SetFieldData(fd);
  vtkNew<vtkCatadioptricRayTracer> tracer;
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(tracer);
  tracer->SetCamera(camera);
  tracer->AddMeshData(bad);
  tracer->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Last.find("malformed lighting record"), std::string::npos) << errors->Last;
  tracer->UseInputLightingOff();
  tracer->Update();
  EXPECT_EQ(errors->Count, 1) << errors->Last;
}

namespace
{
// A lit sphere of 64 x 32 facets (with point normals) in view of the demo camera.
vtkSmartPointer<vtkPolyData> Ball(double x, double y, double z, double radius)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(x, y, z);
  sphere->SetRadius(radius);
  sphere->SetThetaResolution(64);
  sphere->SetPhiResolution(32);
  sphere->Update();
  return sphere->GetOutput();
}

vtkSmartPointer<vtkCatadioptricLighting> Spotlight()
{
  auto lighting = vtkSmartPointer<vtkCatadioptricLighting>::New();
  lighting->AddSpotLight(0.25, 0.05, 1.35, 0.06, -0.32, 0.92, 45, 1.0, 0.95, 0.85);
  lighting->SetDiffuseColor(0.2, 0.6, 1.0);
  lighting->SetSpecular(0.4);
  lighting->SetShadingModeToGouraud();
  return lighting;
}

// A tracer of `meshes`, each lit by `lighting`, through `camera`, with the visible triangles.
void SetUpTracer(vtkCatadioptricRayTracer* tracer, vtkCatadioptricCamera* camera,
  const std::vector<vtkPolyData*>& meshes, vtkCatadioptricLighting* lighting)
{
  tracer->SetCamera(camera);
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    tracer->AddMeshData(meshes[m]);
    tracer->SetMeshLighting(static_cast<int>(m), lighting);
  }
  tracer->OutputVisibleTriangleOn();
}

// Renders `meshes` lit by `lighting` through `camera` with a tracer of its own (nothing kept).
vtkSmartPointer<vtkImageData> FreshRender(vtkCatadioptricCamera* camera,
  const std::vector<vtkPolyData*>& meshes, vtkCatadioptricLighting* lighting)
{
  vtkNew<vtkCatadioptricCamera> copy;
  copy->SetModel(camera->GetModel());
  vtkNew<vtkCatadioptricRayTracer> tracer;
  SetUpTracer(tracer, copy, meshes, lighting);
  tracer->Update();
  auto image = vtkSmartPointer<vtkImageData>::New();
  image->DeepCopy(tracer->GetOutput());
  return image;
}

// Pixels (RGBA) and visible triangles that differ between two images of the same size.
long Differences(vtkImageData* a, vtkImageData* b)
{
  int da[3], db[3];
  a->GetDimensions(da);
  b->GetDimensions(db);
  if (da[0] != db[0] || da[1] != db[1])
  {
    return -1;
  }
  auto* ca = static_cast<const unsigned char*>(a->GetScalarPointer());
  auto* cb = static_cast<const unsigned char*>(b->GetScalarPointer());
  auto* ia = vtkTypeInt64Array::SafeDownCast(a->GetPointData()->GetArray("VisibleTriangle"));
  auto* ib = vtkTypeInt64Array::SafeDownCast(b->GetPointData()->GetArray("VisibleTriangle"));
  long n = 0;
  for (vtkIdType i = 0; i < static_cast<vtkIdType>(da[0]) * da[1]; ++i)
  {
    n += !std::equal(ca + 4 * i, ca + 4 * i + 4, cb + 4 * i) ||
      (ia && ib && ia->GetValue(i) != ib->GetValue(i));
  }
  return n;
}
} // namespace

// A new pose or a moved light re-traces the kept scene and rays: the same picture as a tracer
// that starts afresh, with no scene built and no ray back-projected again.
TEST(vtkCatadioptricRayTracer, KeptSceneAndRaysGiveAFreshTracersPicture)
{
  auto camera = DemoCamera();
  auto ball = Ball(0.06, -0.32, 0.92, 0.05);
  auto lighting = Spotlight();
  vtkNew<vtkCatadioptricRayTracer> tracer;
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(tracer);
  SetUpTracer(tracer, camera, { ball }, lighting);
  tracer->Update();
  ASSERT_EQ(errors->Count, 0) << errors->Last;
  EXPECT_GT(tracer->GetNumberOfHits(), 1000);
  EXPECT_EQ(tracer->GetNumberOfSceneBuilds(), 1);
  EXPECT_EQ(tracer->GetNumberOfRayBackProjections(), 1);
  vtkNew<vtkImageData> first;
  first->DeepCopy(tracer->GetOutput());
  EXPECT_EQ(Differences(first, FreshRender(camera, { ball }, lighting)), 0);

  // The camera turned by 0.3 degrees and moved by 2 mm.
  double pose[16];
  camera->GetWorldToCameraElements(pose);
  const double a = 0.3 * 3.14159265358979 / 180.0;
  const double turn[16] = { std::cos(a), 0, std::sin(a), 0.002, 0, 1, 0, 0.001, -std::sin(a), 0,
    std::cos(a), 0, 0, 0, 0, 1 };
  double moved[16];
  vtkMatrix4x4::Multiply4x4(turn, pose, moved);
  camera->SetWorldToCameraElements(moved);
  tracer->Update();
  ASSERT_EQ(errors->Count, 0) << errors->Last;
  EXPECT_EQ(tracer->GetNumberOfSceneBuilds(), 1);
  EXPECT_EQ(tracer->GetNumberOfRayBackProjections(), 1);
  EXPECT_GT(Differences(tracer->GetOutput(), first), 100); // the ball moved in the picture
  EXPECT_EQ(Differences(tracer->GetOutput(), FreshRender(camera, { ball }, lighting)), 0);

  // The spotlight moved.
  vtkNew<vtkImageData> beforeLight;
  beforeLight->DeepCopy(tracer->GetOutput());
  auto* light = vtkLight::SafeDownCast(lighting->GetLights()->GetItemAsObject(0));
  ASSERT_NE(light, nullptr);
  light->SetPosition(0.1, 0.0, 1.4);
  lighting->Modified();
  tracer->Update();
  ASSERT_EQ(errors->Count, 0) << errors->Last;
  EXPECT_EQ(tracer->GetNumberOfSceneBuilds(), 1);
  EXPECT_EQ(tracer->GetNumberOfRayBackProjections(), 1);
  EXPECT_GT(Differences(tracer->GetOutput(), beforeLight), 100);
  EXPECT_EQ(Differences(tracer->GetOutput(), FreshRender(camera, { ball }, lighting)), 0);

  // Another colour and flat shading: the shading arrays are read again, the scene is kept.
  lighting->SetDiffuseColor(1.0, 0.3, 0.2);
  lighting->SetShadingModeToFlat();
  tracer->Update();
  ASSERT_EQ(errors->Count, 0) << errors->Last;
  EXPECT_EQ(tracer->GetNumberOfSceneBuilds(), 1);
  EXPECT_EQ(Differences(tracer->GetOutput(), FreshRender(camera, { ball }, lighting)), 0);

  // Another sample count back-projects the rays again (and a pose change after it does not).
  tracer->SetSamples(2);
  tracer->Update();
  EXPECT_EQ(tracer->GetNumberOfRayBackProjections(), 2);
  EXPECT_EQ(tracer->GetNumberOfSceneBuilds(), 1);
}

// A mesh whose points are changed in place, marked modified by its points or by itself (the scene
// refitted), whose cells change, and a mesh added or taken away (the scene built again): the
// picture is a fresh tracer's.
TEST(vtkCatadioptricRayTracer, ChangedMeshesBuildTheSceneAgain)
{
  auto camera = DemoCamera();
  auto ball = Ball(0.06, -0.32, 0.92, 0.05);
  auto lighting = Spotlight();
  vtkNew<vtkCatadioptricRayTracer> tracer;
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(tracer);
  SetUpTracer(tracer, camera, { ball }, lighting);
  tracer->Update();
  ASSERT_EQ(errors->Count, 0) << errors->Last;
  vtkNew<vtkImageData> first;
  first->DeepCopy(tracer->GetOutput());
  const vtkIdType hits = tracer->GetNumberOfHits();

  // Points moved in place by 2 cm along x, then the points marked modified.
  vtkPoints* points = ball->GetPoints();
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
  {
    double p[3];
    points->GetPoint(i, p);
    p[0] += 0.02;
    points->SetPoint(i, p);
  }
  points->Modified();
  tracer->Update();
  ASSERT_EQ(errors->Count, 0) << errors->Last;
  EXPECT_EQ(tracer->GetNumberOfSceneBuilds(), 1); // the same triangles: refitted
  EXPECT_EQ(tracer->GetNumberOfSceneRefits(), 1);
  EXPECT_EQ(tracer->GetNumberOfRayBackProjections(), 1);
  EXPECT_GT(Differences(tracer->GetOutput(), first), 100);
  EXPECT_EQ(Differences(tracer->GetOutput(), FreshRender(camera, { ball }, lighting)), 0);

  // Points written through the raw array, only the mesh marked modified.
  vtkDataArray* data = points->GetData();
  for (vtkIdType i = 0; i < data->GetNumberOfTuples(); ++i)
  {
    data->SetComponent(i, 2, data->GetComponent(i, 2) + 0.01);
  }
  vtkNew<vtkImageData> second;
  second->DeepCopy(tracer->GetOutput());
  ball->Modified();
  tracer->Update();
  ASSERT_EQ(errors->Count, 0) << errors->Last;
  EXPECT_EQ(tracer->GetNumberOfSceneBuilds(), 1);
  EXPECT_EQ(tracer->GetNumberOfSceneRefits(), 2);
  EXPECT_GT(Differences(tracer->GetOutput(), second), 100);
  EXPECT_EQ(Differences(tracer->GetOutput(), FreshRender(camera, { ball }, lighting)), 0);

  // Other cells (every other triangle left out): built again.
  vtkNew<vtkCellArray> half;
  vtkNew<vtkIdList> cell;
  for (vtkIdType c = 0; c < ball->GetNumberOfPolys(); c += 2)
  {
    ball->GetPolys()->GetCellAtId(c, cell);
    half->InsertNextCell(cell);
  }
  vtkSmartPointer<vtkCellArray> allCells = ball->GetPolys();
  ball->SetPolys(half);
  tracer->Update();
  ASSERT_EQ(errors->Count, 0) << errors->Last;
  EXPECT_EQ(tracer->GetNumberOfSceneBuilds(), 2);
  EXPECT_EQ(tracer->GetNumberOfSceneRefits(), 2);
  EXPECT_EQ(Differences(tracer->GetOutput(), FreshRender(camera, { ball }, lighting)), 0);
  ball->SetPolys(allCells);

  // A second mesh added.
  auto other = Ball(-0.05, -0.30, 0.95, 0.03);
  tracer->AddMeshData(other);
  tracer->SetMeshLighting(1, lighting);
  tracer->Update();
  ASSERT_EQ(errors->Count, 0) << errors->Last;
  EXPECT_EQ(tracer->GetNumberOfSceneBuilds(), 3); // the cells put back and a mesh added
  EXPECT_GT(tracer->GetNumberOfHits(), hits);
  EXPECT_EQ(Differences(tracer->GetOutput(), FreshRender(camera, { ball, other }, lighting)), 0);
  tracer->Update(); // nothing changed: nothing runs
  EXPECT_EQ(tracer->GetNumberOfSceneBuilds(), 3);

  // The first taken away: the second alone, now mesh 0.
  tracer->RemoveAllMeshConnections();
  tracer->AddMeshData(other);
  tracer->SetMeshLighting(0, lighting);
  tracer->Update();
  ASSERT_EQ(errors->Count, 0) << errors->Last;
  EXPECT_EQ(tracer->GetNumberOfSceneBuilds(), 4);
  EXPECT_EQ(tracer->GetNumberOfSceneRefits(), 2);
  EXPECT_EQ(Differences(tracer->GetOutput(), FreshRender(camera, { other }, lighting)), 0);
}
