// vtkCatadioptricRigSource against oracles of its own: the camera centre from the pose matrix; the
// frustum's corners projected back onto the image corners with OpenCV's lens formula written out
// here; every mirror point on the mirror's implicit surface (sphere |p - c| = r, hyperboloid
// X^T Q X = 0 with Q made here from a and b) and inside its z_range; the normals along the
// surface's gradient; each mirror point the first point of the mirror on the camera ray through
// it (the ray-quadric roots solved here); the forward projection of a point on its reflected ray
// finding it again; the sphere's outline on its tangent cone and the triangles' area against the
// visible cap's. For the demo camera (its calibration file) and the tilted hyperboloid with lens
// distortion and a turned pose.
#include "TestUtilities.h"

#include "vtkCatadioptricCamera.h"
#include "vtkCatadioptricRigSource.h"
#include "vtkCellData.h"
#include "vtkDataArray.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkIntArray.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace
{
using catar::Mat3;
using catar::Mat4;
using catar::Vec2;
using catar::Vec3;
using Vec4 = Eigen::Vector4d;
constexpr double kPi = 3.14159265358979323846;

// A mirror as this test knows it: a quadric Q (mirror frame, X = (x, y, z, 1)), its placement in
// the camera frame, and its z_range (none for the closed-form sphere).
struct MirrorOracle
{
  Mat4 q = Mat4::Zero();
  Mat4 mirrorToCamera = Mat4::Identity();
  bool bounded = false;
  double zmin = 0.0, zmax = 0.0;

  Vec4 ToMirror(const Vec3& p) const
  {
    return mirrorToCamera.inverse() * Vec4(p.x(), p.y(), p.z(), 1.0);
  }
  // X^T Q X at a camera-frame point, and its gradient (camera frame).
  double Value(const Vec3& p) const
  {
    const Vec4 X = ToMirror(p);
    return X.dot(q * X);
  }
  Vec3 Gradient(const Vec3& p) const
  {
    const Vec4 X = ToMirror(p);
    const Vec3 g = (2.0 * q * X).head<3>();
    return mirrorToCamera.topLeftCorner<3, 3>() * g; // rotation: gradients turn as directions
  }
  double Z(const Vec3& p) const { return ToMirror(p).z(); }
  bool InRange(const Vec3& p, double tol) const
  {
    return !bounded || (Z(p) >= zmin - tol && Z(p) <= zmax + tol);
  }
  // The distance along the unit camera-frame direction d to the first point of the mirror, or -1.
  double FirstHit(const Vec3& d) const
  {
    const Mat4 toMirror = mirrorToCamera.inverse();
    const Vec4 o = toMirror * Vec4(0, 0, 0, 1);
    const Vec4 v = toMirror * Vec4(d.x(), d.y(), d.z(), 0);
    const double a = v.dot(q * v), b = 2.0 * v.dot(q * o), c = o.dot(q * o);
    double disc = b * b - 4 * a * c;
    if (disc < -1e-12 * b * b)
    {
      return -1;
    }
    // The stable pair of roots (a ray that grazes the mirror: a double root, the discriminant
    // rounded to zero).
    const double s = std::sqrt(std::max(0.0, disc));
    const double k = -0.5 * (b + (b >= 0 ? s : -s));
    std::vector<double> roots = { k / a, c / k };
    std::sort(roots.begin(), roots.end());
    for (double t : roots)
    {
      const Vec4 X = o + t * v;
      if (t > 0 && (!bounded || (X.z() >= zmin - 1e-9 && X.z() <= zmax + 1e-9)))
      {
        return t;
      }
    }
    return -1;
  }
};

MirrorOracle SphereOracle(const Vec3& centre, double radius)
{
  MirrorOracle m;
  m.q = Mat4::Identity();
  m.q(3, 3) = -radius * radius;
  m.mirrorToCamera.topRightCorner<3, 1>() = centre;
  return m;
}

// The hyperboloid of TestCameras.h's description: (x^2 + y^2) / b^2 - z^2 / a^2 + 1 = 0.
MirrorOracle HyperboloidOracle(const catar::MirrorDescription& d)
{
  EXPECT_EQ(d.type, "hyperboloid");
  EXPECT_EQ(d.parameters.size(), 20u);
  MirrorOracle m;
  const double a = d.parameters[0], b = d.parameters[1];
  m.q.diagonal() << 1 / (b * b), 1 / (b * b), -1 / (a * a), 1.0;
  for (int i = 0; i < 16; ++i)
  {
    m.mirrorToCamera(i / 4, i % 4) = d.parameters[2 + i];
  }
  m.bounded = true;
  m.zmin = d.parameters[18];
  m.zmax = d.parameters[19];
  return m;
}

// OpenCV's projection of a camera-frame point, written out (cv::projectPoints' formula).
Vec2 LensPixel(const catar::CameraModel& model, const Vec3& p)
{
  const double x = p.x() / p.z(), y = p.y() / p.z();
  const catar::Distortion& k = model.distortion;
  const double r2 = x * x + y * y;
  const double radial = 1 + k.k1 * r2 + k.k2 * r2 * r2 + k.k3 * r2 * r2 * r2;
  const double xd = x * radial + 2 * k.p1 * x * y + k.p2 * (r2 + 2 * x * x);
  const double yd = y * radial + k.p1 * (r2 + 2 * y * y) + 2 * k.p2 * x * y;
  const catar::Intrinsics& in = model.intrinsics;
  return Vec2(in.fx * xd + in.skew * yd + in.cx, in.fy * yd + in.cy);
}

// The output taken apart, back in the camera frame.
struct Rig
{
  Vec3 centre = Vec3::Constant(std::nan(""));
  std::vector<std::array<Vec3, 2>> frustumLines; // camera frame
  std::vector<std::vector<Vec3>> frustumLoops;   // camera frame
  std::vector<Vec3> mirrorPoints, mirrorNormals; // camera frame, the points of mirror triangles
  std::vector<std::array<int, 3>> triangles;     // indices into mirrorPoints
  std::vector<std::vector<Vec3>> outlines;       // camera frame
  int centres = 0;
  bool bad = false;
};

Rig Read(vtkPolyData* out, const Mat4& worldToCamera)
{
  Rig rig;
  vtkIntArray* parts = vtkIntArray::SafeDownCast(out->GetCellData()->GetAbstractArray("RigPart"));
  vtkDataArray* normals = out->GetPointData()->GetNormals();
  EXPECT_NE(parts, nullptr);
  EXPECT_NE(normals, nullptr);
  if (!parts || !normals || parts->GetNumberOfTuples() != out->GetNumberOfCells())
  {
    rig.bad = true;
    return rig;
  }
  const Mat3 R = worldToCamera.topLeftCorner<3, 3>();
  const Vec3 t = worldToCamera.topRightCorner<3, 1>();
  auto point = [&](vtkIdType id) {
    double p[3];
    out->GetPoint(id, p);
    return Vec3(R * Vec3(p[0], p[1], p[2]) + t);
  };
  std::map<vtkIdType, int> mirrorIndex;
  for (vtkIdType c = 0; c < out->GetNumberOfCells(); ++c)
  {
    vtkIdType n;
    const vtkIdType* ids;
    out->GetCellPoints(c, n, ids);
    std::vector<Vec3> pts;
    for (vtkIdType k = 0; k < n; ++k)
    {
      pts.push_back(point(ids[k]));
    }
    switch (parts->GetValue(c))
    {
      case vtkCatadioptricRigSource::CAMERA_CENTRE:
        EXPECT_EQ(n, 1);
        double p[3];
        out->GetPoint(ids[0], p);
        rig.centre = Vec3(p[0], p[1], p[2]);
        ++rig.centres;
        break;
      case vtkCatadioptricRigSource::FRUSTUM:
        if (n == 2)
        {
          rig.frustumLines.push_back({ { pts[0], pts[1] } });
        }
        else
        {
          rig.frustumLoops.push_back(pts);
        }
        break;
      case vtkCatadioptricRigSource::MIRROR:
      {
        EXPECT_EQ(n, 3);
        std::array<int, 3> tri{};
        for (int k = 0; k < 3 && k < n; ++k)
        {
          auto it = mirrorIndex.find(ids[k]);
          if (it == mirrorIndex.end())
          {
            it = mirrorIndex.emplace(ids[k], static_cast<int>(rig.mirrorPoints.size())).first;
            rig.mirrorPoints.push_back(pts[k]);
            double nw[3];
            normals->GetTuple(ids[k], nw);
            rig.mirrorNormals.push_back(R * Vec3(nw[0], nw[1], nw[2]));
          }
          tri[k] = it->second;
        }
        rig.triangles.push_back(tri);
        break;
      }
      case vtkCatadioptricRigSource::MIRROR_OUTLINE:
        rig.outlines.push_back(pts);
        break;
      default:
        ADD_FAILURE() << "RigPart " << parts->GetValue(c);
        rig.bad = true;
    }
  }
  return rig;
}

struct Measured
{
  double surface = 0, range = 0, normal = 0, firstHit = 0, firstHitGrazing = 0, reflected = 0,
         corner = 0, depth = 0;
  int reflectedChecked = 0;
};

// Every check but the shape-specific ones; returns the worst errors seen.
Measured Check(const Rig& rig, const catar::CameraModel& model, const MirrorOracle& mirror,
  vtkCatadioptricCamera* camera, double frustumLength)
{
  Measured m;
  // The camera centre: -R^T t.
  const Mat3 R = model.worldToCamera.topLeftCorner<3, 3>();
  const Vec3 t = model.worldToCamera.topRightCorner<3, 1>();
  EXPECT_EQ(rig.centres, 1);
  EXPECT_LT((rig.centre - (-R.transpose() * t)).norm(), 1e-12) << rig.centre.transpose();

  // The frustum: four lines from the centre (camera-frame origin) to points at depth
  // frustumLength that the lens images on the four image corners; one closed border loop.
  const double w = model.intrinsics.width, h = model.intrinsics.height;
  const std::vector<Vec2> corners = { Vec2(-0.5, -0.5), Vec2(w - 0.5, -0.5), Vec2(w - 0.5, h - 0.5),
    Vec2(-0.5, h - 0.5) };
  EXPECT_EQ(rig.frustumLines.size(), 4u);
  std::set<int> matched;
  for (const auto& line : rig.frustumLines)
  {
    EXPECT_LT(line[0].norm(), 1e-12);
    m.depth = std::max(m.depth, std::abs(line[1].z() - frustumLength));
    const Vec2 px = LensPixel(model, line[1]);
    int best = -1;
    double bestDistance = 1e300;
    for (int k = 0; k < 4; ++k)
    {
      if ((px - corners[k]).norm() < bestDistance)
      {
        bestDistance = (px - corners[k]).norm();
        best = k;
      }
    }
    m.corner = std::max(m.corner, bestDistance);
    matched.insert(best);
  }
  EXPECT_EQ(matched.size(), 4u);
  EXPECT_EQ(rig.frustumLoops.size(), 1u);
  for (const auto& loop : rig.frustumLoops)
  {
    EXPECT_LT((loop.front() - loop.back()).norm(), 1e-15); // closed
    for (const Vec3& p : loop)
    {
      m.depth = std::max(m.depth, std::abs(p.z() - frustumLength));
      // On the image border: one coordinate at -0.5 or size - 0.5.
      const Vec2 px = LensPixel(model, p);
      const double border = std::min({ std::abs(px.x() + 0.5), std::abs(px.x() - (w - 0.5)),
        std::abs(px.y() + 0.5), std::abs(px.y() - (h - 0.5)) });
      m.corner = std::max(m.corner, border);
    }
  }

  // The mirror.
  EXPECT_GT(rig.triangles.size(), 100u);
  const Mat4 worldToCamera = model.worldToCamera;
  const Mat4 cameraToWorld = worldToCamera.inverse();
  for (std::size_t k = 0; k < rig.mirrorPoints.size(); ++k)
  {
    const Vec3& p = rig.mirrorPoints[k];
    const Vec3& n = rig.mirrorNormals[k];
    const Vec3 g = mirror.Gradient(p);
    // On the surface: |X^T Q X| / |gradient| is the distance to it, to first order.
    m.surface = std::max(m.surface, std::abs(mirror.Value(p)) / g.norm());
    if (mirror.bounded)
    {
      m.range = std::max(m.range, std::max(mirror.zmin - mirror.Z(p), mirror.Z(p) - mirror.zmax));
    }
    // The normal: unit, along the gradient, facing the camera.
    EXPECT_NEAR(n.norm(), 1.0, 1e-12);
    m.normal = std::max(m.normal, n.cross(g.normalized()).norm());
    EXPECT_LT(n.dot(p.normalized()), 1e-12) << "the normal faces the camera (or grazes the ray)";
    // Seen in the image: its pixel inside the image (edges included).
    const Vec2 px = LensPixel(model, p);
    EXPECT_TRUE(px.x() >= -0.5 - 1e-6 && px.x() <= w - 0.5 + 1e-6 && px.y() >= -0.5 - 1e-6 &&
      px.y() <= h - 0.5 + 1e-6)
      << px.transpose();
    // The camera ray through it meets the mirror there first.
    const double hit = mirror.FirstHit(p.normalized());
    // (A ray that grazes the mirror meets it at a double root, known to about sqrt(epsilon).)
    const bool grazing = std::abs(p.normalized().dot(n)) < 1e-3;
    double& worstHit = grazing ? m.firstHitGrazing : m.firstHit;
    worstHit = std::max(worstHit, std::abs(hit - p.norm()));
    // A point on its reflected ray projects back to it (the camera's forward solver), away from
    // grazing rays.
    const Vec3 d = p.normalized();
    if (k % 5 == 0 && std::abs(d.dot(n)) > 0.05)
    {
      const Vec3 r = d - 2.0 * d.dot(n) * n;
      const Vec3 P = p + 0.3 * r;
      const Vec4 Pw = cameraToWorld * Vec4(P.x(), P.y(), P.z(), 1.0);
      double pixel[2], mirrorPoint[3];
      const int status = camera->ProjectWorldPoint(Pw.data(), pixel, mirrorPoint);
      EXPECT_TRUE(
        status == vtkCatadioptricCamera::VALID || status == vtkCatadioptricCamera::OUTSIDE_IMAGE)
        << status;
      m.reflected =
        std::max(m.reflected, (Vec3(mirrorPoint[0], mirrorPoint[1], mirrorPoint[2]) - p).norm());
      ++m.reflectedChecked;
    }
  }
  // The triangles face the camera, as their vertices' normals.
  int facing = 0;
  for (const auto& tri : rig.triangles)
  {
    const Vec3& a = rig.mirrorPoints[tri[0]];
    const Vec3 cross = (rig.mirrorPoints[tri[1]] - a).cross(rig.mirrorPoints[tri[2]] - a);
    facing += cross.dot(rig.mirrorNormals[tri[0]]) >= 0.0 ? 1 : 0;
  }
  EXPECT_EQ(facing, static_cast<int>(rig.triangles.size()));
  // The outline: closed loops on the mirror.
  EXPECT_GE(rig.outlines.size(), 1u);
  for (const auto& loop : rig.outlines)
  {
    EXPECT_GE(loop.size(), 10u);
    EXPECT_LT((loop.front() - loop.back()).norm(), 1e-15);
  }
  std::printf(
    "  %zu mirror points, %zu triangles, %zu outline loop(s) of %zu points; worst: "
    "surface %.2e, z_range %.2e, normal %.2e, first hit %.2e (grazing %.2e), reflected %.2e (%d "
    "points), corner pixel %.2e, depth %.2e\n",
    rig.mirrorPoints.size(), rig.triangles.size(), rig.outlines.size(),
    rig.outlines.empty() ? std::size_t(0) : rig.outlines[0].size(), m.surface, m.range, m.normal,
    m.firstHit, m.firstHitGrazing, m.reflected, m.reflectedChecked, m.corner, m.depth);
  return m;
}

// The area of the triangles' radial projection onto the sphere (Van Oosterom and Strackee's solid
// angle): the cap they cover, overlaps counted twice.
double SphericalArea(const Rig& rig, const Vec3& centre, double radius)
{
  double area = 0;
  for (const auto& tri : rig.triangles)
  {
    const Vec3 a = (rig.mirrorPoints[tri[0]] - centre).normalized();
    const Vec3 b = (rig.mirrorPoints[tri[1]] - centre).normalized();
    const Vec3 c = (rig.mirrorPoints[tri[2]] - centre).normalized();
    const double solid =
      2 * std::atan2(std::abs(a.dot(b.cross(c))), 1 + a.dot(b) + b.dot(c) + c.dot(a));
    area += solid * radius * radius;
  }
  return area;
}

double Area(const Rig& rig)
{
  double area = 0;
  for (const auto& tri : rig.triangles)
  {
    const Vec3& a = rig.mirrorPoints[tri[0]];
    area += 0.5 * (rig.mirrorPoints[tri[1]] - a).cross(rig.mirrorPoints[tri[2]] - a).norm();
  }
  return area;
}

Mat4 Pose(vtkCatadioptricCamera* camera)
{
  double e[16];
  camera->GetWorldToCameraElements(e);
  Mat4 m;
  for (int i = 0; i < 16; ++i)
  {
    m(i / 4, i % 4) = e[i];
  }
  return m;
}

// The tilted hyperboloid with lens distortion, seen from a turned and moved pose.
catar::CameraModel DistortedHyperboloidModel()
{
  catar::CameraModel model = catar_test::TiltedHyperboloidCameraModel();
  model.intrinsics = catar::Intrinsics{ 620.0, 640.0, 330.0, 236.0, 0.5, 640, 480 };
  model.distortion = catar::Distortion{ -0.12, 0.03, 0.001, -0.0015, -0.002 };
  const Eigen::AngleAxisd turn(0.7, Vec3(1, 2, 3).normalized());
  model.worldToCamera.setIdentity();
  model.worldToCamera.topLeftCorner<3, 3>() = turn.toRotationMatrix();
  model.worldToCamera.topRightCorner<3, 1>() = Vec3(0.1, -0.2, 0.3);
  return model;
}
} // namespace

// The demo camera from its calibration file: a sphere wholly inside the image.
TEST(RigSource, DemoSphereFromCalibrationFile)
{
  vtkNew<vtkCatadioptricRigSource> source;
  source->SetCalibrationFileName(CATAR_SOURCE_DIR "/Data/calibration/demo-camera.yaml");
  ASSERT_TRUE(source->GetExecutive()->Update());
  vtkNew<vtkCatadioptricCamera> camera;
  ASSERT_TRUE(camera->Load(CATAR_SOURCE_DIR "/Data/calibration/demo-camera.yaml"));
  const catar::CameraModel model = camera->GetModel();
  const Vec3 centre(0.0, 0.0, 0.14);
  const double radius = 0.05;
  const MirrorOracle sphere = SphereOracle(centre, radius);
  const Rig rig = Read(source->GetOutput(), Pose(camera));
  ASSERT_FALSE(rig.bad);
  // The automatic depth: 1.25 times the farthest mirror point's.
  double farthest = 0;
  for (const Vec3& p : rig.mirrorPoints)
  {
    farthest = std::max(farthest, p.z());
  }
  EXPECT_NEAR(source->GetFrustumLengthUsed(), 1.25 * farthest, 1e-15);
  const Measured m = Check(rig, model, sphere, camera, source->GetFrustumLengthUsed());
  EXPECT_LT(m.surface, 1e-12);
  EXPECT_LT(m.normal, 1e-9);
  EXPECT_LT(m.firstHit, 1e-12);
  EXPECT_LT(m.firstHitGrazing, 1e-7);
  EXPECT_LT(m.reflected, 1e-8);
  EXPECT_GT(m.reflectedChecked, 100);
  EXPECT_LT(m.corner, 1e-9);
  EXPECT_LT(m.depth, 1e-15);
  // The camera centre of the file: world (0, -0.14, 1).
  EXPECT_LT((rig.centre - Vec3(0, -0.14, 1)).norm(), 1e-15);
  // The sphere's image is inside the frame: one loop, on the tangent cone of half-angle
  // asin(r / |c|) around the centre's direction.
  ASSERT_EQ(rig.outlines.size(), 1u);
  const double alpha = std::asin(radius / centre.norm());
  double cone = 0;
  for (const Vec3& p : rig.outlines[0])
  {
    cone = std::max(cone, std::abs(std::acos(p.normalized().dot(centre.normalized())) - alpha));
  }
  std::printf("  outline off the tangent cone by %.2e rad at most\n", cone);
  EXPECT_LT(cone, 1e-6);
  // The triangles cover the cap the camera sees, 2 pi r^2 (1 - r / |c|), once: the area of their
  // projection onto the sphere from its centre is the cap's, but for the slivers that the chords
  // along the rim leave out. (Their flat area is no bound: a sliver whose plane passes near the
  // centre is larger than its projection.)
  const double cap = 2 * kPi * radius * radius * (1 - radius / centre.norm());
  const double covered = SphericalArea(rig, centre, radius);
  std::printf(
    "  mirror area %.7f m^2 (flat %.7f), the visible cap %.7f m^2\n", covered, Area(rig), cap);
  EXPECT_LE(covered, cap * (1 + 1e-12));
  EXPECT_GT(covered, cap * (1 - 1e-3));
  EXPECT_NEAR(Area(rig) / cap, 1.0, 0.01);
  // The camera travels as field data.
  vtkNew<vtkCatadioptricCamera> used;
  EXPECT_TRUE(used->ReadFromFieldData(source->GetOutput()->GetFieldData()));
  // Finer sampling: closer to the cap.
  source->SetMirrorResolution(128);
  source->Update();
  const Rig fine = Read(source->GetOutput(), Pose(camera));
  const double fineCovered = SphericalArea(fine, centre, radius);
  std::printf(
    "  at resolution 128: %zu triangles, area %.7f m^2\n", fine.triangles.size(), fineCovered);
  EXPECT_GT(fine.triangles.size(), rig.triangles.size());
  EXPECT_LE(fineCovered, cap * (1 + 1e-12));
  EXPECT_LT(cap - fineCovered, cap - covered);
  // No outline on request.
  source->MirrorOutlineOff();
  source->Update();
  EXPECT_TRUE(Read(source->GetOutput(), Pose(camera)).outlines.empty());
}

// The tilted hyperboloid, with distortion, skew and a turned pose: the whole camera model.
TEST(RigSource, TiltedHyperboloidWithDistortion)
{
  const catar::CameraModel model = DistortedHyperboloidModel();
  vtkNew<vtkCatadioptricCamera> camera;
  camera->SetModel(model);
  ASSERT_TRUE(camera->IsValid()) << camera->GetLastError();
  vtkNew<vtkCatadioptricRigSource> source;
  source->SetCamera(camera);
  source->SetFrustumLength(0.2);
  ASSERT_TRUE(source->GetExecutive()->Update());
  EXPECT_EQ(source->GetFrustumLengthUsed(), 0.2);
  const Rig rig = Read(source->GetOutput(), model.worldToCamera);
  ASSERT_FALSE(rig.bad);
  const MirrorOracle hyperboloid = HyperboloidOracle(model.mirror);
  const Measured m = Check(rig, model, hyperboloid, camera, 0.2);
  EXPECT_LT(m.surface, 1e-12);
  EXPECT_LT(m.range, 1e-9);
  EXPECT_LT(m.normal, 1e-9);
  EXPECT_LT(m.firstHit, 1e-12);
  EXPECT_LT(m.firstHitGrazing, 1e-7);
  EXPECT_LT(m.reflected, 1e-8);
  EXPECT_GT(m.reflectedChecked, 100);
  EXPECT_LT(m.corner, 1e-8);
  EXPECT_LT(m.depth, 1e-15);
  // The border follows the distorted image edge: 16 points a side.
  ASSERT_EQ(rig.frustumLoops.size(), 1u);
  EXPECT_EQ(rig.frustumLoops[0].size(), 4u * 16u + 1u);
  // The rim the camera sees is the cut at z_range's top: outline points there.
  double top = 1e300;
  for (const auto& loop : rig.outlines)
  {
    for (const Vec3& p : loop)
    {
      top = std::min(top, std::abs(hyperboloid.Z(p) - hyperboloid.zmax));
    }
  }
  EXPECT_LT(top, 1e-9);
}

// The mirror chosen over a calibration file's (ParaView's panel) gives what the camera with that
// mirror gives.
TEST(RigSource, MirrorInPlaceOfTheFiles)
{
  const catar::CameraModel model = catar_test::TiltedHyperboloidCameraModel();
  vtkNew<vtkCatadioptricRigSource> panel;
  panel->SetCalibrationFileName(CATAR_SOURCE_DIR "/Data/calibration/demo-camera.yaml");
  panel->SetMirrorType("hyperboloid");
  panel->SetNumberOfMirrorParameters(static_cast<int>(model.mirror.parameters.size()));
  for (std::size_t i = 0; i < model.mirror.parameters.size(); ++i)
  {
    panel->SetMirrorParameter(static_cast<int>(i), model.mirror.parameters[i]);
  }
  ASSERT_TRUE(panel->GetExecutive()->Update());
  vtkNew<vtkCatadioptricCamera> camera;
  camera->SetModel(model);
  vtkNew<vtkCatadioptricRigSource> object;
  object->SetCamera(camera);
  ASSERT_TRUE(object->GetExecutive()->Update());
  vtkPolyData* a = panel->GetOutput();
  vtkPolyData* b = object->GetOutput();
  ASSERT_EQ(a->GetNumberOfPoints(), b->GetNumberOfPoints());
  ASSERT_EQ(a->GetNumberOfCells(), b->GetNumberOfCells());
  for (vtkIdType i = 0; i < a->GetNumberOfPoints(); ++i)
  {
    double p[3], q[3];
    a->GetPoint(i, p);
    b->GetPoint(i, q);
    ASSERT_EQ(Vec3(p[0], p[1], p[2]), Vec3(q[0], q[1], q[2])) << i;
  }
  const Rig rig = Read(b, model.worldToCamera);
  const Measured m =
    Check(rig, model, HyperboloidOracle(model.mirror), camera, object->GetFrustumLengthUsed());
  EXPECT_LT(m.surface, 1e-12);
  EXPECT_LT(m.range, 1e-9);
  EXPECT_LT(m.firstHit, 1e-12);
  EXPECT_LT(m.firstHitGrazing, 1e-7);
}

// A trajectory: its times as time steps; at each, the centre where that pose puts it.
TEST(RigSource, FollowsATrajectory)
{
  const std::filesystem::path dir = std::filesystem::path(CATAR_TEST_OUTPUT_DIR) / "rig-source";
  std::filesystem::create_directories(dir);
  const std::string file = (dir / "poses.txt").string();
  {
    std::ofstream f(file);
    for (int k = 0; k < 3; ++k)
    {
      f << 0.5 * k << " 1 0 0 " << -0.02 * k << "  0 0 -1 1.0  0 1 0 0.14  0 0 0 1\n";
    }
  }
  vtkNew<vtkCatadioptricRigSource> source;
  source->SetCalibrationFileName(CATAR_SOURCE_DIR "/Data/calibration/demo-camera.yaml");
  source->SetTrajectoryFileName(file.c_str());
  source->UpdateInformation();
  vtkInformation* info = source->GetOutputInformation(0);
  ASSERT_TRUE(info->Has(vtkStreamingDemandDrivenPipeline::TIME_STEPS()));
  ASSERT_EQ(info->Length(vtkStreamingDemandDrivenPipeline::TIME_STEPS()), 3);
  for (int k = 0; k < 3; ++k)
  {
    ASSERT_TRUE(source->UpdateTimeStep(0.5 * k));
    double c[3];
    source->GetOutput()->GetPoint(0, c);
    EXPECT_LT((Vec3(c[0], c[1], c[2]) - Vec3(0.02 * k, -0.14, 1.0)).norm(), 1e-12) << k;
  }
}

// Bad cameras and values: an error, an empty output, no crash.
TEST(RigSource, BadInput)
{
  vtkNew<vtkCatadioptricRigSource> source;
  vtkNew<catar_test::ErrorCounter> errors;
  errors->Watch(source);
  // A missing calibration file.
  source->SetCalibrationFileName("/nonexistent/camera.yaml");
  EXPECT_FALSE(source->GetExecutive()->Update());
  EXPECT_GE(errors->Count, 1);
  EXPECT_EQ(source->GetOutput()->GetNumberOfPoints(), 0);
  // An invalid camera object.
  vtkNew<vtkCatadioptricCamera> camera;
  camera->SetModel(catar_test::DemoCameraModel());
  camera->SetFocalLength(-5.0, 1000.0);
  source->SetCamera(camera);
  const int before = errors->Count;
  EXPECT_FALSE(source->GetExecutive()->Update());
  EXPECT_GT(errors->Count, before);
  EXPECT_NE(errors->Last.find("camera"), std::string::npos) << errors->Last;
  EXPECT_EQ(source->GetOutput()->GetNumberOfPoints(), 0);
  // NaN and infinite frustum lengths are refused.
  camera->SetModel(catar_test::DemoCameraModel());
  source->SetFrustumLength(0.3);
  source->SetFrustumLength(std::nan(""));
  source->SetFrustumLength(HUGE_VAL);
  EXPECT_EQ(source->GetFrustumLength(), 0.3);
  EXPECT_TRUE(source->GetExecutive()->Update());
  // Resolutions are clamped.
  source->SetMirrorResolution(-4);
  EXPECT_EQ(source->GetMirrorResolution(), 2);
  EXPECT_TRUE(source->GetExecutive()->Update());
  source->SetMirrorResolution(1 << 30);
  EXPECT_EQ(source->GetMirrorResolution(), 1024);
  source->SetMirrorResolution(48);
  // A camera that does not see its mirror (it lies outside the field of view): the centre and the
  // frustum, no mirror, no error.
  catar::CameraModel aside = catar_test::DemoCameraModel();
  aside.mirror = catar::MirrorDescription("sphere", { 2.0, 0.0, 0.5, 0.05 });
  camera->SetModel(aside);
  ASSERT_TRUE(camera->IsValid()) << camera->GetLastError();
  const int quiet = errors->Count;
  EXPECT_TRUE(source->GetExecutive()->Update());
  EXPECT_EQ(errors->Count, quiet);
  vtkPolyData* out = source->GetOutput();
  EXPECT_EQ(out->GetNumberOfPolys(), 0);
  EXPECT_EQ(out->GetNumberOfVerts(), 1);
  EXPECT_EQ(out->GetNumberOfLines(), 5);
  EXPECT_EQ(source->GetFrustumLengthUsed(), 0.3); // the length set above
  // The automatic depth then: 1.25 times the mirror's viewpoint's (the sphere's centre).
  source->SetFrustumLength(0.0);
  EXPECT_TRUE(source->GetExecutive()->Update());
  EXPECT_NEAR(source->GetFrustumLengthUsed(), 1.25 * 0.5, 1e-15);
}
