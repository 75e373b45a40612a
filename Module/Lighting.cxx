#include "Lighting.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace catar
{
Vec3 DirectionToLight(const LightSource& light, const Vec3& p, double* distance)
{
  if (light.kind == LightSource::Kind::Directional)
  {
    if (distance)
    {
      *distance = std::numeric_limits<double>::infinity();
    }
    const Vec3 d = light.position - light.focalPoint;
    const double n = d.norm();
    return n > 0 ? Vec3(d / n) : Vec3(0, 0, 1);
  }
  const Vec3 d = light.position - p;
  const double n = d.norm();
  if (distance)
  {
    *distance = n;
  }
  return n > 0 ? Vec3(d / n) : Vec3(0, 0, 0);
}

double Attenuation(const LightSource& light, double distance)
{
  if (light.kind == LightSource::Kind::Directional || !std::isfinite(distance))
  {
    return 1.0;
  }
  const Vec3& a = light.attenuation;
  const double denominator = a.x() + distance * (a.y() + distance * a.z());
  return denominator > 0 ? 1.0 / denominator : 1.0;
}

double SpotFactor(const LightSource& light, const Vec3& toLight)
{
  if (light.kind != LightSource::Kind::Spot || light.coneAngle >= 90.0)
  {
    return 1.0;
  }
  const Vec3 axis = light.focalPoint - light.position;
  const double axisNorm = axis.norm();
  if (!(axisNorm > 0))
  {
    return 1.0;
  }
  const double c = -toLight.dot(axis) / axisNorm; // cosine between the axis and light -> point
  const double limit = std::cos(light.coneAngle * M_PI / 180.0);
  if (c < limit)
  {
    return 0.0;
  }
  return light.exponent == 0.0 ? 1.0 : std::pow(std::max(c, 0.0), light.exponent);
}

Vec3 Shade(const Vec3& p, const Vec3& normal, const Vec3& viewer,
  const std::vector<LightSource>& lights, const Material& m, const Vec3& globalAmbient,
  const unsigned char* lit, bool twoSided)
{
  Vec3 n = normal;
  Vec3 e = viewer - p;
  const double en = e.norm();
  e = en > 0 ? Vec3(e / en) : Vec3(n);
  if (twoSided && n.dot(e) < 0)
  {
    n = -n;
  }
  Vec3 color = m.emission + globalAmbient.cwiseProduct(m.ambient);
  for (size_t k = 0; k < lights.size(); ++k)
  {
    const LightSource& light = lights[k];
    double distance = 0;
    const Vec3 l = DirectionToLight(light, p, &distance);
    const double factor = Attenuation(light, distance) * SpotFactor(light, l);
    if (factor == 0.0)
    {
      continue;
    }
    Vec3 term = light.ambient.cwiseProduct(m.ambient);
    const double nl = n.dot(l);
    if (nl > 0 && (!lit || lit[k]))
    {
      term += nl * light.diffuse.cwiseProduct(m.diffuse);
      const Vec3 r = 2.0 * nl * n - l;
      const double re = r.dot(e);
      if (re > 0 && m.shininess >= 0)
      {
        term += std::pow(re, m.shininess) * light.specular.cwiseProduct(m.specular);
      }
    }
    color += factor * term;
  }
  return color.cwiseMax(0.0).cwiseMin(1.0);
}
} // namespace catar
