// vtkCatadioptricCamera, vtkCatadioptricProjection and vtkCatadioptricPainterSort.
#include "CalibrationIO.h"
#include "CameraModel.h"
#include "Projector.h"

#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricPainterSort.h"
#include "vtkCatadioptricProjection.h"
#include "vtkCellArray.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkIdTypeArray.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSphereSource.h"
#include "vtkStringArray.h"
#include "vtkUnsignedCharArray.h"

#include "TestCameras.h"
#include "TestUtilities.h"

#include <Eigen/Geometry> // cross products
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <numeric>
#include <random>
#include <set>
#include <vector>

namespace
{
// Camera of the demo: at world (0, -0.14, 1) looking along +y at a 5 cm mirror.
vtkSmartPointer<vtkPolyData> SphereAt(double x, double y, double z, double r)
{
  vtkNew<vtkSphereSource> s;
  s->SetCenter(x, y, z);
  s->SetRadius(r);
  s->SetThetaResolution(24);
  s->SetPhiResolution(12);
  s->Update();
  return s->GetOutput();
}
} // namespace

TEST(vtkCatadioptricCamera, FieldDataAndFileRoundTrip)
{
  vtkNew<vtkCatadioptricCamera> cam;
  catar_test::SetSmallDemoCamera(cam);
  cam->SetDistortion(-0.1, 0.01, 0.001, 0.002, 0.0);
  ASSERT_TRUE(cam->IsValid()) << cam->GetLastError();
  vtkNew<vtkFieldData> fd;
  cam->WriteToFieldData(fd);
  vtkNew<vtkCatadioptricCamera> back;
  ASSERT_TRUE(back->ReadFromFieldData(fd)) << back->GetLastError();
  EXPECT_EQ(back->GetImageWidth(), 640);
  EXPECT_DOUBLE_EQ(back->GetDistortion()[3], 0.002);
  EXPECT_DOUBLE_EQ(back->GetWorldToCamera()->GetElement(2, 3), 0.14);

  const std::string path = ::testing::TempDir() + "/catar_vtkcamera.json";
  ASSERT_TRUE(cam->Save(path.c_str())) << cam->GetLastError();
  vtkNew<vtkCatadioptricCamera> loaded;
  ASSERT_TRUE(loaded->Load(path.c_str())) << loaded->GetLastError();
  EXPECT_DOUBLE_EQ(loaded->GetFocalLength()[0], 480);
  double pos[3];
  loaded->GetCameraPosition(pos);
  EXPECT_NEAR(pos[1], -0.14, 1e-15);
  EXPECT_NEAR(pos[2], 1.0, 1e-15);
  std::remove(path.c_str());

  // A failed load keeps the camera and says why.
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(loaded);
  EXPECT_FALSE(loaded->Load("/nonexistent.yaml"));
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(std::string(loaded->GetLastError()).find("nonexistent"), std::string::npos);
  EXPECT_DOUBLE_EQ(loaded->GetFocalLength()[0], 480);
  // Empty field data has no camera.
  vtkNew<vtkFieldData> empty;
  EXPECT_FALSE(back->ReadFromFieldData(empty));
}

TEST(vtkCatadioptricCamera, LensModelsTravelThroughFieldDataAndFiles)
{
  vtkNew<vtkCatadioptricCamera> cam;
  catar_test::SetSmallDemoCamera(cam);
  EXPECT_STREQ(cam->GetLens(), "pinhole");
  const std::vector<double> rational = { 0.25, 0.11, 0.001, -0.0007, 0.009, 0.61, 0.18, 0.012,
    0.001, -0.0005, 0.0008, 0.0002, 0.01, -0.02 };
  ASSERT_TRUE(cam->SetLens("pinhole", rational)) << cam->GetLastError();
  EXPECT_EQ(cam->GetDistortionCoefficients(), rational);
  EXPECT_DOUBLE_EQ(cam->GetDistortion()[4], 0.009);
  vtkNew<vtkFieldData> fd;
  cam->WriteToFieldData(fd);
  vtkNew<vtkCatadioptricCamera> back;
  ASSERT_TRUE(back->ReadFromFieldData(fd)) << back->GetLastError();
  EXPECT_EQ(back->GetDistortionCoefficients(), rational);
  EXPECT_TRUE(back->GetModel().SameLens(cam->GetModel()));

  const std::vector<double> fisheye = { 0.01, -0.002, 0.0003, -0.00002 };
  ASSERT_TRUE(cam->SetLens("fisheye", fisheye)) << cam->GetLastError();
  cam->WriteToFieldData(fd);
  ASSERT_TRUE(back->ReadFromFieldData(fd)) << back->GetLastError();
  EXPECT_STREQ(back->GetLens(), "fisheye");
  EXPECT_EQ(back->GetDistortionCoefficients(), fisheye);
  const std::string path = ::testing::TempDir() + "/catar_vtkcamera_fisheye.yaml";
  ASSERT_TRUE(cam->Save(path.c_str())) << cam->GetLastError();
  vtkNew<vtkCatadioptricCamera> loaded;
  ASSERT_TRUE(loaded->Load(path.c_str())) << loaded->GetLastError();
  EXPECT_STREQ(loaded->GetLens(), "fisheye");
  EXPECT_EQ(loaded->GetDistortionCoefficients(), fisheye);
  std::remove(path.c_str());

  // Field data written before the lens models (five numbers, no CameraLens) is a pinhole's.
  fd->RemoveArray("CameraLens");
  vtkNew<vtkDoubleArray> five;
  five->SetName("CameraDistortion");
  for (const double k : { -0.1, 0.01, 0.0, 0.0, 0.001 })
  {
    five->InsertNextValue(k);
  }
  fd->AddArray(five);
  ASSERT_TRUE(back->ReadFromFieldData(fd)) << back->GetLastError();
  EXPECT_STREQ(back->GetLens(), "pinhole");
  EXPECT_EQ(back->GetDistortionCoefficients(), (std::vector<double>{ -0.1, 0.01, 0, 0, 0.001 }));

  // Wrong models and counts change nothing.
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(cam);
  EXPECT_FALSE(cam->SetLens("telephoto", { 0.0, 0.0, 0.0, 0.0 }));
  EXPECT_FALSE(cam->SetLens("fisheye", { 0.0, 0.0, 0.0, 0.0, 0.0 }));
  EXPECT_FALSE(cam->SetLens("pinhole", { 0.0, 0.0, 0.0 }));
  EXPECT_EQ(errors->Count, 3);
  EXPECT_STREQ(cam->GetLens(), "fisheye");
  EXPECT_EQ(cam->GetDistortionCoefficients(), fisheye);
}

TEST(vtkCatadioptricCamera, MirrorByTypeAndKey)
{
  vtkNew<vtkCatadioptricCamera> cam;
  // The default is the demo rig's mirror, the first type.
  EXPECT_EQ(std::string(cam->GetMirrorType()), vtkCatadioptricCamera::GetMirrorTypes().front());
  const std::vector<std::string> types = vtkCatadioptricCamera::GetMirrorTypes();
  EXPECT_EQ(std::set<std::string>(types.begin(), types.end()).size(), types.size()); // once each
  const std::vector<std::string> keys = vtkCatadioptricCamera::GetMirrorParameterKeys("sphere");
  ASSERT_EQ(keys, (std::vector<std::string>{ "center", "radius" }));
  EXPECT_EQ(cam->GetMirrorParameters(), (std::vector<double>{ 0.0, 0.0, 0.14, 0.05 }));

  const vtkMTimeType before = cam->GetMTime();
  ASSERT_TRUE(cam->SetMirrorParameter("center", { 0.01, 0.0, 0.2 }));
  ASSERT_TRUE(cam->SetMirrorParameter("radius", 0.06));
  EXPECT_GT(cam->GetMTime(), before);
  EXPECT_EQ(cam->GetMirrorParameter("radius"), std::vector<double>{ 0.06 });
  EXPECT_EQ(cam->GetMirrorParameters(), (std::vector<double>{ 0.01, 0.0, 0.2, 0.06 }));

  // Wrong keys, counts and types are errors that change nothing.
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(cam);
  const vtkMTimeType unchanged = cam->GetMTime();
  EXPECT_FALSE(cam->SetMirrorParameter("centre", { 0.0, 0.0, 0.2 }));
  EXPECT_FALSE(cam->SetMirrorParameter("center", { 0.0, 0.2 }));
  EXPECT_FALSE(cam->SetMirrorParameters({ 1.0, 2.0 }));
  EXPECT_FALSE(cam->SetMirrorType("blob"));
  EXPECT_FALSE(cam->SetMirrorType(nullptr));
  EXPECT_EQ(errors->Count, 5);
  EXPECT_NE(std::string(cam->GetLastError()).find("unknown mirror type"), std::string::npos);
  EXPECT_EQ(cam->GetMTime(), unchanged);
  EXPECT_TRUE(cam->GetMirrorParameter("no such key").empty());
  EXPECT_EQ(cam->GetMirrorParameters(), (std::vector<double>{ 0.01, 0.0, 0.2, 0.06 }));

  // The model, the field data and a calibration file carry the type and the numbers.
  EXPECT_EQ(cam->GetModel().mirror, catar::MirrorDescription("sphere", { 0.01, 0.0, 0.2, 0.06 }));
  vtkNew<vtkFieldData> fd;
  cam->WriteToFieldData(fd);
  vtkNew<vtkCatadioptricCamera> back;
  ASSERT_TRUE(back->ReadFromFieldData(fd)) << back->GetLastError();
  EXPECT_EQ(std::string(back->GetMirrorType()), "sphere");
  EXPECT_EQ(back->GetMirrorParameters(), cam->GetMirrorParameters());
  // Field data naming an unknown type, or the wrong count of numbers, holds no camera.
  vtkStringArray::SafeDownCast(fd->GetAbstractArray("MirrorType"))->SetValue(0, "blob");
  EXPECT_FALSE(back->ReadFromFieldData(fd));
  cam->WriteToFieldData(fd);
  vtkDataArray::SafeDownCast(fd->GetAbstractArray("MirrorParameters"))->SetNumberOfTuples(3);
  EXPECT_FALSE(back->ReadFromFieldData(fd));
}

// The mirror override (ParaView's Mirror Type and Mirror Parameters): the projection of a camera
// whose mirror is replaced is the projection with that mirror; wrong numbers are an error; an
// empty type gives the camera's own mirror back.
TEST(vtkCatadioptricProjection, MirrorOverride)
{
  vtkNew<vtkSphereSource> sphere;
  sphere->SetCenter(0.06, -0.32, 0.92);
  sphere->SetRadius(0.03);
  auto sphereCamera = catar_test::DemoCamera();
  vtkNew<vtkCatadioptricCamera> hyperboloid;
  hyperboloid->SetModel(catar_test::TiltedHyperboloidCameraModel());
  const catar::MirrorDescription mirror = catar_test::TiltedHyperboloidCameraModel().mirror;

  vtkNew<vtkCatadioptricProjection> direct;
  direct->SetInputConnection(sphere->GetOutputPort());
  direct->SetCamera(hyperboloid);
  direct->Update();
  vtkNew<vtkCatadioptricProjection> overridden;
  overridden->SetInputConnection(sphere->GetOutputPort());
  overridden->SetCamera(sphereCamera);
  overridden->SetMirrorType(mirror.type.c_str());
  overridden->SetNumberOfMirrorParameters(static_cast<int>(mirror.parameters.size()));
  for (std::size_t i = 0; i < mirror.parameters.size(); ++i)
  {
    overridden->SetMirrorParameter(static_cast<int>(i), mirror.parameters[i]);
  }
  overridden->Update();
  vtkDataArray* a = direct->GetOutput()->GetPointData()->GetArray("ImageCoordinates");
  vtkDataArray* b = overridden->GetOutput()->GetPointData()->GetArray("ImageCoordinates");
  ASSERT_TRUE(a && b);
  ASSERT_EQ(a->GetNumberOfTuples(), b->GetNumberOfTuples());
  for (vtkIdType i = 0; i < a->GetNumberOfTuples(); ++i)
  {
    EXPECT_EQ(a->GetComponent(i, 0), b->GetComponent(i, 0)) << i;
    EXPECT_EQ(a->GetComponent(i, 1), b->GetComponent(i, 1)) << i;
  }
  // The output's camera is the hyperboloid's.
  vtkNew<vtkCatadioptricCamera> fromField;
  ASSERT_TRUE(fromField->ReadFromFieldData(overridden->GetOutput()->GetFieldData()));
  EXPECT_EQ(fromField->GetModel().mirror, mirror);

  // One number short: an error, no output.
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(overridden);
  overridden->SetNumberOfMirrorParameters(static_cast<int>(mirror.parameters.size()) - 1);
  overridden->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Last.find("takes 20 numbers"), std::string::npos) << errors->Last;
  // No type: the camera's own sphere again.
  overridden->SetMirrorType("");
  overridden->Update();
  vtkNew<vtkCatadioptricProjection> plain;
  plain->SetInputConnection(sphere->GetOutputPort());
  plain->SetCamera(sphereCamera);
  plain->Update();
  EXPECT_EQ(plain->GetOutput()->GetPointData()->GetArray("ImageCoordinates")->GetComponent(5, 0),
    overridden->GetOutput()->GetPointData()->GetArray("ImageCoordinates")->GetComponent(5, 0));
}

TEST(vtkCatadioptricProjection, ArraysMatchTheCoreProjection)
{
  vtkNew<vtkCatadioptricCamera> cam;
  catar_test::SetSmallDemoCamera(cam);
  vtkNew<vtkCatadioptricProjection> proj;
  proj->SetCamera(cam);
  proj->SetInputData(SphereAt(0.1, -0.35, 0.9, 0.04));
  proj->Update();
  vtkPolyData* out = proj->GetOutput();
  vtkDataArray* px = out->GetPointData()->GetArray("ImageCoordinates");
  vtkDataArray* mp = out->GetPointData()->GetArray("MirrorPoint");
  vtkDataArray* pl = out->GetPointData()->GetArray("PathLength");
  vtkDataArray* st = out->GetPointData()->GetArray("ProjectionStatus");
  vtkDataArray* vis = out->GetPointData()->GetArray("Visible");
  vtkDataArray* depth = out->GetCellData()->GetArray("CentroidDepth");
  vtkDataArray* cvis = out->GetCellData()->GetArray("Visible");
  ASSERT_TRUE(px && mp && pl && st && vis && depth && cvis);
  ASSERT_EQ(px->GetNumberOfComponents(), 2);
  ASSERT_EQ(mp->GetNumberOfComponents(), 3);
  // Points stay in world coordinates; the camera travels in field data.
  EXPECT_EQ(out->GetPoints(),
    proj->GetInput() ? vtkPolyData::SafeDownCast(proj->GetInput())->GetPoints() : nullptr);
  vtkNew<vtkCatadioptricCamera> fromField;
  ASSERT_TRUE(fromField->ReadFromFieldData(out->GetFieldData()));

  const catar::Projector core(cam->GetModel());
  int visibleCount = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    double p[3];
    out->GetPoint(i, p);
    const catar::ProjectedPoint q = core.ProjectWorld(catar::Vec3(p[0], p[1], p[2]));
    EXPECT_EQ(st->GetComponent(i, 0), static_cast<int>(q.status));
    EXPECT_DOUBLE_EQ(px->GetComponent(i, 0), q.pixel.x());
    EXPECT_DOUBLE_EQ(px->GetComponent(i, 1), q.pixel.y());
    EXPECT_DOUBLE_EQ(mp->GetComponent(i, 2), q.mirrorPoint.z());
    EXPECT_DOUBLE_EQ(pl->GetComponent(i, 0), q.pathLength);
    visibleCount += vis->GetComponent(i, 0) != 0;
  }
  EXPECT_EQ(visibleCount, out->GetNumberOfPoints());
  // CentroidDepth is the centroid's own path length.
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); c += 7)
  {
    out->GetCellPoints(c, ids);
    catar::Vec3 centroid = catar::Vec3::Zero();
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      double p[3];
      out->GetPoint(ids->GetId(k), p);
      centroid += catar::Vec3(p[0], p[1], p[2]);
    }
    centroid /= static_cast<double>(ids->GetNumberOfIds());
    EXPECT_NEAR(depth->GetComponent(c, 0), core.ProjectWorld(centroid).pathLength, 1e-15);
    EXPECT_EQ(cvis->GetComponent(c, 0), 1);
  }
  // The iterative solver gives the same pixels.
  proj->SetSolverToIterative();
  proj->Update();
  vtkDataArray* px2 = proj->GetOutput()->GetPointData()->GetArray("ImageCoordinates");
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    EXPECT_NEAR(px2->GetComponent(i, 0),
      core
        .ProjectWorld([&] {
          double p[3];
          proj->GetOutput()->GetPoint(i, p);
          return catar::Vec3(p[0], p[1], p[2]);
        }())
        .pixel.x(),
      1e-9);
  }
}

TEST(vtkCatadioptricProjection, CellsWithAHiddenVertexAreInvisible)
{
  vtkNew<vtkCatadioptricCamera> cam;
  catar_test::SetSmallDemoCamera(cam);
  // A sphere straddling the mirror's shadow: behind the mirror (world y > 0.05) some vertices are
  // hidden, some cells are invisible, none is NaN.
  vtkNew<vtkCatadioptricProjection> proj;
  proj->SetCamera(cam);
  proj->SetInputData(SphereAt(0.0, 0.2, 1.0, 0.12));
  proj->Update();
  vtkPolyData* out = proj->GetOutput();
  vtkDataArray* st = out->GetPointData()->GetArray("ProjectionStatus");
  vtkDataArray* vis = out->GetPointData()->GetArray("Visible");
  vtkDataArray* px = out->GetPointData()->GetArray("ImageCoordinates");
  int hidden = 0;
  for (vtkIdType i = 0; i < out->GetNumberOfPoints(); ++i)
  {
    ASSERT_TRUE(std::isfinite(px->GetComponent(i, 0)) && std::isfinite(px->GetComponent(i, 1)));
    if (st->GetComponent(i, 0) == vtkCatadioptricCamera::HIDDEN_BY_MIRROR ||
      st->GetComponent(i, 0) == vtkCatadioptricCamera::INSIDE_MIRROR)
    {
      ++hidden;
      EXPECT_EQ(vis->GetComponent(i, 0), 0);
    }
  }
  EXPECT_GT(hidden, 0);
  vtkDataArray* cvis = out->GetCellData()->GetArray("Visible");
  vtkNew<vtkIdList> ids;
  int invisibleCells = 0;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    out->GetCellPoints(c, ids);
    bool all = true;
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      all = all && vis->GetComponent(ids->GetId(k), 0) != 0;
    }
    if (!all)
    {
      EXPECT_EQ(cvis->GetComponent(c, 0), 0) << c;
      ++invisibleCells;
    }
  }
  EXPECT_GT(invisibleCells, 0);
}

TEST(vtkCatadioptricProjection, BackFaceCullingDropsExactlyTheCellsFacingAway)
{
  vtkNew<vtkCatadioptricCamera> cam;
  catar_test::SetSmallDemoCamera(cam);
  vtkNew<vtkSphereSource> sphere; // closed, outward normals
  sphere->SetCenter(0.1, -0.3, 0.95);
  sphere->SetRadius(0.05);
  sphere->SetThetaResolution(64);
  sphere->SetPhiResolution(32);
  vtkNew<vtkCatadioptricProjection> all;
  all->SetCamera(cam);
  all->SetInputConnection(sphere->GetOutputPort());
  all->Update();
  vtkNew<vtkCatadioptricProjection> culled;
  culled->SetCamera(cam);
  culled->SetInputConnection(sphere->GetOutputPort());
  culled->BackFaceCullingOn();
  culled->Update();
  vtkPolyData* a = all->GetOutput();
  vtkPolyData* b = culled->GetOutput();
  vtkDataArray* visA = a->GetCellData()->GetArray("Visible");
  vtkDataArray* visB = b->GetCellData()->GetArray("Visible");
  vtkDataArray* mirror = a->GetCellData()->GetArray("CentroidMirrorPoint");
  vtkDataArray* depthA = a->GetCellData()->GetArray("CentroidDepth");
  vtkDataArray* depthB = b->GetCellData()->GetArray("CentroidDepth");
  const catar::CameraModel model = cam->GetModel();
  vtkNew<vtkIdList> ids;
  int visible = 0, kept = 0;
  for (vtkIdType c = 0; c < a->GetNumberOfCells(); ++c)
  {
    if (visA->GetComponent(c, 0) == 0)
    {
      EXPECT_EQ(visB->GetComponent(c, 0), 0) << c;
      continue;
    }
    ++visible;
    // The exact test: the face normal against the direction to the centroid's reflection point.
    a->GetCellPoints(c, ids);
    catar::Vec3 centroid = catar::Vec3::Zero(), normal = catar::Vec3::Zero();
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
    {
      double p[3], q[3];
      a->GetPoint(ids->GetId(k), p);
      a->GetPoint(ids->GetId((k + 1) % ids->GetNumberOfIds()), q);
      centroid += catar::Vec3(p[0], p[1], p[2]) / static_cast<double>(ids->GetNumberOfIds());
      normal += catar::Vec3(p[0], p[1], p[2]).cross(catar::Vec3(q[0], q[1], q[2]));
    }
    double m[3];
    mirror->GetTuple(c, m);
    const catar::Vec3 toViewer = model.CameraToWorld(catar::Vec3(m[0], m[1], m[2])) - centroid;
    const double facing = normal.normalized().dot(toViewer.normalized());
    if (visB->GetComponent(c, 0) != 0)
    {
      ++kept;
      EXPECT_GT(facing, 0.0) << c;
      EXPECT_EQ(depthA->GetComponent(c, 0), depthB->GetComponent(c, 0)) << c;
    }
    else
    {
      EXPECT_LE(facing, 0.0) << c;
    }
  }
  // Less than half of a sphere's cells face a viewer this close (0.42 of them here).
  ASSERT_GT(visible, 1000);
  EXPECT_GT(kept, visible / 4);
  EXPECT_LT(kept, 2 * visible / 3);
  std::printf("[ culling  ] %d of %d visible cells face the viewer\n", kept, visible);
}

// Without a camera object or a calibration file, the projection uses the panel camera: the
// demo camera (as Data/calibration/demo-camera.yaml describes it) until its properties change, and
// then a camera with those values; bad values are errors that name the panel property.
TEST(vtkCatadioptricProjection, PanelCameraIsTheDemoCameraUntilChanged)
{
  auto sphere = SphereAt(0.06, -0.32, 0.92, 0.03);
  auto pixelsOf = [&](vtkCatadioptricProjection* p) {
    p->SetInputData(sphere);
    p->Update();
    vtkDataArray* px = p->GetOutput()->GetPointData()->GetArray("ImageCoordinates");
    std::vector<double> values;
    for (vtkIdType i = 0; px && i < px->GetNumberOfTuples(); ++i)
    {
      values.push_back(px->GetComponent(i, 0));
      values.push_back(px->GetComponent(i, 1));
    }
    return values;
  };
  vtkNew<vtkCatadioptricProjection> panel;
  vtkNew<vtkCatadioptricProjection> file;
  file->SetCalibrationFileName(CATAR_SOURCE_DIR "/Data/calibration/demo-camera.yaml");
  const std::vector<double> fromPanel = pixelsOf(panel);
  ASSERT_FALSE(fromPanel.empty());
  EXPECT_EQ(fromPanel, pixelsOf(file));
  int size[2];
  double f[2], c[2], pose[16];
  panel->GetCameraImageSize(size);
  panel->GetFocalLength(f);
  panel->GetPrincipalPoint(c);
  panel->GetWorldToCamera(pose);
  EXPECT_EQ(size[0], 1328);
  EXPECT_EQ(size[1], 1048);
  EXPECT_EQ(f[0], 1000.0);
  EXPECT_EQ(c[1], 523.5);
  EXPECT_EQ(pose[7], 1.0); // the demo camera sits 1 m behind the world's origin along y

  // Changed values: the same pixels as a camera object with those values. Halving the focal
  // length about the principal point halves each pixel's offset from it (no distortion).
  panel->SetFocalLength(500, 500);
  const std::vector<double> half = pixelsOf(panel);
  ASSERT_EQ(half.size(), fromPanel.size());
  for (std::size_t i = 0; i < half.size(); i += 2)
  {
    EXPECT_NEAR(half[i] - 663.5, 0.5 * (fromPanel[i] - 663.5), 1e-9);
    EXPECT_NEAR(half[i + 1] - 523.5, 0.5 * (fromPanel[i + 1] - 523.5), 1e-9);
  }
  vtkNew<vtkCatadioptricCamera> object;
  ASSERT_TRUE(object->Load(CATAR_SOURCE_DIR "/Data/calibration/demo-camera.yaml"));
  object->SetFocalLength(500, 500);
  vtkNew<vtkCatadioptricProjection> withObject;
  withObject->SetCamera(object);
  EXPECT_EQ(half, pixelsOf(withObject));
  // A 4x4 pose and its 16 numbers are the same pose.
  double matrix[4][4];
  std::memcpy(matrix, pose, sizeof(pose));
  matrix[0][3] = 0.05;
  panel->SetWorldToCamera(matrix);
  double back[16];
  panel->GetWorldToCamera(back);
  EXPECT_EQ(back[3], 0.05);
  EXPECT_EQ(back[7], 1.0);

  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(panel);
  struct Case
  {
    std::function<void()> set;
    const char* property;
  };
  double skew[16];
  std::memcpy(skew, pose, sizeof(pose));
  skew[1] = 0.5; // not a rotation
  const std::vector<Case> cases = {
    { [&] { panel->SetFocalLength(-1, 500); }, "Focal Length" },
    { [&] { panel->SetFocalLength(500, std::nan("")); }, "Focal Length" },
    { [&] { panel->SetCameraImageSize(100000, 10); }, "Camera Image Size" },
    { [&] { panel->SetPrincipalPoint(std::nan(""), 0); }, "Principal Point" },
    { [&] { panel->SetDistortion(0, 0, std::numeric_limits<double>::infinity(), 0, 0); },
      "Distortion" },
    { [&] { panel->SetWorldToCamera(skew); }, "World To Camera" },
    { [&] { panel->SetMirrorType("sphere"); }, "Mirror Type" }, // no parameters
  };
  int expected = 0;
  for (const Case& k : cases)
  {
    // Each case from a good camera.
    panel->SetCameraImageSize(1328, 1048);
    panel->SetFocalLength(1000, 1000);
    panel->SetPrincipalPoint(663.5, 523.5);
    panel->SetDistortion(0, 0, 0, 0, 0);
    panel->SetWorldToCamera(pose);
    panel->SetMirrorType("");
    EXPECT_FALSE(pixelsOf(panel).empty());
    EXPECT_EQ(errors->Count, expected) << errors->Last;
    k.set();
    EXPECT_TRUE(pixelsOf(panel).empty()) << k.property;
    EXPECT_EQ(errors->Count, ++expected) << k.property;
    EXPECT_NE(errors->Last.find(std::string(": ") + k.property), std::string::npos) << errors->Last;
    EXPECT_EQ(errors->Last.find("Set"), std::string::npos) << errors->Last; // no C++ method
  }
}

TEST(vtkCatadioptricProjection, BadInputFailsCleanly)
{
  vtkNew<vtkCatadioptricProjection> proj;
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(proj);
  proj->SetInputData(SphereAt(0, -0.3, 1, 0.05));
  // No camera object and no file: the panel camera, which is the demo camera until changed; a
  // bad panel value is an error that names the panel property.
  proj->Update();
  EXPECT_EQ(errors->Count, 0) << errors->Last;
  EXPECT_GT(proj->GetOutput()->GetNumberOfPoints(), 0);
  proj->SetCameraImageSize(0, 480);
  proj->Update();
  EXPECT_EQ(errors->Count, 1);
  EXPECT_EQ(proj->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_NE(errors->Last.find(": Camera Image Size must be positive"), std::string::npos)
    << errors->Last;
  proj->SetCameraImageSize(1328, 1048);
  proj->Update();
  EXPECT_EQ(errors->Count, 1) << errors->Last;
  // An invalid camera (camera inside the mirror).
  vtkNew<vtkCatadioptricCamera> cam;
  catar_test::SetSmallDemoCamera(cam);
  cam->SetMirrorParameter("center", { 0, 0, 0.01 });
  proj->SetCamera(cam);
  proj->Update();
  EXPECT_EQ(proj->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(errors->Count, 2);
  EXPECT_NE(errors->Last.find("inside the mirror"), std::string::npos) << errors->Last;
  // A missing calibration file.
  proj->SetCamera(nullptr);
  proj->SetCalibrationFileName("/nonexistent/calibration.yaml");
  proj->Update();
  EXPECT_EQ(proj->GetOutput()->GetNumberOfPoints(), 0);
  EXPECT_EQ(errors->Count, 3);
  EXPECT_NE(errors->Last.find("/nonexistent/calibration.yaml"), std::string::npos);
  // Empty input is fine.
  catar_test::SetSmallDemoCamera(cam);
  proj->SetCamera(cam);
  vtkNew<vtkPolyData> empty;
  proj->SetInputData(empty);
  proj->Update();
  EXPECT_EQ(proj->GetOutput()->GetNumberOfPoints(), 0);
  // NaN coordinates give INVALID_INPUT, not NaN pixels.
  vtkNew<vtkPoints> pts;
  pts->InsertNextPoint(std::nan(""), 0, 1);
  pts->InsertNextPoint(0.1, -0.3, 1);
  pts->InsertNextPoint(0.1, -0.3, 1.1);
  vtkNew<vtkCellArray> tris;
  const vtkIdType tri[3] = { 0, 1, 2 };
  tris->InsertNextCell(3, tri);
  vtkNew<vtkPolyData> bad;
  bad->SetPoints(pts);
  bad->SetPolys(tris);
  proj->SetInputData(bad);
  proj->Update();
  vtkPolyData* out = proj->GetOutput();
  ASSERT_EQ(out->GetNumberOfPoints(), 3);
  EXPECT_EQ(out->GetPointData()->GetArray("ProjectionStatus")->GetComponent(0, 0),
    vtkCatadioptricCamera::INVALID_INPUT);
  EXPECT_EQ(out->GetPointData()->GetArray("ImageCoordinates")->GetComponent(0, 0), 0.0);
  EXPECT_EQ(out->GetCellData()->GetArray("Visible")->GetComponent(0, 0), 0);
}

TEST(vtkCatadioptricPainterSort, FarToNearWithCellDataAligned)
{
  vtkNew<vtkCatadioptricCamera> cam;
  catar_test::SetSmallDemoCamera(cam);
  vtkNew<vtkCatadioptricProjection> proj;
  proj->SetCamera(cam);
  vtkSmartPointer<vtkPolyData> sphere = SphereAt(0.05, -0.3, 0.95, 0.06);
  // Tag each cell with its original id to check that cell data follows the cells.
  vtkNew<vtkIdTypeArray> tag;
  tag->SetName("OriginalId");
  tag->SetNumberOfTuples(sphere->GetNumberOfCells());
  for (vtkIdType c = 0; c < sphere->GetNumberOfCells(); ++c)
  {
    tag->SetValue(c, c);
  }
  sphere->GetCellData()->AddArray(tag);
  proj->SetInputData(sphere);
  vtkNew<vtkCatadioptricPainterSort> sort;
  sort->SetInputConnection(proj->GetOutputPort());
  sort->Update();
  vtkPolyData* in = proj->GetOutput();
  vtkPolyData* out = sort->GetOutput();
  ASSERT_EQ(out->GetNumberOfCells(), in->GetNumberOfCells());
  vtkDataArray* depth = out->GetCellData()->GetArray("CentroidDepth");
  vtkDataArray* ids = out->GetCellData()->GetArray("OriginalId");
  vtkDataArray* inDepth = in->GetCellData()->GetArray("CentroidDepth");
  ASSERT_TRUE(depth && ids);
  vtkNew<vtkIdList> a, b;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    if (c > 0)
    {
      EXPECT_GE(depth->GetComponent(c - 1, 0), depth->GetComponent(c, 0));
    }
    const vtkIdType orig = static_cast<vtkIdType>(ids->GetComponent(c, 0));
    EXPECT_EQ(depth->GetComponent(c, 0), inDepth->GetComponent(orig, 0));
    out->GetCellPoints(c, a);
    in->GetCellPoints(orig, b);
    ASSERT_EQ(a->GetNumberOfIds(), b->GetNumberOfIds());
    for (vtkIdType k = 0; k < a->GetNumberOfIds(); ++k)
    {
      EXPECT_EQ(a->GetId(k), b->GetId(k));
    }
  }
  EXPECT_EQ(out->GetPoints(), in->GetPoints());
  EXPECT_NE(out->GetFieldData()->GetArray("CameraIntrinsics"), nullptr);

  // Dropping invisible cells: hide half the cells by hand.
  vtkNew<vtkPolyData> copy;
  copy->DeepCopy(in);
  vtkUnsignedCharArray* vis =
    vtkUnsignedCharArray::SafeDownCast(copy->GetCellData()->GetArray("Visible"));
  for (vtkIdType c = 0; c < copy->GetNumberOfCells(); c += 2)
  {
    vis->SetValue(c, 0);
  }
  sort->SetInputData(copy);
  sort->DropInvisibleCellsOn();
  sort->Update();
  EXPECT_EQ(sort->GetOutput()->GetNumberOfCells(), copy->GetNumberOfCells() / 2);
  vtkDataArray* outVis = sort->GetOutput()->GetCellData()->GetArray("Visible");
  for (vtkIdType c = 0; c < sort->GetOutput()->GetNumberOfCells(); ++c)
  {
    EXPECT_EQ(outVis->GetComponent(c, 0), 1);
  }

  // Visible values other than 0 and 1 (any nonzero value is visible) come through unchanged,
  // each with its cell.
  for (vtkIdType c = 1; c < copy->GetNumberOfCells(); c += 4)
  {
    vis->SetValue(c, static_cast<unsigned char>(2 + c % 7));
  }
  copy->Modified();
  sort->Update();
  vtkPolyData* sorted = sort->GetOutput();
  EXPECT_EQ(sorted->GetNumberOfCells(), copy->GetNumberOfCells() / 2);
  outVis = sorted->GetCellData()->GetArray("Visible");
  vtkDataArray* outIds = sorted->GetCellData()->GetArray("OriginalCellId");
  ASSERT_TRUE(outVis && outIds);
  int notOne = 0;
  for (vtkIdType c = 0; c < sorted->GetNumberOfCells(); ++c)
  {
    const vtkIdType orig = static_cast<vtkIdType>(outIds->GetComponent(c, 0));
    EXPECT_EQ(outVis->GetComponent(c, 0), vis->GetValue(orig)) << c;
    notOne += outVis->GetComponent(c, 0) != 1 ? 1 : 0;
  }
  EXPECT_GT(notOne, 0);
}

TEST(vtkCatadioptricPainterSort, OrderIsAStableSortByDepth)
{
  // Depths made to stress the sort: exact ties, depths that differ only in their last bits (the
  // radix passes look at the top bits only), long runs of such near ties, zero and
  // -0, negative and huge values; triangles and quads mixed, and triangles only. Then the depths
  // of one scene (0.3 to 0.9 with exact ties), and depths within a few thousand ulps of each other
  // (one long run of ties in the radix's high half, settled by the whole key). The order must be
  // exactly std::stable_sort's by decreasing depth, and cell data must follow.
  std::mt19937_64 rng(17);
  for (const int scene : { 0, 1, 2, 3 })
  {
    const bool quads = scene == 1;
    const vtkIdType n = 50000;
    vtkNew<vtkPoints> points;
    for (int i = 0; i < 8; ++i)
    {
      points->InsertNextPoint(i, i * i, 1);
    }
    vtkNew<vtkCellArray> polys;
    vtkNew<vtkDoubleArray> depth;
    depth->SetName("CentroidDepth");
    vtkNew<vtkUnsignedCharArray> visible;
    visible->SetName("Visible");
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<double> depths;
    for (vtkIdType c = 0; c < n; ++c)
    {
      const vtkIdType tri[3] = { c % 8, (c + 1) % 8, (c + 3) % 8 };
      const vtkIdType quad[4] = { c % 8, (c + 1) % 8, (c + 2) % 8, (c + 5) % 8 };
      if (quads && c % 3 == 0)
      {
        polys->InsertNextCell(4, quad);
      }
      else
      {
        polys->InsertNextCell(3, tri);
      }
      double d = 0.5 + unit(rng);
      switch (c % 10)
      {
        case 0:
          d = 0.75;
          break; // exact ties
        case 1:
          d = std::nextafter(0.75, 2.0) + 1e-13 * (c % 7);
          break; // near ties
        case 2:
          d = 0.25 + 1e-12 * static_cast<double>(c % 1000);
          break; // long runs
        case 3:
          d = (c % 20 == 3) ? 0.0 : -0.0;
          break;
        case 4:
          d = -unit(rng);
          break;
        case 5:
          d = 1e300 * unit(rng);
          break;
        default:
          break;
      }
      if (scene == 2)
      {
        d = c % 10 == 0 ? 0.6 : 0.3 + 0.6 * unit(rng);
      }
      else if (scene == 3)
      {
        std::uint64_t bits;
        const double base = 0.75;
        std::memcpy(&bits, &base, sizeof bits);
        bits += rng() % 4000;
        std::memcpy(&d, &bits, sizeof d);
      }
      depths.push_back(d);
      depth->InsertNextValue(d);
      visible->InsertNextValue(1);
    }
    vtkNew<vtkPolyData> mesh;
    mesh->SetPoints(points);
    mesh->SetPolys(polys);
    mesh->GetCellData()->AddArray(depth);
    mesh->GetCellData()->AddArray(visible);
    vtkNew<vtkCatadioptricPainterSort> sort;
    sort->SetInputData(mesh);
    sort->Update();
    vtkPolyData* out = sort->GetOutput();
    ASSERT_EQ(out->GetNumberOfPolys(), n);

    std::vector<vtkIdType> expected(n);
    std::iota(expected.begin(), expected.end(), 0);
    std::stable_sort(expected.begin(), expected.end(),
      [&](vtkIdType a, vtkIdType b) { return depths[a] > depths[b]; });
    vtkDataArray* original = out->GetCellData()->GetArray("OriginalCellId");
    vtkDataArray* outDepth = out->GetCellData()->GetArray("CentroidDepth");
    ASSERT_TRUE(original && outDepth);
    vtkNew<vtkIdList> a, b;
    for (vtkIdType i = 0; i < n; ++i)
    {
      ASSERT_EQ(static_cast<vtkIdType>(original->GetComponent(i, 0)), expected[i]) << i;
      ASSERT_EQ(outDepth->GetComponent(i, 0), depths[expected[i]]) << i;
      out->GetCellPoints(i, a);
      mesh->GetCellPoints(expected[i], b);
      ASSERT_EQ(a->GetNumberOfIds(), b->GetNumberOfIds());
      for (vtkIdType k = 0; k < a->GetNumberOfIds(); ++k)
      {
        ASSERT_EQ(a->GetId(k), b->GetId(k));
      }
    }
  }
}

TEST(vtkCatadioptricPainterSort, RequiresProjectedInput)
{
  vtkNew<vtkCatadioptricPainterSort> sort;
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(sort);
  sort->SetInputData(SphereAt(0, 0, 0, 1));
  sort->Update();
  EXPECT_EQ(sort->GetOutput()->GetNumberOfCells(), 0);
  EXPECT_EQ(errors->Count, 1);
  EXPECT_NE(errors->Last.find("CentroidDepth"), std::string::npos);
}
