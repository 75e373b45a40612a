// CatadioptricAR Core: Phong lighting for a non-central camera (the paper's section 3.6, eq. 12).
//
// The colour of a surface point p with unit normal n, seen from the viewer point v, is
//
//   I = Ke + Ga Ka + sum_k att_k spot_k ( La_k Ka + occ_k ( max(n.l_k, 0) Ld_k Kd
//                                                          + f_k max(r_k.e, 0)^sh Ls_k Ks ) )
//
// per colour channel, where l_k is the unit vector from p to light k (for a directional light,
// the direction the light comes from), r_k = 2 (n.l_k) n - l_k the reflected light direction,
// e = (v - p)/|v - p| the direction to the viewer, f_k = 1 when n.l_k > 0 and 0 otherwise,
// att_k = 1/(c + l d + q d^2) for lights with a position (d = distance to the light, 1 for
// directional lights), spot_k = max(-l_k.s_k, 0)^exponent inside the cone of a spotlight (axis
// s_k, half angle = cone angle) and 0 outside it (1 for other lights), and occ_k is 0 when
// something blocks the segment from p to light k (shadows), 1 otherwise. The result is clamped
// to [0, 1].
//
// The non-central part: the viewer is not a camera centre but v = the point's own reflection point
// on the mirror (for flat shading, the centroid's).
#ifndef catarLighting_h
#define catarLighting_h

#include "Types.h"

#include <initializer_list>
#include <string>
#include <vector>

namespace catar
{
/// A light, in world coordinates. Colours are already multiplied by the light's intensity.
struct LightSource
{
  enum class Kind
  {
    Directional, ///< from position towards focalPoint, no attenuation
    Point,       ///< at position, all directions
    Spot         ///< at position, cone around focalPoint - position
  };
  Kind kind = Kind::Spot;
  Vec3 position = Vec3(0, 0, 1);
  Vec3 focalPoint = Vec3(0, 0, 0);
  Vec3 ambient = Vec3(0, 0, 0);
  Vec3 diffuse = Vec3(1, 1, 1);
  Vec3 specular = Vec3(1, 1, 1);
  double coneAngle = 30.0;                ///< degrees, half angle of the spot cone
  double exponent = 1.0;                  ///< spot falloff exponent
  Vec3 attenuation = Vec3(1.0, 0.0, 0.0); ///< constant, linear, quadratic
};

/// Material colours (RGB in [0,1]) and shininess.
struct Material
{
  Vec3 ambient = Vec3(0.2, 0.2, 0.2);
  Vec3 diffuse = Vec3(0.8, 0.8, 0.8);
  Vec3 specular = Vec3(0.0, 0.0, 0.0);
  Vec3 emission = Vec3(0.0, 0.0, 0.0);
  double shininess = 1.0;
};

/// Unit vector from p towards the light (for a directional light, the direction it comes from),
/// and the distance to it (infinity for a directional light).
Vec3 DirectionToLight(const LightSource& light, const Vec3& p, double* distance = nullptr);

/// Why these lights, material, global ambient and material factors (ambient, diffuse, opacity)
/// cannot be shaded with: a NaN or infinite value (which would turn every colour black or
/// flat), naming which; "" when they can.
std::string ValidateLighting(const std::vector<LightSource>& lights, const Material& material,
  const Vec3& globalAmbient, double ambientFactor, double diffuseFactor, double opacity);

/// att_k: 1 / (c + l d + q d^2) for lights with a position, 1 for directional lights.
double Attenuation(const LightSource& light, double distance);

/// spot_k for the unit vector l from p to the light: 1 for non-spot lights; 0 outside the cone.
double SpotFactor(const LightSource& light, const Vec3& toLight);

/// x^e for x >= 0: by repeated squaring when e is a whole number up to 256 (Phong and spot
/// exponents mostly are; a few times faster than std::pow, within a few ulps of it), else std::pow.
double PhongPower(double x, double e);

/// Lights with what the equation needs per light computed once (the unit spot axis, the cosine of
/// the cone angle, the direction of a directional light), for shading many points.
class LightSet
{
public:
  LightSet() = default;
  LightSet(std::vector<LightSource> lights); // NOLINT: implicit, as a list of lights is one
  LightSet(std::initializer_list<LightSource> lights);

  std::size_t size() const { return this->Lights.size(); }
  bool empty() const { return this->Lights.empty(); }
  const LightSource& operator[](std::size_t k) const { return this->Lights[k]; }

  /// As DirectionToLight, SpotFactor and Attenuation for light k, from the precomputed values.
  Vec3 DirectionToLight(std::size_t k, const Vec3& p, double* distance = nullptr) const;
  double SpotFactor(std::size_t k, const Vec3& toLight) const;
  double Attenuation(std::size_t k, double distance) const;

private:
  void Prepare();
  struct Constants
  {
    Vec3 direction = Vec3(0, 0, 1); // directional light: unit vector towards it
    Vec3 axis = Vec3::Zero();       // spot with a cone: unit axis
    double cosCone = -1.0;          // spot with a cone: cosine of the half angle
    bool cone = false;              // spot whose cone limits it (angle < 90 and an axis)
  };
  std::vector<LightSource> Lights;
  std::vector<Constants> Prepared;
};

/// The colour of point p, unit normal n, seen from viewer point v (equation above). `lit`, when
/// not null, holds occ_k for each light (0: shadowed). With twoSided, n is flipped to face v.
Vec3 Shade(const Vec3& p, const Vec3& n, const Vec3& viewer, const LightSet& lights,
  const Material& material, const Vec3& globalAmbient, const unsigned char* lit = nullptr,
  bool twoSided = true);

/// How many points ShadeMany shades at once.
constexpr int kShadeLanes = 8;

/// Shade for `count` points (at most kShadeLanes; more are not shaded) side by side, each step for
/// every point before the next step, so that their square roots and divisions overlap instead of
/// waiting on each other: out[i] is exactly Shade(p[i], n[i], viewer[i], lights, materials[i],
/// globalAmbient, lit ? lit + i * lights.size() : nullptr, twoSided).
void ShadeMany(int count, const Vec3* p, const Vec3* n, const Vec3* viewer, const LightSet& lights,
  const Material* materials, const Vec3& globalAmbient, const unsigned char* lit, bool twoSided,
  Vec3* out);
} // namespace catar

#endif
