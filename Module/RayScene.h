// CatadioptricAR Core: ray queries against a triangle mesh (Embree), for shadows and for the
// exact reference renderer.
//
// Build it once from world-space triangles; then Occluded() and Intersect() are thread-safe.
// Embree works in single precision: offsets (tnear) are relative to the scene's size.
#ifndef catarRayScene_h
#define catarRayScene_h

#include "CameraModel.h"
#include "Lighting.h"

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

  /// True when something lies on the open segment from `from` to `to`, ignoring the first and last
  /// `margin` (a length; by default 1e-5 of the scene's diagonal) of it.
  bool Occluded(const Vec3& from, const Vec3& to, double margin = -1.0) const;

  /// Nearest hit along origin + t direction (direction need not be unit) for t in (tnear, tfar).
  struct Hit
  {
    bool hit = false;
    double t = 0.0;
    std::uint32_t triangle = 0;
    double u = 0.0; ///< barycentric weight of the triangle's second vertex
    double v = 0.0; ///< barycentric weight of the third vertex
  };
  Hit Intersect(const Vec3& origin, const Vec3& direction, double tnear, double tfar) const;

  /// Diagonal of the scene's bounding box (0 when empty).
  double GetSceneSize() const { return this->SceneSize; }
  std::size_t GetNumberOfTriangles() const { return this->NumberOfTriangles; }
  const std::string& GetError() const { return this->Error; }

private:
  struct Internals;
  std::unique_ptr<Internals> Internal;
  double SceneSize = 0.0;
  std::size_t NumberOfTriangles = 0;
  std::string Error;
};

/// Shadows at surface point p with normal n (the side the lights are seen from): lit[k] = 0 when
/// the segment from p (moved off the surface by 1e-4 of the scene size) to light k (or far
/// along a directional light) is blocked by the scene, else 1. Lights that cannot light p anyway
/// (n . l <= 0, or a spotlight cone that misses p) are not traced and get 1. Returns the number
/// of rays traced.
int TraceShadows(
  const RayScene& scene, const Vec3& p, const Vec3& n, const LightSet& lights, unsigned char* lit);
} // namespace catar

#endif
