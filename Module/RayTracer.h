// CatadioptricAR Core: the exact reference renderer.
//
// Every pixel (or N x N samples of it) is back-projected through the camera, reflected off the
// mirror, and the reflected ray is intersected with the scene's triangles (Embree). The
// hit point is shaded with the same equation as the fast path (Lighting.h) but exactly where the
// ray lands: the viewer is the pixel's own mirror point, the normal is the face normal (Flat) or
// the interpolated vertex normal (Smooth), base colours and texture coordinates are interpolated
// barycentrically, and shadows are traced by shadow rays. No triangle is approximated by a
// straight-edged 2D triangle and no painter order is involved, so the fast path's image can be
// compared with this one pixel by pixel (ImageMetrics.h).
//
// Usage: SetScene() once per change of the meshes, lights or textures; PrepareRays() once per
// camera (it caches the back-projected rays); then RenderRows() for any split of the rows into
// bands, from several threads at once.
#ifndef catarRayTracer_h
#define catarRayTracer_h

#include "Lighting.h"
#include "Projector.h"
#include "Rasterizer.h" // ImageView, TextureView
#include "RayScene.h"

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace catar
{

/// One mesh of the traced scene (world coordinates).
struct TraceMesh
{
  std::vector<Vec3> points;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  /// Id reported for each triangle in the visible-triangle buffer (a polygon split into a fan
  /// gives its cell id to all its triangles). Empty: the triangle's index.
  std::vector<RasterId> triangleIds;

  enum class ColorSource
  {
    Solid, ///< `color` everywhere
    Point, ///< `colors`: RGBA per point, interpolated
    Cell   ///< `colors`: RGBA per triangle
  };
  ColorSource colorSource = ColorSource::Solid;
  std::vector<float> colors; ///< RGBA in [0, 1], 4 per point or per triangle
  Vec3 color = Vec3(1, 1, 1);

  enum class Shading
  {
    None,  ///< the base colour, unlit (the compositor without lighting)
    Flat,  ///< face normal at the hit point
    Smooth ///< vertex normals interpolated at the hit point (face normals when none given)
  };
  Shading shading = Shading::Smooth;
  std::vector<Vec3> normals; ///< per point (optional)
  /// With a base colour (Point / Cell), material ambient and diffuse are those factors times the
  /// base colour, as vtkCatadioptricLighting does: pass vtkProperty's Ambient and Diffuse here.
  double ambientFactor = 1.0;
  double diffuseFactor = 1.0;
  Material material;
  double opacity = 1.0;
  bool twoSided = true;

  std::vector<float> tcoords; ///< u v per point (optional)
  int texture = -1;           ///< index into the scene's textures; negative: none
};

struct RayTraceStatistics
{
  std::size_t mirrorRays = 0; ///< sample rays that reflect off the mirror
  std::size_t tracedRays = 0; ///< of those, rays that reach the scene's bounding box
  std::size_t hits = 0;       ///< rays that hit a triangle
  std::size_t shadowRays = 0;
};

class RayTracer
{
public:
  /// Builds the scene. Returns false with GetError() on invalid input (indices out of range,
  /// NaN/Inf points, array sizes that do not match); nothing is kept then. Textures are not
  /// owned and must outlive the renders.
  bool SetScene(const std::vector<TraceMesh>& meshes, const std::vector<TextureView>& textures,
    const std::vector<LightSource>& lights, const Vec3& globalAmbient, bool shadows);

  /// Back-projects the N x N samples (N = samples, 1..8) of every pixel of `projector`'s image
  /// and keeps the reflected rays (single precision, as Embree traces). False with GetError()
  /// for an invalid camera.
  bool PrepareRays(const Projector& projector, int samples);

  /// Renders rows [y0, y1) of `target`, which holds the camera frame (RGBA8, the camera's image
  /// size): where the reflected ray of a sample hits the scene, its shaded colour is composited
  /// over the frame (source over, the mesh's opacity); samples are averaged. `ids` (optional,
  /// one int64 per pixel, addressed like target with idRowStride counted in values) receives
  /// the visible triangle of the pixel's centre-most sample: meshIndex * 2^32 + triangle id, or
  /// -1. `pathLengths` (optional, one float per pixel, addressed like ids) receives that
  /// sample's distance from the mirror to the surface it meets, or NaN. Thread-safe for disjoint
  /// row ranges. `statistics` (optional) is added to.
  void RenderRows(const ImageView& target, RasterId* ids, std::ptrdiff_t idRowStride, int y0,
    int y1, RayTraceStatistics* statistics = nullptr, float* pathLengths = nullptr) const;

  const std::string& GetError() const { return this->Error; }
  int GetWidth() const { return this->Width; }
  int GetHeight() const { return this->Height; }
  std::size_t GetNumberOfTriangles() const { return this->Triangles.size(); }

private:
  struct GlobalTriangle
  {
    std::uint32_t mesh;
    std::uint32_t local;
  };
  struct Ray
  {
    float origin[3];
    float direction[3];
  };

  /// Colour (RGBA, [0,1]) of the hit of ray `r` with global triangle `t` at barycentric (u, v).
  void ShadeHit(const Vec3& origin, const Vec3& direction, const RayScene::Hit& hit, float rgba[4],
    RayTraceStatistics& statistics) const;

  std::vector<TraceMesh> Meshes;
  std::vector<TextureView> Textures;
  LightSet Lights;
  Vec3 GlobalAmbient = Vec3::Zero();
  bool Shadows = false;
  std::vector<GlobalTriangle> Triangles;
  RayScene Scene;
  Vec3 BoundsMin = Vec3::Zero();
  Vec3 BoundsMax = Vec3::Zero();
  bool HasScene = false;

  int Width = 0;
  int Height = 0;
  int Samples = 1;
  std::vector<std::uint8_t> RayValid; ///< per sample: 1 when the ray reflects off the mirror
  std::vector<Ray> Rays;              ///< per sample
  std::string Error;
};

} // namespace catar

#endif
