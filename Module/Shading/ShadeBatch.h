// CatadioptricAR Core: many points shaded a batch at a time (Lighting.h's ShadeMany: their square
// roots and divisions overlap), each written as RGBA bytes: what a lighting stage runs per thread.
#ifndef catarShadeBatch_h
#define catarShadeBatch_h

#include "Lighting.h"

#include <algorithm>
#include <vector>

namespace catar
{
class RayScene;

/// A mesh's material as the lighting stage uses it: the Phong material, the factors that scale a
/// base colour into its ambient and diffuse colours, and the opacity.
struct ShadingMaterial
{
  Material material;
  double ambientK = 1.0;
  double diffuseK = 1.0;
  double opacity = 1.0;
};

/// ValidateLighting for the default material and each of materials (the error names the material:
/// "material 2: ..."); "" when every one can be shaded with.
std::string ValidateShading(const std::vector<LightSource>& lights, const ShadingMaterial& defaults,
  const std::vector<ShadingMaterial>& materials, const Vec3& globalAmbient);

/// The byte of a colour channel in [0, 1] (clamped): rounded to nearest, halves up, as
/// std::lround does for these values (without a library call: 255 v + 0.5 is exact for every v
/// in [1/510, 1]).
inline unsigned char ColourByte(double v)
{
  return static_cast<unsigned char>(255.0 * std::min(1.0, std::max(0.0, v)) + 0.5);
}

/// Points shaded kShadeLanes at a time, each with the RGBA bytes it writes. Not thread-safe: one
/// per thread. The batch left at destruction is shaded then.
class ShadeBatch
{
public:
  /// The settings of one run: the shade of a point is Shade(p, n (turned to the viewer when
  /// two-sided), viewer, lights, material with ambient and diffuse from the base colour when
  /// there is one, globalAmbient, shadow flags).
  struct Settings
  {
    const LightSet* lights = nullptr;
    ShadingMaterial defaults;
    /// A material per point (Add's material index), or none: defaults everywhere.
    const std::vector<ShadingMaterial>* materials = nullptr;
    Vec3 globalAmbient = Vec3::Zero();
    bool baseColours = false;
    bool twoSided = false;
    const RayScene* shadowScene = nullptr; ///< null: no shadows
  };

  explicit ShadeBatch(const Settings& settings);
  ~ShadeBatch() { this->Flush(); }
  ShadeBatch(const ShadeBatch&) = delete;
  ShadeBatch& operator=(const ShadeBatch&) = delete;

  /// Point p (normal n, viewer: world), base colour rgba, material (an index into the settings'
  /// materials, or -1: the defaults), whose colour goes to out[0..3].
  void Add(const Vec3& p, const Vec3& n, const Vec3& viewer, const float rgba[4],
    unsigned char* out, int material = -1)
  {
    const int i = this->Count;
    const ShadingMaterial& m = material < 0 ? this->S.defaults : (*this->S.materials)[material];
    if (material >= 0)
    {
      this->M[i] = m.material;
      this->Opacity[i] = m.opacity;
    }
    if (this->S.baseColours)
    {
      const Vec3 c(rgba[0], rgba[1], rgba[2]);
      this->M[i].ambient = m.ambientK * c;
      this->M[i].diffuse = m.diffuseK * c;
    }
    this->P[i] = p;
    this->N[i] = (this->S.twoSided && n.dot(viewer - p) < 0) ? Vec3(-n) : n;
    this->Viewer[i] = viewer;
    if (this->S.shadowScene)
    {
      this->TraceShadows(i);
    }
    this->Alpha[i] = rgba[3];
    this->Out[i] = out;
    if (++this->Count == W)
    {
      this->Flush();
    }
  }

  /// Shades the points added so far.
  void Flush();

private:
  // The shadow flags of point i (RayScene.h stays out of this header).
  void TraceShadows(int i);

  static constexpr int W = kShadeLanes;
  const Settings& S;
  std::vector<unsigned char> Lit; // W x lights shadow flags
  int Count = 0;
  Vec3 P[W], N[W], Viewer[W];
  Material M[W];
  double Opacity[W];
  float Alpha[W];
  unsigned char* Out[W];
};
} // namespace catar

#endif
