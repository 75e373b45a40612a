#include "RayScene.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace catar
{
struct RayScene::Internals
{
  RTCDevice Device = nullptr;
  int DeviceThreads = -1; // the threads the device was made with
  RTCScene Scene = nullptr;
  // Per mesh of the last Build: its points and triangles, and its points' bounds.
  struct Mesh
  {
    std::size_t points = 0;
    std::size_t triangles = 0;
    Vec3 lo, hi;
  };
  std::vector<Mesh> Meshes;

  // The diagonal of the meshes' bounds.
  double Size() const
  {
    Vec3 lo = Vec3::Constant(std::numeric_limits<double>::infinity());
    Vec3 hi = -lo;
    for (const Mesh& m : this->Meshes)
    {
      if (m.points > 0)
      {
        lo = lo.cwiseMin(m.lo);
        hi = hi.cwiseMax(m.hi);
      }
    }
    return lo.x() <= hi.x() ? (hi - lo).norm() : 0.0;
  }

  void ReleaseScene()
  {
    if (this->Scene)
    {
      rtcReleaseScene(this->Scene);
      this->Scene = nullptr;
    }
    this->Meshes.clear();
  }
  void Release()
  {
    this->ReleaseScene();
    if (this->Device)
    {
      rtcReleaseDevice(this->Device);
      this->Device = nullptr;
    }
  }
  // The device, made again only when the number of build threads changes.
  bool Prepare(int threads)
  {
    this->ReleaseScene();
    if (this->Device && this->DeviceThreads == threads)
    {
      return true;
    }
    this->Release();
    const std::string config = "threads=" + std::to_string(threads) + ",verbose=0";
    this->Device = rtcNewDevice(config.c_str());
    this->DeviceThreads = threads;
    return this->Device != nullptr;
  }
  ~Internals() { this->Release(); }
};

namespace
{
// The hit Embree left in rh (no hit: a default Hit).
RayScene::Hit HitOf(const RTCRayHit& rh)
{
  RayScene::Hit h;
  if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID)
  {
    h.hit = true;
    h.t = rh.ray.tfar;
    h.mesh = rh.hit.geomID;
    h.triangle = rh.hit.primID;
    h.u = rh.hit.u;
    h.v = rh.hit.v;
  }
  return h;
}

// Finite points within kMaxCoordinate, and their bounds; else false with `error`.
bool CheckPoints(const float* points, std::size_t n, Vec3& lo, Vec3& hi, std::string& error)
{
  lo = Vec3::Constant(std::numeric_limits<double>::infinity());
  hi = -lo;
  for (std::size_t i = 0; i < n; ++i)
  {
    const float* p = points + 3 * i;
    for (int k = 0; k < 3; ++k)
    {
      if (!std::isfinite(p[k]))
      {
        error = "vertex coordinates contain NaN or Inf";
        return false;
      }
      // Embree's bounds arithmetic (single precision) overflows and aborts on larger ones.
      if (std::abs(p[k]) > RayScene::kMaxCoordinate)
      {
        error = "vertex coordinates beyond +-1e12 cannot be ray traced (a coordinate is " +
          std::to_string(p[k]) + ")";
        return false;
      }
    }
    const Vec3 q(p[0], p[1], p[2]);
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  return true;
}
} // namespace

RayScene::RayScene()
  : Internal(new Internals)
{
}

RayScene::~RayScene() = default;

bool RayScene::Build(const std::vector<float>& points, const std::vector<std::uint32_t>& triangles)
{
  if (points.size() % 3 != 0 || triangles.size() % 3 != 0)
  {
    this->Internal->ReleaseScene();
    this->Error = "points and triangles must come in threes";
    this->SceneSize = 0.0;
    this->NumberOfTriangles = 0;
    return false;
  }
  MeshView mesh;
  mesh.points = points.data();
  mesh.pointCount = points.size() / 3;
  mesh.triangles = triangles.data();
  mesh.triangleCount = triangles.size() / 3;
  return this->Build(std::vector<MeshView>{ mesh });
}

bool RayScene::Build(const std::vector<MeshView>& meshes)
{
  Internals& in = *this->Internal;
  in.ReleaseScene();
  this->Error.clear();
  this->SceneSize = 0.0;
  this->NumberOfTriangles = 0;
  std::size_t triangleCount = 0;
  std::vector<Internals::Mesh> info(meshes.size());
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    const MeshView& mesh = meshes[m];
    const std::size_t nv = mesh.pointCount;
    for (std::size_t i = 0; i < 3 * mesh.triangleCount; ++i)
    {
      if (mesh.triangles[i] >= nv)
      {
        this->Error = "a triangle refers to a vertex that does not exist";
        return false;
      }
    }
    if (!CheckPoints(mesh.points, nv, info[m].lo, info[m].hi, this->Error))
    {
      return false;
    }
    info[m].points = nv;
    info[m].triangles = mesh.triangleCount;
    triangleCount += mesh.triangleCount;
  }
  if (meshes.size() > std::numeric_limits<std::uint32_t>::max() / 2)
  {
    this->Error = "too many meshes";
    return false;
  }
  if (!in.Prepare(this->BuildThreads))
  {
    this->Error = "Embree: cannot create a device";
    return false;
  }
  in.Scene = rtcNewScene(in.Device);
  // Dynamic: the two-level scene, where each mesh's structure (built as the medium quality's,
  // refitted when its points move) is its own.
  rtcSetSceneBuildQuality(
    in.Scene, this->Dynamic ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_MEDIUM);
  // Watertight: rays through shared edges and vertices must not slip between triangles.
  rtcSetSceneFlags(in.Scene,
    this->Dynamic ? RTC_SCENE_FLAG_ROBUST | RTC_SCENE_FLAG_DYNAMIC : RTC_SCENE_FLAG_ROBUST);
  for (std::size_t m = 0; m < meshes.size(); ++m)
  {
    const MeshView& mesh = meshes[m];
    if (mesh.triangleCount == 0)
    {
      continue; // geometry ids are the meshes' indices: empty ones leave theirs unused
    }
    RTCGeometry geom = rtcNewGeometry(in.Device, RTC_GEOMETRY_TYPE_TRIANGLE);
    float* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.pointCount));
    std::uint32_t* t = static_cast<std::uint32_t*>(rtcSetNewGeometryBuffer(geom,
      RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(std::uint32_t), mesh.triangleCount));
    if (!v || !t)
    {
      rtcReleaseGeometry(geom);
      this->Error = "Embree: cannot allocate buffers";
      in.ReleaseScene();
      return false;
    }
    std::memcpy(v, mesh.points, 3 * mesh.pointCount * sizeof(float));
    std::memcpy(t, mesh.triangles, 3 * mesh.triangleCount * sizeof(std::uint32_t));
    if (this->Dynamic)
    {
      rtcSetGeometryBuildQuality(geom, RTC_BUILD_QUALITY_REFIT);
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(in.Scene, geom, static_cast<unsigned int>(m));
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(in.Scene);
  if (rtcGetDeviceError(in.Device) != RTC_ERROR_NONE)
  {
    this->Error = "Embree: the scene could not be built";
    in.ReleaseScene();
    return false;
  }
  in.Meshes = std::move(info);
  this->SceneSize = in.Size();
  this->NumberOfTriangles = triangleCount;
  return true;
}

bool RayScene::UpdatePoints(std::size_t mesh, const float* points)
{
  Internals& in = *this->Internal;
  this->Error.clear();
  if (!this->Dynamic || !in.Scene || mesh >= in.Meshes.size())
  {
    this->Error = "only the meshes of a dynamic scene can be given new points";
    return false;
  }
  Internals::Mesh& info = in.Meshes[mesh];
  Vec3 lo, hi;
  if (!CheckPoints(points, info.points, lo, hi, this->Error))
  {
    return false;
  }
  info.lo = lo;
  info.hi = hi;
  if (info.triangles == 0)
  {
    return true; // no geometry: only the bounds
  }
  RTCGeometry geom = rtcGetGeometry(in.Scene, static_cast<unsigned int>(mesh));
  float* v =
    geom ? static_cast<float*>(rtcGetGeometryBufferData(geom, RTC_BUFFER_TYPE_VERTEX, 0)) : nullptr;
  if (!v)
  {
    this->Error = "Embree: no vertex buffer to update";
    return false;
  }
  std::memcpy(v, points, 3 * info.points * sizeof(float));
  rtcUpdateGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0);
  rtcCommitGeometry(geom);
  return true;
}

bool RayScene::Commit()
{
  Internals& in = *this->Internal;
  this->Error.clear();
  if (!in.Scene)
  {
    this->Error = "no scene to commit";
    return false;
  }
  rtcCommitScene(in.Scene);
  if (rtcGetDeviceError(in.Device) != RTC_ERROR_NONE)
  {
    this->Error = "Embree: the scene could not be refitted";
    in.ReleaseScene();
    this->SceneSize = 0.0;
    this->NumberOfTriangles = 0;
    return false;
  }
  this->SceneSize = in.Size();
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
  return HitOf(rh);
}

void RayScene::Intersect(std::size_t n, const Ray* rays, Hit* hits, bool coherent) const
{
  if (!this->Internal->Scene || this->NumberOfTriangles == 0)
  {
    std::fill_n(hits, n, Hit());
    return;
  }
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags =
    coherent ? RTC_INTERSECT_CONTEXT_FLAG_COHERENT : RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT;
  constexpr std::size_t kChunk = 64;
  RTCRayHit stream[kChunk];
  for (std::size_t first = 0; first < n; first += kChunk)
  {
    const std::size_t m = std::min(kChunk, n - first);
    for (std::size_t i = 0; i < m; ++i)
    {
      const Ray& r = rays[first + i];
      RTCRayHit& rh = stream[i];
      rh.ray.org_x = r.origin[0];
      rh.ray.org_y = r.origin[1];
      rh.ray.org_z = r.origin[2];
      rh.ray.dir_x = r.direction[0];
      rh.ray.dir_y = r.direction[1];
      rh.ray.dir_z = r.direction[2];
      rh.ray.tnear = 0.0f;
      rh.ray.tfar = std::numeric_limits<float>::infinity();
      rh.ray.time = 0.0f;
      rh.ray.mask = 0xFFFFFFFFu;
      rh.ray.id = static_cast<unsigned int>(i);
      rh.ray.flags = 0;
      rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
      rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect1M(
      this->Internal->Scene, &context, stream, static_cast<unsigned int>(m), sizeof(RTCRayHit));
    for (std::size_t i = 0; i < m; ++i)
    {
      hits[first + i] = HitOf(stream[i]);
    }
  }
}
} // namespace catar
