#include "Lighting.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace catar
{
Vec3 DirectionToLight(const LightSource& light, const Vec3& p, double* distance)
{
  return LightSet({ light }).DirectionToLight(0, p, distance);
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
  return LightSet({ light }).SpotFactor(0, toLight);
}

double PhongPower(double x, double e)
{
  if (e >= 0.0 && e <= 256.0 && e == static_cast<double>(static_cast<int>(e)))
  {
    int n = static_cast<int>(e);
    double result = 1.0;
    double square = x;
    while (n)
    {
      if (n & 1)
      {
        result *= square;
      }
      n >>= 1;
      if (n)
      {
        square *= square;
      }
    }
    return result;
  }
  return std::pow(x, e);
}

LightSet::LightSet(std::vector<LightSource> lights)
  : Lights(std::move(lights))
{
  this->Prepare();
}

LightSet::LightSet(std::initializer_list<LightSource> lights)
  : Lights(lights)
{
  this->Prepare();
}

void LightSet::Prepare()
{
  this->Prepared.assign(this->Lights.size(), Constants());
  for (std::size_t k = 0; k < this->Lights.size(); ++k)
  {
    const LightSource& light = this->Lights[k];
    Constants& c = this->Prepared[k];
    const Vec3 d = light.position - light.focalPoint;
    const double dn = d.norm();
    if (dn > 0)
    {
      c.direction = d / dn;
    }
    if (light.kind == LightSource::Kind::Spot && light.coneAngle < 90.0 && dn > 0)
    {
      c.cone = true;
      c.axis = -c.direction; // from the light towards its focal point
      c.cosCone = std::cos(light.coneAngle * M_PI / 180.0);
    }
  }
}

Vec3 LightSet::DirectionToLight(std::size_t k, const Vec3& p, double* distance) const
{
  const LightSource& light = this->Lights[k];
  if (light.kind == LightSource::Kind::Directional)
  {
    if (distance)
    {
      *distance = std::numeric_limits<double>::infinity();
    }
    return this->Prepared[k].direction;
  }
  const Vec3 d = light.position - p;
  const double n = d.norm();
  if (distance)
  {
    *distance = n;
  }
  return n > 0 ? Vec3(d / n) : Vec3(0, 0, 0);
}

double LightSet::SpotFactor(std::size_t k, const Vec3& toLight) const
{
  const Constants& c = this->Prepared[k];
  if (!c.cone)
  {
    return 1.0;
  }
  const double cosine = -toLight.dot(c.axis); // between the axis and light -> point
  if (cosine < c.cosCone)
  {
    return 0.0;
  }
  const double e = this->Lights[k].exponent;
  return e == 0.0 ? 1.0 : PhongPower(std::max(cosine, 0.0), e);
}

double LightSet::Attenuation(std::size_t k, double distance) const
{
  return catar::Attenuation(this->Lights[k], distance);
}

Vec3 Shade(const Vec3& p, const Vec3& normal, const Vec3& viewer, const LightSet& lights,
  const Material& m, const Vec3& globalAmbient, const unsigned char* lit, bool twoSided)
{
  Vec3 color;
  ShadeMany(1, &p, &normal, &viewer, lights, &m, globalAmbient, lit, twoSided, &color);
  return color;
}

void ShadeMany(int count, const Vec3* p, const Vec3* normal, const Vec3* viewer,
  const LightSet& lights, const Material* materials, const Vec3& globalAmbient,
  const unsigned char* lit, bool twoSided, Vec3* out)
{
  constexpr int W = kShadeLanes;
  count = std::min(count, W);
  const std::size_t nLights = lights.size();
  // Each loop below runs one step for every point: the points' steps are independent.
  Vec3 n[W], e[W], color[W];
  for (int i = 0; i < count; ++i)
  {
    const Material& m = materials[i];
    n[i] = normal[i];
    const Vec3 toViewer = viewer[i] - p[i];
    const double en = toViewer.norm();
    e[i] = en > 0 ? Vec3(toViewer / en) : Vec3(n[i]);
    if (twoSided && n[i].dot(e[i]) < 0)
    {
      n[i] = -n[i];
    }
    color[i] = m.emission + globalAmbient.cwiseProduct(m.ambient);
  }
  for (std::size_t k = 0; k < nLights; ++k)
  {
    const LightSource& light = lights[k];
    Vec3 l[W];
    double distance[W], spot[W];
    for (int i = 0; i < count; ++i)
    {
      distance[i] = 0;
      l[i] = lights.DirectionToLight(k, p[i], &distance[i]);
    }
    for (int i = 0; i < count; ++i)
    {
      spot[i] = lights.SpotFactor(k, l[i]);
    }
    for (int i = 0; i < count; ++i)
    {
      if (spot[i] == 0.0)
      {
        continue;
      }
      const double factor = lights.Attenuation(k, distance[i]) * spot[i];
      if (factor == 0.0)
      {
        continue;
      }
      const Material& m = materials[i];
      Vec3 term = light.ambient.cwiseProduct(m.ambient);
      const double nl = n[i].dot(l[i]);
      if (nl > 0 && (!lit || lit[i * nLights + k]))
      {
        term += nl * light.diffuse.cwiseProduct(m.diffuse);
        const Vec3 r = 2.0 * nl * n[i] - l[i];
        const double re = r.dot(e[i]);
        if (re > 0 && m.shininess >= 0)
        {
          term += PhongPower(re, m.shininess) * light.specular.cwiseProduct(m.specular);
        }
      }
      color[i] += factor * term;
    }
  }
  for (int i = 0; i < count; ++i)
  {
    out[i] = color[i].cwiseMax(0.0).cwiseMin(1.0);
  }
}
std::string ValidateLighting(const std::vector<LightSource>& lights, const Material& material,
  const Vec3& globalAmbient, double ambientFactor, double diffuseFactor, double opacity)
{
  for (std::size_t k = 0; k < lights.size(); ++k)
  {
    const LightSource& l = lights[k];
    if (!(l.position.allFinite() && l.focalPoint.allFinite() && l.ambient.allFinite() &&
          l.diffuse.allFinite() && l.specular.allFinite() && std::isfinite(l.coneAngle) &&
          std::isfinite(l.exponent) && l.attenuation.allFinite()))
    {
      return "light " + std::to_string(k) +
        " has a NaN or infinite position, focal point, colour, intensity, cone angle, exponent "
        "or attenuation";
    }
  }
  if (!(material.ambient.allFinite() && material.diffuse.allFinite() &&
        material.specular.allFinite() && material.emission.allFinite() &&
        std::isfinite(material.shininess) && std::isfinite(ambientFactor) &&
        std::isfinite(diffuseFactor) && std::isfinite(opacity)))
  {
    return "the material (colours, ambient, diffuse, specular, specular power, emission or "
           "opacity) has a NaN or infinite value";
  }
  if (!globalAmbient.allFinite())
  {
    return "the global ambient colour has a NaN or infinite value";
  }
  return "";
}
} // namespace catar
