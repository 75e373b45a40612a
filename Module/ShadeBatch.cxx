#include "ShadeBatch.h"

#include "RayScene.h"

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

void ShadeBatch::Add(const Vec3& p, const Vec3& n, const Vec3& viewer, const float rgba[4],
  unsigned char* out, int material)
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
    TraceShadows(*this->S.shadowScene, p, this->N[i], *this->S.lights,
      this->Lit.data() + i * this->S.lights->size());
  }
  this->Alpha[i] = rgba[3];
  this->Out[i] = out;
  if (++this->Count == W)
  {
    this->Flush();
  }
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
} // namespace catar
