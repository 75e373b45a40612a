// vtkCatadioptricLighting: shading modes, the viewer at the reflection point, and shadows (two
// parallel plates: the lower plate is unlit exactly in the umbra of the upper one).
#include "Lighting.h"

#include "vtkAppendPolyData.h"
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricLighting.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"

#include "TestUtilities.h"

#include <gtest/gtest.h>

#include <cmath>

namespace
{
vtkSmartPointer<vtkPolyData> Plate(double x0, double x1, double y0, double y1, double z, int res)
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(x0, y0, z);
  plane->SetPoint1(x1, y0, z);
  plane->SetPoint2(x0, y1, z);
  plane->SetResolution(res, res);
  vtkNew<vtkTriangleFilter> tri;
  tri->SetInputConnection(plane->GetOutputPort());
  tri->Update();
  return tri->GetOutput();
}

std::array<double, 3> ColorAt(vtkDataArray* colors, vtkIdType i)
{
  return { colors->GetComponent(i, 0), colors->GetComponent(i, 1), colors->GetComponent(i, 2) };
}
} // namespace

TEST(vtkCatadioptricLighting, GouraudUsesTheVertexReflectionPointAsViewer)
{
  vtkNew<vtkCatadioptricCamera> cam;
  catar_test::SetSmallDemoCamera(cam);
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0.05, -0.3, 0.95);
  sphere->SetRadius(0.04);
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(12);
  vtkNew<vtkCatadioptricProjection> proj;
  proj->SetCamera(cam);
  proj->SetInputConnection(sphere->GetOutputPort());
  vtkNew<vtkLight> light;
  light->SetPositional(true);
  light->SetPosition(0.2, -0.2, 1.3);
  light->SetFocalPoint(0.05, -0.3, 0.95);
  light->SetConeAngle(40);
  light->SetAmbientColor(0, 0, 0);
  vtkNew<vtkCatadioptricLighting> lighting;
  lighting->SetInputConnection(proj->GetOutputPort());
  lighting->AddLight(light);
  lighting->GetProperty()->SetSpecular(0.6);
  lighting->GetProperty()->SetSpecularPower(20);
  lighting->GetProperty()->SetDiffuseColor(0.8, 0.6, 0.4);
  lighting->ShadowsOff();
  lighting->Update();
  vtkPolyData* out = lighting->GetOutput();
  vtkDataArray* colors = out->GetPointData()->GetArray("Colors");
  ASSERT_NE(colors, nullptr);
  ASSERT_EQ(colors->GetNumberOfTuples(), out->GetNumberOfPoints());
  EXPECT_EQ(out->GetCellData()->GetArray("Colors"), nullptr);

  // Recompute a few vertices with the Core equation, the viewer at the vertex's mirror point.
  catar::LightSource l;
  l.kind = catar::LightSource::Kind::Spot;
  l.position = catar::Vec3(0.2, -0.2, 1.3);
  l.focalPoint = catar::Vec3(0.05, -0.3, 0.95);
  l.coneAngle = 40;
  l.exponent = light->GetExponent();
  l.ambient = catar::Vec3::Zero();
  catar::Material m;
  m.ambient = 0.0 * catar::Vec3(0.8, 0.6, 0.4);
  vtkProperty* p = lighting->GetProperty();
  m.ambient = p->GetAmbient() *
    catar::Vec3(p->GetAmbientColor()[0], p->GetAmbientColor()[1], p->GetAmbientColor()[2]);
  m.diffuse = p->GetDiffuse() * catar::Vec3(0.8, 0.6, 0.4);
  m.specular = 0.6 * catar::Vec3(1, 1, 1);
  m.shininess = 20;
  vtkDataArray* mirror = out->GetPointData()->GetArray("MirrorPoint");
  const catar::CameraModel model = cam->GetModel();
  int checked = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); i += 5)
  {
    double x[3], mp[3];
    out->GetPoint(i, x);
    mirror->GetTuple(i, mp);
    const catar::Vec3 pt(x[0], x[1], x[2]);
    const catar::Vec3 n = (pt - catar::Vec3(0.05, -0.3, 0.95)).normalized();
    const catar::Vec3 viewer = model.CameraToWorld(catar::Vec3(mp[0], mp[1], mp[2]));
    const catar::Vec3 c =
      catar::Shade(pt, n, viewer, { l }, m, catar::Vec3(0.2, 0.2, 0.2), nullptr, true);
    const auto got = ColorAt(colors, i);
    // Vertex normals of the tessellated sphere differ slightly from the exact radial normal.
    EXPECT_NEAR(got[0], 255 * c.x(), 8.0) << i;
    EXPECT_NEAR(got[1], 255 * c.y(), 8.0) << i;
    ++checked;
  }
  EXPECT_GT(checked, 20);

  // Flat: one colour per cell; none: the base colour.
  lighting->SetShadingModeToFlat();
  lighting->Update();
  EXPECT_NE(lighting->GetOutput()->GetCellData()->GetArray("Colors"), nullptr);
  EXPECT_EQ(lighting->GetOutput()->GetPointData()->GetArray("Colors"), nullptr);
  lighting->SetShadingModeToNone();
  lighting->Update();
  vtkDataArray* blob = lighting->GetOutput()->GetCellData()->GetArray("Colors");
  ASSERT_NE(blob, nullptr);
  EXPECT_EQ(ColorAt(blob, 3), (std::array<double, 3>{ 204, 153, 102 }));
}

TEST(vtkCatadioptricLighting, LowerPlateIsDarkExactlyInTheUmbra)
{
  vtkNew<vtkCatadioptricCamera> cam;
  catar_test::SetSmallDemoCamera(cam);
  // Lower plate 30 x 30 cm at z = 0.80, upper plate 8 x 8 cm at z = 0.90, behind the camera.
  const double zl = 0.80, zu = 0.90;
  const double ux0 = -0.04, ux1 = 0.04, uy0 = -0.44, uy1 = -0.36;
  vtkNew<vtkAppendPolyData> both;
  both->AddInputData(Plate(-0.15, 0.15, -0.55, -0.25, zl, 60));
  both->AddInputData(Plate(ux0, ux1, uy0, uy1, zu, 8));
  vtkNew<vtkCatadioptricProjection> proj;
  proj->SetCamera(cam);
  proj->SetInputConnection(both->GetOutputPort());
  const double L[3] = { 0.02, -0.41, 1.10 };
  vtkNew<vtkLight> light;
  light->SetPositional(true);
  light->SetPosition(L);
  light->SetFocalPoint(0.0, -0.4, zl);
  light->SetConeAngle(80);
  light->SetAmbientColor(0, 0, 0);
  vtkNew<vtkCatadioptricLighting> lighting;
  lighting->SetInputConnection(proj->GetOutputPort());
  lighting->AddLight(light);
  lighting->Update();
  vtkPolyData* out = lighting->GetOutput();
  vtkDataArray* colors = out->GetPointData()->GetArray("Colors");
  vtkDataArray* visible = out->GetPointData()->GetArray("Visible");
  ASSERT_TRUE(colors && visible);
  // The umbra: the upper plate projected from the light onto z = zl.
  const double s = (zl - L[2]) / (zu - L[2]);
  const double sx0 = L[0] + (ux0 - L[0]) * s, sx1 = L[0] + (ux1 - L[0]) * s;
  const double sy0 = L[1] + (uy0 - L[1]) * s, sy1 = L[1] + (uy1 - L[1]) * s;
  const double margin = 0.006; // vertex spacing is 5 mm; stay clear of the boundary
  int inside = 0, outside = 0;
  double darkest = 255, brightestShadow = 0, dimmestLit = 255;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double x[3];
    out->GetPoint(i, x);
    if (std::abs(x[2] - zl) > 1e-6 || visible->GetComponent(i, 0) == 0)
    {
      continue;
    }
    const double g = colors->GetComponent(i, 1);
    const bool inUmbra =
      x[0] > sx0 + margin && x[0] < sx1 - margin && x[1] > sy0 + margin && x[1] < sy1 - margin;
    const bool clearlyOut =
      x[0] < sx0 - margin || x[0] > sx1 + margin || x[1] < sy0 - margin || x[1] > sy1 + margin;
    if (inUmbra)
    {
      ++inside;
      brightestShadow = std::max(brightestShadow, g);
      darkest = std::min(darkest, g);
    }
    else if (clearlyOut)
    {
      ++outside;
      dimmestLit = std::min(dimmestLit, g);
    }
  }
  ASSERT_GT(inside, 50);
  ASSERT_GT(outside, 500);
  // In the umbra: global ambient only (0.2 * ambient 0.2 * 255 = ~10 levels; light ambient 0).
  const double ambientOnly = 255 * 0.2 * lighting->GetProperty()->GetAmbient() *
    lighting->GetProperty()->GetAmbientColor()[1];
  EXPECT_NEAR(brightestShadow, ambientOnly, 1.0);
  EXPECT_NEAR(darkest, ambientOnly, 1.0);
  // Outside it the diffuse term lights the plate.
  EXPECT_GT(dimmestLit, ambientOnly + 20);

  // Shadows off: the umbra is lit too.
  lighting->ShadowsOff();
  lighting->Update();
  vtkDataArray* noShadow = lighting->GetOutput()->GetPointData()->GetArray("Colors");
  double minInside = 255;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double x[3];
    out->GetPoint(i, x);
    if (std::abs(x[2] - zl) < 1e-6 && x[0] > sx0 + margin && x[0] < sx1 - margin &&
      x[1] > sy0 + margin && x[1] < sy1 - margin && visible->GetComponent(i, 0))
    {
      minInside = std::min(minInside, noShadow->GetComponent(i, 1));
    }
  }
  EXPECT_GT(minInside, ambientOnly + 20);
}

TEST(vtkCatadioptricLighting, UnprojectedInputIsAnError)
{
  vtkNew<vtkSphereSource> sphere;
  vtkNew<vtkCatadioptricLighting> lighting;
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(lighting);
  lighting->SetInputConnection(sphere->GetOutputPort());
  lighting->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Last.find("vtkCatadioptricProjection"), std::string::npos);
}
