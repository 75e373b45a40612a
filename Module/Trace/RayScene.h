// CatadioptricAR Core: ray queries against a triangle mesh (Embree), for shadows and for the
// exact reference renderer.
//
// Build it once from world-space triangles (one mesh, or several kept apart: a hit says which);
// then Occluded() and Intersect() are thread-safe. Embree works in single precision: offsets
// (tnear) are relative to the scene's size. The Embree device is kept from one build to the next;
// SetBuildThreads chooses how many threads build the acceleration structure.
#ifndef catarRayScene_h
#define catarRayScene_h

#include "Types.h"

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace catar
{
class RayScene
{
public:
  RayScene();
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  /// The largest coordinate a scene may have (1e12, in any unit): Embree works in single
  /// precision and aborts on bounds that overflow it.
  static constexpr float kMaxCoordinate = 1e12f;

  /// Builds the acceleration structure. `points` holds x y z per vertex, `triangles` three vertex
  /// indices per triangle. Returns false (and says why in GetError()) on failure
  /// (ids out of range, NaN or Inf coordinates, coordinates beyond kMaxCoordinate); degenerate
  /// triangles are allowed (Embree skips them). An empty mesh builds an empty scene.
  bool Build(const std::vector<float>& points, const std::vector<std::uint32_t>& triangles);

  /// One mesh of a scene of several: `pointCount` points (x y z each) and `triangleCount`
  /// triangles (three indices into the mesh's own points each).
  struct MeshView
  {
    const float* points = nullptr;
    std::size_t pointCount = 0;
    const std::uint32_t* triangles = nullptr;
    std::size_t triangleCount = 0;
  };
  /// Builds one acceleration structure over several meshes, each kept as its own geometry: a
  /// hit's `mesh` is the index of the mesh it lies on, its `triangle` the index within that mesh.
  /// The same checks and failures as Build(points, triangles), by mesh.
  bool Build(const std::vector<MeshView>& meshes);

  ///@{
  /// A scene whose meshes' points change from frame to frame (set before Build): each mesh gets
  /// an acceleration structure of its own under a small one over the meshes (Embree's two-level
  /// scene), so that UpdatePoints refits a mesh's structure to its moved points in place of
  /// building it again. Off (the default): one structure over all the triangles.
  void SetDynamic(bool dynamic) { this->Dynamic = dynamic; }
  bool GetDynamic() const { return this->Dynamic; }
  ///@}

  /// For a dynamic scene built by Build(meshes): gives mesh `mesh` new point coordinates (as many
  /// as it was built with, x y z each; its triangles stay). Takes effect at Commit(). False (with
  /// GetError()) for a scene that is not dynamic, a mesh that does not exist, NaN, Inf or
  /// coordinates beyond kMaxCoordinate: the scene is then left as it was built or last committed
  /// (call Build again).
  bool UpdatePoints(std::size_t mesh, const float* points);
  /// Refits the acceleration structures of the meshes given new points since the last Build or
  /// Commit. False (with GetError()) when Embree fails: the scene is then empty.
  bool Commit();

  ///@{
  /// Threads that build the acceleration structure (Embree's own, TBB's workers): 1 (the default)
  /// builds on the calling thread alone; 0 uses every hardware thread. Takes effect at the next
  /// Build.
  void SetBuildThreads(int threads) { this->BuildThreads = threads < 0 ? 1 : threads; }
  int GetBuildThreads() const { return this->BuildThreads; }
  ///@}
  /// True when something lies on the open segment from `from` to `to`, ignoring the first and last
  /// `margin` (a length; by default 1e-5 of the scene's diagonal) of it.
  bool Occluded(const Vec3& from, const Vec3& to, double margin = -1.0) const;

  /// Nearest hit along origin + t direction (direction need not be unit) for t in (tnear, tfar).
  struct Hit
  {
    bool hit = false;
    double t = 0.0;
    std::uint32_t mesh = 0; ///< the mesh of Build(meshes) (0 for Build(points, triangles))
    std::uint32_t triangle = 0;
    double u = 0.0; ///< barycentric weight of the triangle's second vertex
    double v = 0.0; ///< barycentric weight of the third vertex
  };
  Hit Intersect(const Vec3& origin, const Vec3& direction, double tnear, double tfar) const;

  /// A ray for Intersect(n, rays, hits): single precision, as Embree traces.
  struct Ray
  {
    float origin[3];
    float direction[3];
  };
  /// The nearest hits of n rays for t in (0, infinity), traced together (Embree's ray streams:
  /// neighbouring rays, e.g. a tile of pixels, share their traversal): hits[i] = Intersect(
  /// rays[i].origin, rays[i].direction, 0, infinity), the same answers. `coherent`: the rays
  /// are neighbours (a hint).
  void Intersect(std::size_t n, const Ray* rays, Hit* hits, bool coherent = true) const;

  /// Diagonal of the scene's bounding box (0 when empty).
  double GetSceneSize() const { return this->SceneSize; }
  std::size_t GetNumberOfTriangles() const { return this->NumberOfTriangles; }
  const std::string& GetError() const { return this->Error; }

private:
  struct Internals;
  std::unique_ptr<Internals> Internal;
  double SceneSize = 0.0;
  std::size_t NumberOfTriangles = 0;
  int BuildThreads = 1;
  bool Dynamic = false;
  std::string Error;
};
} // namespace catar

#endif
