// vtkCatadioptricLighting: shading modes, the viewer at the reflection point, and shadows (two
// parallel plates: the lower plate is unlit exactly in the umbra of the upper one); directional
// and point lights against Lambert + Phong written out here, removing one kind of light, and the
// lighting recorded in the output.
#include "Lighting.h"
#include "Polygons.h"

#include "vtkAppendPolyData.h"
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricColorArray.h"
#include "vtkCatadioptricLighting.h"
#include "vtkCatadioptricLightingSupport.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFloatArray.h"
#include "vtkIdList.h"
#include "vtkLight.h"
#include "vtkLightCollection.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkSphereSource.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"

#include "TestUtilities.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

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

namespace
{
// Lambert + Phong at one point, written out here from the equation of Module/Shading/Lighting.h
// (not with Core's Shade): toLight is the unit vector to the light, att its attenuation, the
// light's colour both diffuse and specular, no light ambient, no emission; the normal is turned
// towards the viewer (two-sided lighting). Material: ambient factor ka (ambient colour white),
// diffuse factor kd times diffuseColor, specular factor ks (white), shininess.
struct HandMaterial
{
  double ka, kd, ks, shininess;
  std::array<double, 3> diffuseColor;
};

std::array<double, 3> HandPhong(const catar::Vec3& p, catar::Vec3 n, const catar::Vec3& viewer,
  const catar::Vec3& toLight, double att, const std::array<double, 3>& lightColour,
  const std::array<double, 3>& globalAmbient, const HandMaterial& m)
{
  const catar::Vec3 e = (viewer - p).normalized();
  if (n.dot(e) < 0)
  {
    n = -n;
  }
  const double ndl = n.dot(toLight);
  const double diffuse = std::max(ndl, 0.0);
  const catar::Vec3 r = 2.0 * ndl * n - toLight;
  const double specular = ndl > 0 ? std::pow(std::max(r.dot(e), 0.0), m.shininess) : 0.0;
  std::array<double, 3> c;
  for (int k = 0; k < 3; ++k)
  {
    const double v = globalAmbient[k] * m.ka +
      att *
        (diffuse * lightColour[k] * m.kd * m.diffuseColor[k] + specular * lightColour[k] * m.ks);
    c[k] = 255.0 * std::min(1.0, std::max(0.0, v));
  }
  return c;
}

// A plate at z = 0.80 below the mirror (normal +z, facing it), lit by `lighting` through the
// small demo camera; calls `check(p, viewer, colour)` for every visible point and returns how
// many.
template<typename Check>
int ForEachLitPoint(vtkCatadioptricLighting* lighting, Check check)
{
  vtkNew<vtkCatadioptricCamera> cam;
  catar_test::SetSmallDemoCamera(cam);
  vtkNew<vtkCatadioptricProjection> proj;
  proj->SetCamera(cam);
  proj->SetInputData(Plate(-0.15, 0.15, -0.55, -0.25, 0.80, 20));
  lighting->SetInputConnection(proj->GetOutputPort());
  lighting->Update();
  vtkPolyData* out = lighting->GetOutput();
  vtkDataArray* colors = out->GetPointData()->GetArray("Colors");
  vtkDataArray* mirror = out->GetPointData()->GetArray("MirrorPoint");
  vtkDataArray* visible = out->GetPointData()->GetArray("Visible");
  EXPECT_TRUE(colors && mirror && visible);
  if (!colors || !mirror || !visible)
  {
    return 0;
  }
  const catar::CameraModel model = cam->GetModel();
  int n = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    if (visible->GetComponent(i, 0) == 0)
    {
      continue;
    }
    double x[3], mp[3];
    out->GetPoint(i, x);
    mirror->GetTuple(i, mp);
    check(catar::Vec3(x[0], x[1], x[2]), model.CameraToWorld(catar::Vec3(mp[0], mp[1], mp[2])),
      ColorAt(colors, i));
    ++n;
  }
  return n;
}

// The number of lights of each kind (spot, point, directional) as the lighting reads them.
std::array<int, 3> Kinds(vtkCatadioptricLighting* lighting)
{
  std::array<int, 3> count{ 0, 0, 0 };
  for (const catar::LightSource& s :
    vtkCatadioptricLightingSupport::ConvertLights(lighting->GetLights()))
  {
    ++count[s.kind == catar::LightSource::Kind::Spot ? 0
        : s.kind == catar::LightSource::Kind::Point  ? 1
                                                     : 2];
  }
  return count;
}
} // namespace

TEST(vtkCatadioptricLighting, DirectionalLightOnAPlaneHasTheClosedFormColour)
{
  // Towards the light: chosen so that the plate reflects it towards the mirror (a highlight).
  const catar::Vec3 towards(0.05, -0.9, 0.45);
  const std::array<double, 3> lightColour{ 1.0, 0.9, 0.8 }, globalAmbient{ 0.1, 0.2, 0.3 };
  const HandMaterial m{ 0.2, 0.9, 0.5, 10.0, { 0.7, 0.6, 0.5 } };
  vtkNew<vtkCatadioptricLighting> lighting;
  lighting->AddDirectionalLight(
    towards.x(), towards.y(), towards.z(), lightColour[0], lightColour[1], lightColour[2]);
  lighting->SetDiffuseColor(m.diffuseColor[0], m.diffuseColor[1], m.diffuseColor[2]);
  lighting->SetAmbient(m.ka);
  lighting->SetDiffuse(m.kd);
  lighting->SetSpecular(m.ks);
  lighting->SetSpecularPower(m.shininess);
  lighting->SetGlobalAmbient(globalAmbient.data());
  lighting->ShadowsOff();
  EXPECT_EQ(Kinds(lighting), (std::array<int, 3>{ 0, 0, 1 }));
  double brightest = 0, dimmest = 255;
  const int n = ForEachLitPoint(
    lighting, [&](const catar::Vec3& p, const catar::Vec3& viewer, const std::array<double, 3>& c) {
      const auto expected = HandPhong(
        p, catar::Vec3(0, 0, 1), viewer, towards.normalized(), 1.0, lightColour, globalAmbient, m);
      for (int k = 0; k < 3; ++k)
      {
        EXPECT_NEAR(c[k], expected[k], 1.0) << "channel " << k << " at " << p.transpose();
      }
      brightest = std::max(brightest, c[0]);
      dimmest = std::min(dimmest, c[0]);
    });
  EXPECT_GT(n, 100);
  // The highlight makes the red channel vary by far more than the tolerance over the plate.
  EXPECT_GT(brightest - dimmest, 40) << brightest << " " << dimmest;
}

TEST(vtkCatadioptricLighting, PointLightFallsOffAsItsAttenuationSays)
{
  const catar::Vec3 light(0.02, -0.38, 0.95);
  const std::array<double, 3> white{ 1.0, 1.0, 1.0 }, globalAmbient{ 0.2, 0.2, 0.2 };
  const HandMaterial m{ 0.2, 0.9, 0.2, 20.0, { 0.7, 0.6, 0.5 } };
  std::vector<double> near, far; // red at the points nearest to and farthest from the light
  for (const std::array<double, 3> att :
    { std::array<double, 3>{ 1, 0, 0 }, std::array<double, 3>{ 0.5, 2.0, 30.0 } })
  {
    vtkNew<vtkCatadioptricLighting> lighting;
    lighting->AddPointLight(
      light.x(), light.y(), light.z(), white[0], white[1], white[2], att[0], att[1], att[2]);
    lighting->SetDiffuseColor(m.diffuseColor[0], m.diffuseColor[1], m.diffuseColor[2]);
    lighting->SetAmbient(m.ka);
    lighting->SetDiffuse(m.kd);
    lighting->SetSpecular(m.ks);
    lighting->SetSpecularPower(m.shininess);
    lighting->ShadowsOff();
    EXPECT_EQ(Kinds(lighting), (std::array<int, 3>{ 0, 1, 0 }));
    double nearest = 1e9, farthest = 0, redNear = 0, redFar = 0;
    const int n = ForEachLitPoint(lighting,
      [&](const catar::Vec3& p, const catar::Vec3& viewer, const std::array<double, 3>& c) {
        const double d = (light - p).norm();
        const double a = 1.0 / (att[0] + att[1] * d + att[2] * d * d);
        const auto expected =
          HandPhong(p, catar::Vec3(0, 0, 1), viewer, (light - p) / d, a, white, globalAmbient, m);
        for (int k = 0; k < 3; ++k)
        {
          EXPECT_NEAR(c[k], expected[k], 1.0) << "channel " << k << " at " << p.transpose();
        }
        if (d < nearest)
        {
          nearest = d;
          redNear = c[0];
        }
        if (d > farthest)
        {
          farthest = d;
          redFar = c[0];
        }
      });
    EXPECT_GT(n, 100);
    near.push_back(redNear);
    far.push_back(redFar);
  }
  // With fall-off the far points lose most of their light, the near ones less.
  EXPECT_LT(far[1], 0.6 * far[0]) << far[0] << " " << far[1];
  EXPECT_GT(near[0] - near[1], 5.0);
}

TEST(vtkCatadioptricLighting, RemovingOneKindKeepsTheOthers)
{
  vtkNew<vtkCatadioptricLighting> lighting;
  // Dim lights, so that no channel saturates and each light shows.
  lighting->AddSpotLight(0.2, -0.2, 1.3, 0.0, -0.4, 0.8, 30, 0.2, 0.2, 0.2);
  lighting->AddSpotLight(-0.2, -0.2, 1.3, 0.0, -0.4, 0.8, 45, 0.2, 0, 0);
  lighting->AddPointLight(0.0, -0.4, 0.95, 0, 0.3, 0, 1, 0, 0);
  lighting->AddDirectionalLight(0, -1, 1, 0, 0, 0.2);
  vtkNew<vtkLight> spot; // positional, cone below 90: a spot added as a vtkLight
  spot->SetPositional(true);
  spot->SetConeAngle(20);
  spot->SetPosition(0.1, -0.4, 1.0);
  spot->SetFocalPoint(0.0, -0.4, 0.8);
  spot->SetIntensity(0.2);
  lighting->AddLight(spot);
  vtkNew<vtkLight> sun; // not positional: directional
  sun->SetPosition(1, 0, 1);
  sun->SetIntensity(0.2);
  lighting->AddLight(sun);
  EXPECT_EQ(Kinds(lighting), (std::array<int, 3>{ 3, 1, 2 }));

  // Bad values are errors that add nothing.
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(lighting);
  lighting->AddPointLight(0, 0, 1, 1, 1, 1, 0, 0, 0);
  lighting->AddPointLight(0, 0, 1, 1, 1, 1, 1, -1, 0);
  lighting->AddDirectionalLight(0, 0, 0, 1, 1, 1);
  EXPECT_EQ(errors->Count, 3);
  EXPECT_NE(errors->Last.find("direction"), std::string::npos) << errors->Last;
  EXPECT_EQ(Kinds(lighting), (std::array<int, 3>{ 3, 1, 2 }));

  // The output after removing the point lights is that of a filter with the others only.
  ForEachLitPoint(
    lighting, [](const catar::Vec3&, const catar::Vec3&, const std::array<double, 3>&) {});
  vtkSmartPointer<vtkDataArray> before = vtkSmartPointer<vtkDataArray>::Take(
    lighting->GetOutput()->GetPointData()->GetArray("Colors")->NewInstance());
  before->DeepCopy(lighting->GetOutput()->GetPointData()->GetArray("Colors"));
  lighting->RemoveAllPointLights();
  EXPECT_EQ(Kinds(lighting), (std::array<int, 3>{ 3, 0, 2 }));
  lighting->Update();
  vtkNew<vtkCatadioptricLighting> others;
  others->AddSpotLight(0.2, -0.2, 1.3, 0.0, -0.4, 0.8, 30, 0.2, 0.2, 0.2);
  others->AddSpotLight(-0.2, -0.2, 1.3, 0.0, -0.4, 0.8, 45, 0.2, 0, 0);
  others->AddDirectionalLight(0, -1, 1, 0, 0, 0.2);
  others->AddLight(spot);
  others->AddLight(sun);
  ForEachLitPoint(
    others, [](const catar::Vec3&, const catar::Vec3&, const std::array<double, 3>&) {});
  vtkDataArray* after = lighting->GetOutput()->GetPointData()->GetArray("Colors");
  vtkDataArray* expected = others->GetOutput()->GetPointData()->GetArray("Colors");
  ASSERT_EQ(after->GetNumberOfTuples(), expected->GetNumberOfTuples());
  int changed = 0;
  for (vtkIdType i = 0; i < after->GetNumberOfTuples(); ++i)
  {
    EXPECT_EQ(ColorAt(after, i), ColorAt(expected, i)) << i;
    changed += ColorAt(after, i) != ColorAt(before, i);
  }
  EXPECT_GT(changed, 50); // the green point light was seen, and is gone

  lighting->RemoveAllSpotLights();
  EXPECT_EQ(Kinds(lighting), (std::array<int, 3>{ 0, 0, 2 }));
  lighting->AddPointLight(0.0, -0.4, 0.95, 0, 0.3, 0, 1, 0, 0);
  lighting->RemoveAllDirectionalLights();
  EXPECT_EQ(Kinds(lighting), (std::array<int, 3>{ 0, 1, 0 }));
  lighting->RemoveAllLights();
  EXPECT_EQ(Kinds(lighting), (std::array<int, 3>{ 0, 0, 0 }));
  EXPECT_EQ(errors->Count, 3);
}

TEST(vtkCatadioptricLighting, OutputRecordsTheLighting)
{
  // A box face colour per cell named Colors: the lit Colors replace them, so the output keeps
  // them as BaseColors and the record names that.
  vtkNew<vtkCatadioptricLighting> lighting;
  lighting->AddSpotLight(0.2, -0.2, 1.3, 0.0, -0.4, 0.8, 30, 1, 0.5, 0.25);
  lighting->AddPointLight(0.0, -0.4, 0.95, 0, 1, 0, 1, 2, 3);
  lighting->AddDirectionalLight(0, -1, 1, 0, 0, 1);
  vtkNew<vtkLight> off;
  off->SwitchOff();
  lighting->AddLight(off);
  lighting->SetShadingModeToFlat();
  lighting->ShadowsOff();
  lighting->TwoSidedLightingOff();
  lighting->SetGlobalAmbient(0.1, 0.2, 0.3);
  lighting->SetEmission(0.01, 0.02, 0.03);
  lighting->SetSpecular(0.4);
  lighting->SetSpecularPower(17);
  lighting->SetOpacity(0.75);
  lighting->GetProperty()->SetAmbientColor(0.9, 0.8, 0.7);
  vtkNew<vtkCatadioptricCamera> cam;
  catar_test::SetSmallDemoCamera(cam);
  auto plate = Plate(-0.15, 0.15, -0.55, -0.25, 0.80, 4);
  vtkNew<vtkUnsignedCharArray> faces;
  faces->SetName("Colors");
  faces->SetNumberOfComponents(3);
  for (vtkIdType c = 0; c < plate->GetNumberOfCells(); ++c)
  {
    faces->InsertNextTuple3(10 * c, 200, 100);
  }
  plate->GetCellData()->AddArray(faces);
  vtkNew<vtkCatadioptricProjection> proj;
  proj->SetCamera(cam);
  proj->SetInputData(plate);
  lighting->SetInputConnection(proj->GetOutputPort());
  lighting->Update();
  vtkPolyData* out = lighting->GetOutput();
  ASSERT_TRUE(vtkCatadioptricLighting::HasLightingRecord(out->GetFieldData()));
  vtkDataArray* kept = out->GetCellData()->GetArray("BaseColors");
  ASSERT_NE(kept, nullptr);
  EXPECT_EQ(ColorAt(kept, 3), (std::array<double, 3>{ 30, 200, 100 }));

  vtkNew<vtkCatadioptricLighting> copy;
  ASSERT_TRUE(copy->ReadFromFieldData(out->GetFieldData()));
  EXPECT_EQ(copy->GetShadingMode(), vtkCatadioptricLighting::FLAT);
  EXPECT_FALSE(copy->GetShadows());
  EXPECT_FALSE(copy->GetTwoSidedLighting());
  EXPECT_EQ(copy->GetGlobalAmbient()[2], 0.3);
  EXPECT_EQ(copy->GetEmission()[1], 0.02);
  EXPECT_STREQ(copy->GetInputColorArrayName(), "BaseColors");
  vtkProperty* p = copy->GetProperty();
  EXPECT_EQ(p->GetSpecular(), 0.4);
  EXPECT_EQ(p->GetSpecularPower(), 17);
  EXPECT_EQ(p->GetOpacity(), 0.75);
  EXPECT_EQ(p->GetAmbientColor()[1], 0.8);
  // The lights that are on, as the shading reads them, value for value.
  const auto a = vtkCatadioptricLightingSupport::ConvertLights(lighting->GetLights());
  const auto b = vtkCatadioptricLightingSupport::ConvertLights(copy->GetLights());
  ASSERT_EQ(a.size(), 3u);
  ASSERT_EQ(b.size(), 3u);
  for (std::size_t k = 0; k < a.size(); ++k)
  {
    EXPECT_EQ(a[k].kind, b[k].kind);
    EXPECT_EQ(a[k].position, b[k].position);
    EXPECT_EQ(a[k].focalPoint, b[k].focalPoint);
    EXPECT_EQ(a[k].diffuse, b[k].diffuse);
    EXPECT_EQ(a[k].specular, b[k].specular);
    EXPECT_EQ(a[k].ambient, b[k].ambient);
    EXPECT_EQ(a[k].coneAngle, b[k].coneAngle);
    EXPECT_EQ(a[k].attenuation, b[k].attenuation);
  }

  // No base colour array: the record names none (the lit Colors are no base colours).
  lighting->SetInputColorArrayName("NoSuchArray");
  lighting->Update();
  ASSERT_TRUE(copy->ReadFromFieldData(lighting->GetOutput()->GetFieldData()));
  EXPECT_STREQ(copy->GetInputColorArrayName(), "");
  // A malformed record reads as none, and leaves the filter as it was.
  vtkNew<vtkFieldData> bad;
  bad->DeepCopy(out->GetFieldData());
  vtkNew<vtkDoubleArray> wrong;
  wrong->SetName("LightingSettings");
  wrong->SetNumberOfComponents(3);
  wrong->InsertNextTuple3(1, 1, 1);
  bad->AddArray(wrong);
  EXPECT_TRUE(vtkCatadioptricLighting::HasLightingRecord(bad));
  EXPECT_FALSE(copy->ReadFromFieldData(bad));
  EXPECT_EQ(copy->GetShadingMode(), vtkCatadioptricLighting::FLAT);
  EXPECT_FALSE(vtkCatadioptricLighting::HasLightingRecord(plate->GetFieldData()));
}

namespace
{
// A 4 cm sphere (24 x 12) in front of the small demo camera's mirror, with its normals: a mesh
// of its own (a deep copy), to be changed by the test.
vtkSmartPointer<vtkPolyData> SmallLitSphere()
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0.05, -0.3, 0.95);
  sphere->SetRadius(0.04);
  sphere->SetThetaResolution(24);
  sphere->SetPhiResolution(12);
  sphere->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(sphere->GetOutput());
  return mesh;
}

// The lighting of the projection's output: a spotlight on that sphere, specular 0.4, no shadows.
void SpotOnSmallSphere(vtkCatadioptricProjection* proj, vtkCatadioptricLighting* lighting)
{
  lighting->SetInputConnection(proj->GetOutputPort());
  lighting->AddSpotLight(0.2, -0.2, 1.3, 0.05, -0.3, 0.95, 40, 1, 0.9, 0.8);
  lighting->SetSpecular(0.4);
  lighting->ShadowsOff();
}
} // namespace

// Gouraud shading of cell colours: they are averaged at the points once and kept while the
// colours and the polygons are unchanged. Every frame's colours are those of the same mesh given
// the averages as point colours (what the filter computed anew every frame before): after the
// camera is marked modified (the averages kept), and after the cell colours change (averaged
// again).
TEST(vtkCatadioptricLighting, CellColoursAveragedAtPointsOnceAndAgainWhenTheyChange)
{
  vtkNew<vtkCatadioptricCamera> cam;
  catar_test::SetSmallDemoCamera(cam);
  vtkSmartPointer<vtkPolyData> mesh = SmallLitSphere();
  const vtkIdType nCells = mesh->GetNumberOfCells();
  vtkNew<vtkUnsignedCharArray> cellColors;
  cellColors->SetName("Colors");
  cellColors->SetNumberOfComponents(4);
  cellColors->SetNumberOfTuples(nCells);
  auto paint = [&](int seed) {
    for (vtkIdType c = 0; c < nCells; ++c)
    {
      for (int k = 0; k < 4; ++k)
      {
        cellColors->SetComponent(c, k, k == 3 ? 255 : (37 * c + 91 * k + seed) % 256);
      }
    }
    cellColors->Modified();
  };
  paint(0);
  mesh->GetCellData()->AddArray(cellColors);

  // The same mesh with the cell colours averaged at its points as float point colours.
  vtkNew<vtkPolyData> averaged;
  averaged->CopyStructure(mesh);
  averaged->GetPointData()->SetNormals(mesh->GetPointData()->GetNormals());
  vtkNew<vtkFloatArray> pointColors;
  pointColors->SetName("Colors");
  pointColors->SetNumberOfComponents(4);
  pointColors->SetNumberOfTuples(mesh->GetNumberOfPoints());
  averaged->GetPointData()->AddArray(pointColors);
  auto average = [&]() {
    const float none[4] = { 0, 0, 0, 0 };
    const vtkCatadioptricColorArray base(mesh, "Colors", none);
    vtkNew<vtkIdList> ids;
    const std::vector<float> mean = catar::AverageAtPoints<float>(
      static_cast<std::size_t>(mesh->GetNumberOfPoints()), static_cast<std::size_t>(nCells), 4,
      [&](std::size_t c, auto&& visit) {
        mesh->GetPolys()->GetCellAtId(static_cast<vtkIdType>(c), ids);
        for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
        {
          visit(static_cast<std::size_t>(ids->GetId(k)));
        }
      },
      [&](std::size_t c, float* v) { base.Get(0, static_cast<vtkIdType>(c), v); });
    std::copy(mean.begin(), mean.end(), pointColors->GetPointer(0));
    pointColors->Modified();
  };
  average();

  auto pipeline = [&](vtkPolyData* input, vtkCatadioptricProjection* proj,
                    vtkCatadioptricLighting* lighting) {
    proj->SetCamera(cam);
    proj->SetInputData(input);
    SpotOnSmallSphere(proj, lighting);
  };
  vtkNew<vtkCatadioptricProjection> proj, refProj;
  vtkNew<vtkCatadioptricLighting> lighting, reference;
  pipeline(mesh, proj, lighting);
  pipeline(averaged, refProj, reference);
  auto same = [&](const char* when) {
    lighting->Update();
    reference->Update();
    vtkDataArray* got = lighting->GetOutput()->GetPointData()->GetArray("Colors");
    vtkDataArray* want = reference->GetOutput()->GetPointData()->GetArray("Colors");
    ASSERT_NE(got, nullptr) << when;
    ASSERT_NE(want, nullptr) << when;
    ASSERT_EQ(got->GetNumberOfTuples(), want->GetNumberOfTuples()) << when;
    vtkIdType differ = 0, lit = 0;
    for (vtkIdType i = 0; i < got->GetNumberOfTuples(); ++i)
    {
      for (int k = 0; k < 4; ++k)
      {
        differ += got->GetComponent(i, k) != want->GetComponent(i, k);
      }
      lit += want->GetComponent(i, 3) > 0;
    }
    EXPECT_EQ(differ, 0) << when;
    EXPECT_GT(lit, 50) << when;
  };
  same("first frame");
  std::vector<unsigned char> first(4 * mesh->GetNumberOfPoints());
  {
    auto* c =
      vtkUnsignedCharArray::SafeDownCast(lighting->GetOutput()->GetPointData()->GetArray("Colors"));
    ASSERT_NE(c, nullptr);
    std::copy(c->GetPointer(0), c->GetPointer(0) + first.size(), first.begin());
  }
  cam->Modified(); // a new frame, the colours unchanged
  same("camera marked modified");
  auto* again =
    vtkUnsignedCharArray::SafeDownCast(lighting->GetOutput()->GetPointData()->GetArray("Colors"));
  ASSERT_NE(again, nullptr);
  EXPECT_TRUE(std::equal(first.begin(), first.end(), again->GetPointer(0)));
  paint(40); // other cell colours: averaged again
  average();
  same("cell colours changed");
  auto* changed =
    vtkUnsignedCharArray::SafeDownCast(lighting->GetOutput()->GetPointData()->GetArray("Colors"));
  EXPECT_FALSE(std::equal(first.begin(), first.end(), changed->GetPointer(0)));
}

TEST(vtkCatadioptricLighting, GivenNormalsMadeUnitOnceAndAgainWhenTheyChange)
{
  // Given normals are made unit length once and kept while their array is unchanged: a filter
  // that runs frame after frame gives a fresh filter's colours, before and after the normals
  // change (scaled, then turned), and the change shows.
  vtkNew<vtkCatadioptricCamera> cam;
  catar_test::SetSmallDemoCamera(cam);
  vtkSmartPointer<vtkPolyData> mesh = SmallLitSphere();
  auto* normals = vtkFloatArray::SafeDownCast(mesh->GetPointData()->GetNormals());
  ASSERT_NE(normals, nullptr);
  auto colours = [&](vtkCatadioptricLighting* lighting) {
    lighting->Update();
    auto* c =
      vtkUnsignedCharArray::SafeDownCast(lighting->GetOutput()->GetPointData()->GetArray("Colors"));
    EXPECT_NE(c, nullptr);
    return c
      ? std::vector<unsigned char>(c->GetPointer(0), c->GetPointer(0) + 4 * c->GetNumberOfTuples())
      : std::vector<unsigned char>();
  };
  auto setUp = [&](vtkCatadioptricProjection* proj, vtkCatadioptricLighting* lighting) {
    proj->SetCamera(cam);
    proj->SetInputData(mesh);
    SpotOnSmallSphere(proj, lighting);
  };
  vtkNew<vtkCatadioptricProjection> proj;
  vtkNew<vtkCatadioptricLighting> lighting;
  setUp(proj, lighting);
  auto fresh = [&]() {
    vtkNew<vtkCatadioptricProjection> p;
    vtkNew<vtkCatadioptricLighting> l;
    setUp(p, l);
    return colours(l);
  };
  const std::vector<unsigned char> first = colours(lighting);
  EXPECT_EQ(first, fresh());
  // Scaled by 3: the same unit normals, the same colours.
  for (vtkIdType i = 0; i < 3 * normals->GetNumberOfTuples(); ++i)
  {
    normals->SetValue(i, 3.0f * normals->GetValue(i));
  }
  normals->Modified();
  EXPECT_EQ(colours(lighting), first);
  // Turned a quarter turn about z: other colours, as a fresh filter gives them.
  for (vtkIdType i = 0; i < normals->GetNumberOfTuples(); ++i)
  {
    const float x = normals->GetComponent(i, 0), y = normals->GetComponent(i, 1);
    normals->SetComponent(i, 0, -y);
    normals->SetComponent(i, 1, x);
  }
  normals->Modified();
  const std::vector<unsigned char> turned = colours(lighting);
  EXPECT_EQ(turned, fresh());
  EXPECT_NE(turned, first);
}
