// Phong lighting (Module/Shading/Lighting.h) on single points: analytic checks of each term.
#include "Lighting.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace catar;

namespace
{
Vec3 RandomUnit(std::mt19937_64& rng)
{
  std::normal_distribution<double> n(0.0, 1.0);
  return Vec3(n(rng), n(rng), n(rng)).normalized();
}

LightSource Directional(const Vec3& towardsLight)
{
  LightSource l;
  l.kind = LightSource::Kind::Directional;
  l.position = towardsLight;
  l.focalPoint = Vec3::Zero();
  l.ambient = Vec3::Zero();
  return l;
}

Material DiffuseOnly(const Vec3& kd)
{
  Material m;
  m.ambient = Vec3::Zero();
  m.diffuse = kd;
  m.specular = Vec3::Zero();
  return m;
}
} // namespace

TEST(Lighting, DiffuseIsNDotLTimesTheColours)
{
  std::mt19937_64 rng(5);
  const Vec3 kd(0.9, 0.5, 0.2);
  for (int i = 0; i < 1000; ++i)
  {
    const Vec3 n = RandomUnit(rng);
    const Vec3 l = RandomUnit(rng);
    LightSource light = Directional(l);
    light.diffuse = Vec3(0.7, 1.0, 0.4);
    const Vec3 p = Vec3::Zero();
    const Vec3 viewer = p + n; // in front of the surface
    const Vec3 c = Shade(p, n, viewer, { light }, DiffuseOnly(kd), Vec3::Zero(), nullptr, false);
    const double nl = std::max(0.0, n.dot(l));
    EXPECT_NEAR(c.x(), std::min(1.0, nl * 0.7 * 0.9), 1e-12);
    EXPECT_NEAR(c.y(), std::min(1.0, nl * 1.0 * 0.5), 1e-12);
    EXPECT_NEAR(c.z(), std::min(1.0, nl * 0.4 * 0.2), 1e-12);
  }
}

TEST(Lighting, SpecularPeaksWhereTheReflectedLightMeetsTheViewer)
{
  // Surface at the origin, normal +z; point light up and to the left. The mirror direction of the
  // light about the normal is up and to the right; scan viewers around it.
  LightSource light;
  light.kind = LightSource::Kind::Point;
  light.position = Vec3(-1.0, 0.0, 2.0);
  light.ambient = Vec3::Zero();
  light.diffuse = Vec3::Zero();
  Material m;
  m.ambient = m.diffuse = Vec3::Zero();
  m.specular = Vec3(1, 1, 1);
  m.shininess = 40;
  const Vec3 n(0, 0, 1);
  const Vec3 l = light.position.normalized();
  const Vec3 mirrorDirection = 2 * n.dot(l) * n - l;
  const double peakAngle = std::atan2(mirrorDirection.x(), mirrorDirection.z());
  double best = -1, bestAngle = 0;
  for (int k = -300; k <= 300; ++k)
  {
    const double a = peakAngle + k * 0.002;
    const Vec3 viewer = 0.5 * Vec3(std::sin(a), 0.0, std::cos(a)); // at distance 0.5
    const double s = Shade(Vec3::Zero(), n, viewer, { light }, m, Vec3::Zero(), nullptr, false).x();
    if (s > best)
    {
      best = s;
      bestAngle = a;
    }
  }
  EXPECT_NEAR(bestAngle, peakAngle, 0.002 + 1e-12);
  EXPECT_NEAR(best, 1.0, 1e-9); // (r.e)^sh = 1 at the peak, Ls Ks = 1
  // Half-way falloff follows cos^shininess.
  const double a = peakAngle + 0.1;
  const Vec3 viewer(std::sin(a), 0.0, std::cos(a));
  EXPECT_NEAR(Shade(Vec3::Zero(), n, viewer, { light }, m, Vec3::Zero(), nullptr, false).x(),
    std::pow(std::cos(0.1), 40), 1e-9);
}

TEST(Lighting, OnlyAmbientBehindTheSurfaceOrOutsideTheCone)
{
  Material m;
  m.ambient = Vec3(0.3, 0.3, 0.3);
  m.diffuse = Vec3(1, 1, 1);
  m.specular = Vec3(1, 1, 1);
  m.shininess = 5;
  const Vec3 ga(0.1, 0.2, 0.3);
  LightSource spot;
  spot.kind = LightSource::Kind::Spot;
  spot.position = Vec3(0, 0, 1);
  spot.focalPoint = Vec3(0, 0, 0);
  spot.coneAngle = 20;
  spot.exponent = 2;
  spot.ambient = Vec3(0.5, 0.5, 0.5);
  const Vec3 n(0, 0, 1);
  const Vec3 viewer(0.2, 0.1, 0.5);
  // Light behind the surface (normal facing away): ambient terms only (global + light's).
  {
    const Vec3 c = Shade(Vec3::Zero(), -n, viewer, { spot }, m, ga, nullptr, false);
    const double spotFactor = 1.0; // on the axis
    EXPECT_NEAR(c.x(), 0.1 * 0.3 + spotFactor * 0.5 * 0.3, 1e-12);
    EXPECT_NEAR(c.z(), 0.3 * 0.3 + spotFactor * 0.5 * 0.3, 1e-12);
  }
  // Outside the cone (point at 45 degrees off the axis): global ambient only.
  {
    const Vec3 p(1.0, 0.0, 0.0);
    const Vec3 c = Shade(p, n, viewer, { spot }, m, ga, nullptr, false);
    EXPECT_NEAR(c.x(), 0.1 * 0.3, 1e-12);
    EXPECT_NEAR(c.y(), 0.2 * 0.3, 1e-12);
  }
  // Inside the cone, lit: more than ambient; shadowed (occ = 0): ambient only.
  {
    const Vec3 p(0.1, 0.0, 0.0);
    const unsigned char shadowed = 0;
    const Vec3 lit = Shade(p, n, viewer, { spot }, m, ga, nullptr, false);
    const Vec3 dark = Shade(p, n, viewer, { spot }, m, ga, &shadowed, false);
    const Vec3 l = (spot.position - p).normalized();
    const double s = std::pow(l.dot(Vec3(0, 0, 1)), 2);
    EXPECT_NEAR(dark.x(), 0.1 * 0.3 + s * 0.5 * 0.3, 1e-12);
    EXPECT_GT(lit.x(), dark.x() + 0.1);
  }
}

TEST(Lighting, AttenuationObeysItsFormula)
{
  LightSource light;
  light.kind = LightSource::Kind::Point;
  light.ambient = Vec3::Zero();
  light.attenuation = Vec3(0.5, 0.3, 0.2);
  const Material m = DiffuseOnly(Vec3(1, 1, 1));
  const Vec3 n(0, 0, 1);
  for (double d : { 0.5, 1.0, 2.0, 7.0 })
  {
    light.position = Vec3(0, 0, d);
    const double expected = 1.0 / (0.5 + 0.3 * d + 0.2 * d * d);
    EXPECT_NEAR(Attenuation(light, d), expected, 1e-15);
    const double c =
      Shade(Vec3::Zero(), n, Vec3(0, 0, 0.1), { light }, m, Vec3::Zero(), nullptr, false).x();
    EXPECT_NEAR(c, std::min(1.0, expected), 1e-12) << d;
  }
  // Directional lights do not attenuate.
  LightSource sun = Directional(Vec3(0, 0, 1));
  sun.attenuation = light.attenuation;
  EXPECT_EQ(Attenuation(sun, 100.0), 1.0);
}

TEST(Lighting, SpotExponentAndTwoSidedLighting)
{
  LightSource spot;
  spot.kind = LightSource::Kind::Spot;
  spot.position = Vec3(0, 0, 1);
  spot.focalPoint = Vec3(0, 0, 0);
  spot.coneAngle = 40;
  spot.exponent = 3;
  const Vec3 p(0.3, 0, 0);
  const Vec3 l = (spot.position - p).normalized();
  EXPECT_NEAR(SpotFactor(spot, l), std::pow(l.z(), 3), 1e-15);
  spot.coneAngle = 10;
  EXPECT_EQ(SpotFactor(spot, l), 0.0);
  // Two-sided: a surface whose normal points away from the viewer is lit as its other side.
  LightSource sun = Directional(Vec3(0, 0, 1));
  const Material m = DiffuseOnly(Vec3(1, 1, 1));
  const Vec3 viewer(0, 0, 1);
  const double oneSided =
    Shade(Vec3::Zero(), Vec3(0, 0, -1), viewer, { sun }, m, Vec3::Zero(), nullptr, false).x();
  const double twoSided =
    Shade(Vec3::Zero(), Vec3(0, 0, -1), viewer, { sun }, m, Vec3::Zero(), nullptr, true).x();
  EXPECT_EQ(oneSided, 0.0);
  EXPECT_NEAR(twoSided, 1.0, 1e-12);
}

TEST(Lighting, ShadeManyIsShadeForEachPoint)
{
  // Eight points side by side give each point's Shade exactly: lights of every kind (spot
  // exponents whole and not, a narrow cone that leaves some points dark, attenuation), materials
  // that differ per point (shininess whole, fractional, huge, negative), shadow flags per point
  // and light, one- and two-sided, and fewer points than lanes.
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto randomVec = [&](double scale) -> Vec3 { return Vec3(u(rng), u(rng), u(rng)) * scale; };
  std::vector<LightSource> sources;
  for (int k = 0; k < 4; ++k)
  {
    LightSource l;
    l.kind = k == 0 ? LightSource::Kind::Directional
      : k == 1      ? LightSource::Kind::Point
                    : LightSource::Kind::Spot;
    l.position = Vec3(0, 0, 2) + randomVec(0.5);
    l.focalPoint = randomVec(0.2);
    l.ambient = randomVec(0.1).cwiseAbs();
    l.diffuse = randomVec(1.0).cwiseAbs();
    l.specular = randomVec(1.0).cwiseAbs();
    l.coneAngle = k == 3 ? 8.0 : 50.0;
    l.exponent = k == 3 ? 2.5 : 3.0;
    l.attenuation = Vec3(1.0, 0.3 * (k % 2), 0.1 * (k % 2));
    sources.push_back(l);
  }
  const LightSet lights(sources);
  const Vec3 ga(0.1, 0.2, 0.05);
  const double shininess[] = { 1.0, 7.5, 300.0, -1.0, 20.0, 0.0, 2.0, 64.0 };
  for (const bool twoSided : { false, true })
  {
    for (const int count : { kShadeLanes, 3 })
    {
      for (int trial = 0; trial < 50; ++trial)
      {
        Vec3 p[kShadeLanes], n[kShadeLanes], viewer[kShadeLanes], out[kShadeLanes];
        Material m[kShadeLanes];
        unsigned char lit[kShadeLanes * 4];
        for (int i = 0; i < kShadeLanes; ++i)
        {
          p[i] = randomVec(0.3);
          n[i] = RandomUnit(rng);
          viewer[i] = i == 5 ? p[i] : Vec3(0, 0, -1) + randomVec(0.1); // i = 5: at the point
          m[i].ambient = randomVec(0.3).cwiseAbs();
          m[i].diffuse = randomVec(1.0).cwiseAbs();
          m[i].specular = randomVec(1.0).cwiseAbs();
          m[i].emission = randomVec(0.05).cwiseAbs();
          m[i].shininess = shininess[i];
          for (int k = 0; k < 4; ++k)
          {
            lit[i * 4 + k] = (rng() % 3) != 0 ? 1 : 0;
          }
        }
        for (const bool shadows : { false, true })
        {
          ShadeMany(count, p, n, viewer, lights, m, ga, shadows ? lit : nullptr, twoSided, out);
          for (int i = 0; i < count; ++i)
          {
            const Vec3 one = Shade(
              p[i], n[i], viewer[i], lights, m[i], ga, shadows ? lit + i * 4 : nullptr, twoSided);
            for (int c = 0; c < 3; ++c)
            {
              ASSERT_EQ(out[i][c], one[c])
                << "point " << i << " of " << count << ", trial " << trial;
            }
          }
        }
      }
    }
  }
}
