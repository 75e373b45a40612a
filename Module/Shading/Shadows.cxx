#include "Shadows.h"

#include "RayScene.h"

namespace catar
{
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
