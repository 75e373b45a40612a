#include "ShadeBatch.h"

#include "RayScene.h"
#include "Shadows.h"

#include <algorithm>

namespace catar
{
ShadeBatch::ShadeBatch(const Settings& settings)
  : S(settings)
  , Lit(static_cast<size_t>(W) * settings.lights->size(), 1)
{
  std::fill(this->M, this->M + W, settings.defaults.material);
  std::fill(this->Opacity, this->Opacity + W, settings.defaults.opacity);
}

void ShadeBatch::TraceShadows(int i)
{
  catar::TraceShadows(*this->S.shadowScene, this->P[i], this->N[i], *this->S.lights,
    this->Lit.data() + i * this->S.lights->size());
}

void ShadeBatch::Flush()
{
  Vec3 colour[W];
  ShadeMany(this->Count, this->P, this->N, this->Viewer, *this->S.lights, this->M,
    this->S.globalAmbient, this->S.shadowScene ? this->Lit.data() : nullptr, false, colour);
  for (int i = 0; i < this->Count; ++i)
  {
    unsigned char* o = this->Out[i];
    o[0] = ColourByte(colour[i].x());
    o[1] = ColourByte(colour[i].y());
    o[2] = ColourByte(colour[i].z());
    o[3] = ColourByte(this->Opacity[i] * this->Alpha[i]);
  }
  this->Count = 0;
}
std::string ValidateShading(const std::vector<LightSource>& lights, const ShadingMaterial& defaults,
  const std::vector<ShadingMaterial>& materials, const Vec3& globalAmbient)
{
  std::string error = ValidateLighting(lights, defaults.material, globalAmbient, defaults.ambientK,
    defaults.diffuseK, defaults.opacity);
  for (std::size_t m = 0; m < materials.size() && error.empty(); ++m)
  {
    error = ValidateLighting(lights, materials[m].material, globalAmbient, materials[m].ambientK,
      materials[m].diffuseK, materials[m].opacity);
    if (!error.empty())
    {
      error = "material " + std::to_string(m) + ": " + error;
    }
  }
  return error;
}
} // namespace catar
