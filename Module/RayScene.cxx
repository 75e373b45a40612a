#include "RayScene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

namespace catar
{
struct RayScene::Internals
{
  RTCDevice Device = nullptr;
  RTCScene Scene = nullptr;

  void Release()
  {
    if (this->Scene)
    {
      rtcReleaseScene(this->Scene);
      this->Scene = nullptr;
    }
    if (this->Device)
    {
      rtcReleaseDevice(this->Device);
      this->Device = nullptr;
    }
  }
  ~Internals() { this->Release(); }
};

RayScene::RayScene()
  : Internal(new Internals)
{
}

RayScene::~RayScene() = default;

bool RayScene::Build(const std::vector<float>& points, const std::vector<std::uint32_t>& triangles)
{
  this->Internal->Release();
  this->Error.clear();
  this->SceneSize = 0.0;
  this->NumberOfTriangles = 0;
  if (points.size() % 3 != 0 || triangles.size() % 3 != 0)
  {
    this->Error = "points and triangles must come in threes";
    return false;
  }
  const std::size_t nv = points.size() / 3;
  for (std::uint32_t id : triangles)
  {
    if (id >= nv)
    {
      this->Error = "a triangle refers to a vertex that does not exist";
      return false;
    }
  }
  for (float v : points)
  {
    if (!std::isfinite(v))
    {
      this->Error = "vertex coordinates contain NaN or Inf";
      return false;
    }
    // Embree's bounds arithmetic (single precision) overflows and aborts on larger ones.
    if (std::abs(v) > kMaxCoordinate)
    {
      this->Error = "vertex coordinates beyond +-1e12 cannot be ray traced (a coordinate is " +
        std::to_string(v) + ")";
      return false;
    }
  }
  Internals& in = *this->Internal;
  in.Device = rtcNewDevice("threads=1,verbose=0");
  if (!in.Device)
  {
    this->Error = "Embree: cannot create a device";
    return false;
  }
  in.Scene = rtcNewScene(in.Device);
  rtcSetSceneBuildQuality(in.Scene, RTC_BUILD_QUALITY_MEDIUM);
  // Watertight: rays through shared edges and vertices must not slip between triangles.
  rtcSetSceneFlags(in.Scene, RTC_SCENE_FLAG_ROBUST);
  if (!triangles.empty())
  {
    RTCGeometry geom = rtcNewGeometry(in.Device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), nv));
    std::uint32_t* t = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(geom,
      RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), triangles.size() / 3));
    if (!v || !t)
    {
      rtcReleaseGeometry(geom);
      this->Error = "Embree: cannot allocate buffers";
      in.Release();
      return false;
    }
    std::memcpy(v, points.data(), points.size() * sizeof(float));
    std::memcpy(t, triangles.data(), triangles.size() * sizeof(std::uint32_t));
    rtcCommitGeometry(geom);
    rtcAttachGeometry(in.Scene, geom);
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(in.Scene);
  if (rtcGetDeviceError(in.Device) != RTC_ERROR_NONE)
  {
    this->Error = "Embree: the scene could not be built";
    in.Release();
    return false;
  }
  Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 hi = -lo;
  for (std::size_t i = 0; i < nv; ++i)
  {
    const Vec3 p(points[3 * i], points[3 * i + 1], points[3 * i + 2]);
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  this->SceneSize = nv > 0 ? (hi - lo).norm() : 0.0;
  this->NumberOfTriangles = triangles.size() / 3;
  return true;
}

bool RayScene::Occluded(const Vec3& from, const Vec3& to, double margin) const
{
  if (!this->Internal->Scene || this->NumberOfTriangles == 0)
  {
    return false;
  }
  const Vec3 d = to - from;
  const double length = d.norm();
  if (!(length > 0) || !std::isfinite(length))
  {
    return false;
  }
  if (margin < 0)
  {
    margin = 1e-5 * this->SceneSize;
  }
  if (2 * margin >= length)
  {
    return false;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray;
  ray.org_x = static_cast<float>(from.x());
  ray.org_y = static_cast<float>(from.y());
  ray.org_z = static_cast<float>(from.z());
  ray.dir_x = static_cast<float>(d.x() / length);
  ray.dir_y = static_cast<float>(d.y() / length);
  ray.dir_z = static_cast<float>(d.z() / length);
  ray.tnear = static_cast<float>(margin);
  ray.tfar = std::isfinite(to.x()) ? static_cast<float>(length - margin)
                                   : std::numeric_limits<float>::infinity();
  ray.time = 0.0f;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
  rtcOccluded1(this->Internal->Scene, &context, &ray);
  return ray.tfar == -std::numeric_limits<float>::infinity();
}

RayScene::Hit RayScene::Intersect(
  const Vec3& origin, const Vec3& direction, double tnear, double tfar) const
{
  Hit result;
  if (!this->Internal->Scene || this->NumberOfTriangles == 0)
  {
    return result;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray.org_x = static_cast<float>(origin.x());
  rh.ray.org_y = static_cast<float>(origin.y());
  rh.ray.org_z = static_cast<float>(origin.z());
  rh.ray.dir_x = static_cast<float>(direction.x());
  rh.ray.dir_y = static_cast<float>(direction.y());
  rh.ray.dir_z = static_cast<float>(direction.z());
  rh.ray.tnear = static_cast<float>(tnear);
  rh.ray.tfar = static_cast<float>(std::min(tfar, 3e38));
  rh.ray.time = 0.0f;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(this->Internal->Scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
  {
    return result;
  }
  result.hit = true;
  result.t = rh.ray.tfar;
  result.triangle = rh.hit.primID;
  result.u = rh.hit.u;
  result.v = rh.hit.v;
  return result;
}

int TraceShadows(
  const RayScene& scene, const Vec3& p, const Vec3& n, const LightSet& lights, unsigned char* lit)
{
  const double offset = 1e-4 * scene.GetSceneSize();
  const Vec3 start = p + offset * n;
  int rays = 0;
  for (std::size_t k = 0; k < lights.size(); ++k)
  {
    const LightSource& light = lights[k];
    lit[k] = 1;
    // A light the surface faces away from, or whose cone misses the point, adds no diffuse or
    // specular term whatever the occlusion.
    const Vec3 toLight = lights.DirectionToLight(k, p);
    if (n.dot(toLight) <= 0.0 || lights.SpotFactor(k, toLight) == 0.0)
    {
      continue;
    }
    const Vec3 target = light.kind == LightSource::Kind::Directional
      ? Vec3(start + 2.0 * scene.GetSceneSize() * toLight)
      : light.position;
    lit[k] = scene.Occluded(start, target, 0.5 * offset) ? 0 : 1;
    ++rays;
  }
  return rays;
}
} // namespace catar
