// CatadioptricAR Core: shadows: which lights a surface point sees past the scene (RayScene's
// occlusion queries toward each light).
#ifndef catarShadows_h
#define catarShadows_h

#include "Lighting.h"

namespace catar
{
class RayScene;

/// Shadows at surface point p with normal n (the side the lights are seen from): lit[k] = 0 when
/// the segment from p (moved off the surface by 1e-4 of the scene size) to light k (or far
/// along a directional light) is blocked by the scene, else 1. Lights that cannot light p anyway
/// (n . l <= 0, or a spotlight cone that misses p) are not traced and get 1. Returns the number
/// of rays traced.
int TraceShadows(
  const RayScene& scene, const Vec3& p, const Vec3& n, const LightSet& lights, unsigned char* lit);
} // namespace catar

#endif
