#include "Lighting.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

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
  Vec3 n = normal;
  Vec3 e = viewer - p;
  const double en = e.norm();
  e = en > 0 ? Vec3(e / en) : Vec3(n);
  if (twoSided && n.dot(e) < 0)
  {
    n = -n;
  }
  Vec3 color = m.emission + globalAmbient.cwiseProduct(m.ambient);
  for (std::size_t k = 0; k < lights.size(); ++k)
  {
    const LightSource& light = lights[k];
    double distance = 0;
    const Vec3 l = lights.DirectionToLight(k, p, &distance);
    const double spot = lights.SpotFactor(k, l);
    if (spot == 0.0)
    {
      continue;
    }
    const double factor = lights.Attenuation(k, distance) * spot;
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
        term += PhongPower(re, m.shininess) * light.specular.cwiseProduct(m.specular);
      }
    }
    color += factor * term;
  }
  return color.cwiseMax(0.0).cwiseMin(1.0);
}
} // namespace catar
