// vtkCatadioptricOccluders: one shadow structure shared by the lighting filters of a scene gives
// the very colours that every filter's own occluder inputs give (a box over a plate: the box
// shadows the plate and itself), is built once for all the filters, and is rebuilt when a mesh
// moves (the shadow on the plate moves with the box, though the plate's own input did not change).
#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricLighting.h"
#include "vtkCatadioptricOccluders.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCellData.h"
#include "vtkLight.h"
#include "vtkNew.h"
#include "vtkPlaneSource.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkProperty.h"
#include "vtkSmartPointer.h"
#include "vtkTessellatedBoxSource.h"
#include "vtkTriangleFilter.h"
#include "vtkUnsignedCharArray.h"

#include "TestUtilities.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <vector>

namespace
{
void SharedShadowsCamera(vtkCatadioptricCamera* cam)
{
  cam->SetImageWidth(640);
  cam->SetImageHeight(480);
  cam->SetFocalLength(480, 480);
  cam->SetPrincipalPoint(319.5, 239.5);
  cam->SetMirrorParameter("center", { 0, 0, 0.14 });
  cam->SetMirrorParameter("radius", 0.05);
  const double pose[16] = { 1, 0, 0, 0, 0, 0, -1, 1.0, 0, 1, 0, 0.14, 0, 0, 0, 1 };
  cam->SetWorldToCameraElements(pose);
}

vtkSmartPointer<vtkPolyData> Triangulated(vtkAlgorithm* source)
{
  vtkNew<vtkTriangleFilter> tri;
  tri->SetInputConnection(source->GetOutputPort());
  tri->Update();
  auto mesh = vtkSmartPointer<vtkPolyData>::New();
  mesh->DeepCopy(tri->GetOutput());
  return mesh;
}

// A 30 x 30 cm plate at z = 0.80 (5 mm vertex spacing) and an 8 x 8 x 4 cm box over it.
constexpr double kPlateZ = 0.80;

vtkSmartPointer<vtkPolyData> Plate()
{
  vtkNew<vtkPlaneSource> plane;
  plane->SetOrigin(-0.15, -0.55, kPlateZ);
  plane->SetPoint1(0.15, -0.55, kPlateZ);
  plane->SetPoint2(-0.15, -0.25, kPlateZ);
  plane->SetResolution(60, 60);
  return Triangulated(plane);
}

vtkSmartPointer<vtkPolyData> Box()
{
  vtkNew<vtkTessellatedBoxSource> box;
  box->SetBounds(-0.04, 0.04, -0.44, -0.36, 0.88, 0.92);
  box->SetLevel(3);
  box->QuadsOff();
  return Triangulated(box);
}

// Moves every point of `mesh` by dx along x, in place.
void MoveX(vtkPolyData* mesh, double dx)
{
  vtkPoints* pts = mesh->GetPoints();
  for (vtkIdType i = 0; i < pts->GetNumberOfPoints(); ++i)
  {
    double p[3];
    pts->GetPoint(i, p);
    p[0] += dx;
    pts->SetPoint(i, p);
  }
  pts->Modified();
}

// One object's per-frame filters: projection and lighting (a spotlight over the box and a dim
// directional fill light, both casting shadows).
struct ObjectPipeline
{
  vtkNew<vtkCatadioptricProjection> Projection;
  vtkNew<vtkCatadioptricLighting> Lighting;

  ObjectPipeline(vtkPolyData* mesh, vtkCatadioptricCamera* cam)
  {
    this->Projection->SetCamera(cam);
    this->Projection->SetInputData(mesh);
    this->Lighting->SetInputConnection(this->Projection->GetOutputPort());
    vtkNew<vtkLight> spot;
    spot->SetPositional(true);
    spot->SetPosition(0.02, -0.41, 1.10);
    spot->SetFocalPoint(0.0, -0.4, kPlateZ);
    spot->SetConeAngle(80);
    spot->SetAmbientColor(0, 0, 0);
    this->Lighting->AddLight(spot);
    vtkNew<vtkLight> fill;
    fill->SetPositional(false);
    fill->SetPosition(-0.3, 0.2, 1.5);
    fill->SetFocalPoint(0.0, -0.4, kPlateZ);
    fill->SetDiffuseColor(0.1, 0.1, 0.12);
    fill->SetSpecularColor(0.1, 0.1, 0.12);
    fill->SetAmbientColor(0, 0, 0);
    this->Lighting->AddLight(fill);
    this->Lighting->GetProperty()->SetSpecular(0.4);
  }

  // The lighting's colour bytes (point or cell data, as the shading mode writes them).
  std::vector<unsigned char> Colors()
  {
    this->Lighting->Update();
    vtkPolyData* out = this->Lighting->GetOutput();
    vtkDataArray* colors = out->GetPointData()->GetArray("Colors");
    if (!colors)
    {
      colors = out->GetCellData()->GetArray("Colors");
    }
    auto* bytes = vtkUnsignedCharArray::SafeDownCast(colors);
    EXPECT_NE(bytes, nullptr);
    if (!bytes)
    {
      return {};
    }
    return std::vector<unsigned char>(
      bytes->GetPointer(0), bytes->GetPointer(0) + bytes->GetNumberOfValues());
  }
};

// The plate's points in the spotlight's shadow: visible, and at least 60 levels of green darker
// than with shadows off (the fill light adds at most 36: 255 x (0.1 diffuse + 0.4 x 0.1 specular)).
// Their number, and their mean x.
int ShadowedPoints(ObjectPipeline& plate, double* meanX)
{
  vtkCatadioptricLighting* lighting = plate.Lighting;
  const bool shadows = lighting->GetShadows();
  lighting->ShadowsOff();
  const std::vector<unsigned char> off = plate.Colors();
  lighting->ShadowsOn();
  const std::vector<unsigned char> on = plate.Colors();
  lighting->SetShadows(shadows);
  vtkPolyData* out = lighting->GetOutput();
  vtkDataArray* visible = out->GetPointData()->GetArray("Visible");
  int n = 0;
  double sum = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints() && on.size() == off.size(); ++i)
  {
    if (visible->GetComponent(i, 0) != 0 && off[4 * i + 1] - on[4 * i + 1] >= 60)
    {
      double x[3];
      out->GetPoint(i, x);
      sum += x[0];
      ++n;
    }
  }
  *meanX = n > 0 ? sum / n : std::numeric_limits<double>::quiet_NaN();
  return n;
}
} // namespace

TEST(vtkCatadioptricOccluders, SharedStructureGivesTheColoursOfOccluderInputs)
{
  vtkNew<vtkCatadioptricCamera> cam;
  SharedShadowsCamera(cam);
  vtkSmartPointer<vtkPolyData> plate = Plate();
  vtkSmartPointer<vtkPolyData> box = Box();

  // Each filter with the other object on its occluder port (the mesh itself is always traced).
  ObjectPipeline plateOwn(plate, cam), boxOwn(box, cam);
  plateOwn.Lighting->AddOccluderData(box);
  boxOwn.Lighting->AddOccluderData(plate);
  // Both filters sharing one structure of both meshes.
  vtkNew<vtkCatadioptricOccluders> occluders;
  occluders->AddMesh(plate);
  occluders->AddMesh(box);
  occluders->AddMesh(nullptr); // ignored
  EXPECT_EQ(occluders->GetNumberOfMeshes(), 2);
  EXPECT_EQ(occluders->GetMesh(1), box.Get());
  EXPECT_EQ(occluders->GetMesh(2), nullptr);
  ObjectPipeline plateShared(plate, cam), boxShared(box, cam);
  plateShared.Lighting->SetOccluders(occluders);
  boxShared.Lighting->SetOccluders(occluders);
  EXPECT_EQ(plateShared.Lighting->GetOccluders(), occluders.Get());

  for (int mode : { vtkCatadioptricLighting::GOURAUD, vtkCatadioptricLighting::FLAT })
  {
    for (ObjectPipeline* p : { &plateOwn, &boxOwn, &plateShared, &boxShared })
    {
      p->Lighting->SetShadingMode(mode);
    }
    EXPECT_EQ(plateShared.Colors(), plateOwn.Colors()) << "mode " << mode;
    EXPECT_EQ(boxShared.Colors(), boxOwn.Colors()) << "mode " << mode;
  }
  // Built once for both filters and both modes.
  EXPECT_EQ(occluders->GetNumberOfBuilds(), 1);
  EXPECT_EQ(occluders->GetNumberOfTriangles(), plate->GetNumberOfPolys() + box->GetNumberOfPolys());

  // The shadow is there: part of the plate is darker with shadows on.
  plateShared.Lighting->SetShadingModeToGouraud();
  plateOwn.Lighting->SetShadingModeToGouraud();
  double meanX = 0;
  EXPECT_GT(ShadowedPoints(plateShared, &meanX), 50);

  // A new frame (the camera moved): projection and lighting run again, nothing is rebuilt and the
  // meshes are not modified (the occluders object is not either).
  const vtkMTimeType occludersTime = occluders->GetMTime();
  cam->Modified();
  EXPECT_EQ(plateShared.Colors(), plateOwn.Colors());
  EXPECT_EQ(boxShared.Colors(), boxOwn.Colors());
  EXPECT_EQ(occluders->GetNumberOfBuilds(), 1);
  EXPECT_EQ(occluders->GetMTime(), occludersTime);
}

TEST(vtkCatadioptricOccluders, RebuiltWhenAMeshMoves)
{
  vtkNew<vtkCatadioptricCamera> cam;
  SharedShadowsCamera(cam);
  vtkSmartPointer<vtkPolyData> plate = Plate();
  vtkSmartPointer<vtkPolyData> box = Box();
  vtkNew<vtkCatadioptricOccluders> occluders;
  occluders->AddMesh(plate);
  occluders->AddMesh(box);
  ObjectPipeline plateShared(plate, cam), boxShared(box, cam);
  plateShared.Lighting->SetOccluders(occluders);
  boxShared.Lighting->SetOccluders(occluders);
  ObjectPipeline plateOwn(plate, cam);
  plateOwn.Lighting->AddOccluderData(box);
  vtkNew<vtkPoints> original;
  original->DeepCopy(box->GetPoints());

  double before = 0, after = 0;
  const int n0 = ShadowedPoints(plateShared, &before);
  boxShared.Lighting->Update();
  EXPECT_EQ(occluders->GetNumberOfBuilds(), 1);
  EXPECT_GT(n0, 50);

  // The box moves 5 cm along +x (its points changed in place) and only the plate's lighting is
  // updated: its own input is the same, yet it runs again and rebuilds the structure.
  MoveX(box, 0.05);
  plateShared.Lighting->Update();
  EXPECT_EQ(occluders->GetNumberOfBuilds(), 2);
  // The box's filter then finds it built.
  boxShared.Lighting->Update();
  EXPECT_EQ(occluders->GetNumberOfBuilds(), 2);
  // The shadow moved with the box: the spotlight is 18 to 22 cm above the box's faces and 30 cm
  // above the plate, so the umbra moves 1.36 to 1.67 times as far.
  const int n1 = ShadowedPoints(plateShared, &after);
  EXPECT_GT(n1, 50);
  EXPECT_GT(after - before, 0.05 * 1.3);
  EXPECT_LT(after - before, 0.05 * 1.7);
  // The same colours as a filter with the box on its occluder port.
  EXPECT_EQ(plateShared.Colors(), plateOwn.Colors());
  EXPECT_EQ(occluders->GetNumberOfBuilds(), 2);

  // The box's points object replaced by its first coordinates (an object older than the last
  // build): rebuilt, and the shadow is back where it was.
  box->SetPoints(original);
  double back = 0;
  EXPECT_EQ(ShadowedPoints(plateShared, &back), n0);
  EXPECT_EQ(occluders->GetNumberOfBuilds(), 3);
  EXPECT_EQ(back, before);
  EXPECT_EQ(plateShared.Colors(), plateOwn.Colors());
}

TEST(vtkCatadioptricOccluders, BadInputIsAnError)
{
  vtkNew<vtkCatadioptricCamera> cam;
  SharedShadowsCamera(cam);
  vtkSmartPointer<vtkPolyData> plate = Plate();
  vtkSmartPointer<vtkPolyData> box = Box();
  vtkNew<vtkCatadioptricOccluders> occluders;
  occluders->AddMesh(plate);
  occluders->AddMesh(box);

  // Occluders on port 1 and shared ones: ambiguous.
  ObjectPipeline both(plate, cam);
  both.Lighting->SetOccluders(occluders);
  both.Lighting->AddOccluderData(box);
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(both.Lighting);
  both.Lighting->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Last.find("SetOccluders"), std::string::npos) << errors->Last;

  // A mesh whose coordinates are not finite: the structure cannot be built.
  vtkSmartPointer<vtkPolyData> broken = Box();
  broken->GetPoints()->SetPoint(0, std::numeric_limits<double>::quiet_NaN(), 0, 0);
  vtkNew<vtkCatadioptricOccluders> bad;
  bad->AddMesh(broken);
  vtkNew<catar_test::ErrorCounter> badErrors;
  badErrors->Watch(bad);
  EXPECT_FALSE(bad->Update());
  EXPECT_EQ(badErrors->Count, 1);
  EXPECT_EQ(bad->GetNumberOfTriangles(), 0);
  EXPECT_EQ(bad->GetNumberOfBuilds(), 0);
  ObjectPipeline lit(plate, cam);
  lit.Lighting->SetOccluders(bad);
  vtkNew<catar_test::ErrorCounter> litErrors;
  litErrors->Watch(lit.Lighting);
  lit.Lighting->Update();
  EXPECT_EQ(litErrors->Count, 1);

  // Removing the meshes leaves an empty structure: nothing casts shadows.
  bad->RemoveAllMeshes();
  EXPECT_TRUE(bad->Update());
  EXPECT_EQ(bad->GetNumberOfTriangles(), 0);
}
