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
// Usage: SetScene() at every change of the meshes, lights or textures (meshes given again by the
// same pointer keep their acceleration structure: a light, a colour or a material that changes
// costs no rebuild); PrepareRays() at every change of the camera (the rays are back-projected in
// the camera frame and kept while the lens, the mirror, the image size and the samples stay: a
// new pose only moves them); then RenderRows() for any split of the rows into bands, from several
// threads at once. The image is traced in tiles of kTile x kTile pixels: a tile whose rays cannot
// reach the scene's bounding sphere (a cone of rays from a ball of origins, tested once) is
// skipped whole, the rays of the others are traced together (Embree's streams).
#ifndef catarRayTracer_h
#define catarRayTracer_h

#include "Projector.h"
#include "Rasterizer.h" // ImageView, TextureView
#include "RayScene.h"
#include "Shadows.h"

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
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
  /// Pixels a side of the tiles the image is traced in.
  static constexpr int kTile = 8;

  /// Runs body(begin, end) over disjoint ranges that cover [0, n), possibly from several threads
  /// at once, and returns when all are done (e.g. vtkSMPTools::For). Empty: one range, on the
  /// calling thread.
  using ParallelFor =
    std::function<void(std::size_t n, const std::function<void(std::size_t, std::size_t)>& body)>;

  /// Builds the scene. Returns false with GetError() on invalid input (indices out of range,
  /// NaN/Inf points, array sizes that do not match); nothing is kept then. Textures are not
  /// owned and must outlive the renders. A mesh given by the same pointer as at the last call
  /// that succeeded, in the same place of the list, is taken to have the same points and
  /// triangles: its part of the acceleration structure is kept (when every mesh is such, nothing
  /// is rebuilt); its other members (colours, normals, texture coordinates, shading, material,
  /// opacity) are read again at every render, and may be changed between renders, not during
  /// one. Give a new object for new points or triangles. `buildThreads`: as
  /// RayScene::SetBuildThreads.
  bool SetScene(const std::vector<std::shared_ptr<const TraceMesh>>& meshes,
    const std::vector<TextureView>& textures, const std::vector<LightSource>& lights,
    const Vec3& globalAmbient, bool shadows, int buildThreads = 1);
  /// The same with copies of `meshes` (always rebuilt).
  bool SetScene(const std::vector<TraceMesh>& meshes, const std::vector<TextureView>& textures,
    const std::vector<LightSource>& lights, const Vec3& globalAmbient, bool shadows);

  /// Times the acceleration structure was built (by SetScene calls that succeeded), and times
  /// it was refitted: when every mesh given anew has the same triangles and number of points as
  /// the one it replaces (and no mesh is added or removed), its structure is refitted to the new
  /// points (RayScene's dynamic scene) in place of building the scene again.
  std::size_t GetNumberOfBuilds() const { return this->Builds; }
  std::size_t GetNumberOfRefits() const { return this->Refits; }

  /// Sets the camera: back-projects the N x N samples (N = samples, 1..8) of every pixel of
  /// `projector`'s image in the camera frame and keeps the reflected rays (single precision, as
  /// Embree traces), unless the rays kept are those of the same lens, mirror, image size and
  /// samples: then only the pose is taken (the rays are moved into the world at render time).
  /// `parallel` splits the back projection by rows of tiles. False with GetError() for an
  /// invalid camera.
  bool PrepareRays(const Projector& projector, int samples, const ParallelFor& parallel = {});

  /// Times the rays were back-projected (by PrepareRays calls that succeeded).
  std::size_t GetNumberOfRayPreparations() const { return this->RayPreparations; }

  /// Renders rows [y0, y1) of `target`, which holds the camera frame (RGBA8, the camera's image
  /// size): where the reflected ray of a sample hits the scene, its shaded colour is composited
  /// over the frame (source over, the mesh's opacity); samples are averaged. `ids` (optional,
  /// one int64 per pixel, addressed like target with idRowStride counted in values) receives
  /// the visible triangle of the pixel's centre-most sample: meshIndex * 2^32 + triangle id, or
  /// -1. `pathLengths` (optional, one float per pixel, addressed like ids) receives that
  /// sample's distance from the mirror to the surface it meets, or NaN. Thread-safe for disjoint
  /// row ranges (fastest when they begin and end on multiples of kTile). `statistics`
  /// (optional) is added to.
  void RenderRows(const ImageView& target, RasterId* ids, std::ptrdiff_t idRowStride, int y0,
    int y1, RayTraceStatistics* statistics = nullptr, float* pathLengths = nullptr) const;

  ///@{
  /// Skip the tiles whose rays cannot reach the scene's bounding sphere (default on; off traces
  /// every tile, for tests: the picture is the same).
  void SetTileCulling(bool on) { this->TileCulling = on; }
  bool GetTileCulling() const { return this->TileCulling; }
  ///@}

  const std::string& GetError() const { return this->Error; }
  int GetWidth() const { return this->Width; }
  int GetHeight() const { return this->Height; }
  std::size_t GetNumberOfTriangles() const { return this->Scene.GetNumberOfTriangles(); }

private:
  using Ray = RayScene::Ray;

  /// What the tile culling knows of a tile's rays (camera frame): every origin lies within
  /// `radius` of `centre`, every direction within an angle (of cosine `cosAngle` and sine
  /// `sinAngle`) of the unit `axis`.
  struct Tile
  {
    float centre[3];
    float radius;
    float axis[3];
    double cosAngle; // double: the cosine of a small angle in single precision loses it
    double sinAngle;
    std::uint32_t rays; ///< samples of the tile that reflect off the mirror
  };

  /// Colour (RGBA, [0,1]) of the hit of ray (origin, direction) at `hit`.
  void ShadeHit(const Vec3& origin, const Vec3& direction, const RayScene::Hit& hit, float rgba[4],
    RayTraceStatistics& statistics) const;
  /// Back-projects tile rows [r0, r1) of the kept camera.
  void BackProjectTileRows(const Projector& projector, int r0, int r1);
  /// Can a ray of the tile reach the scene's bounding sphere (camera frame: centre c, radius r)?
  static bool TileMeetsSphere(const Tile& tile, const Vec3& c, double r);
  /// A tile's rays in the world, hits, and which ray each sample has (-1: none traced).
  struct TileBuffers
  {
    std::vector<Ray> rays;
    std::vector<std::int16_t> which;
    std::vector<RayScene::Hit> hits;
  };
  /// Renders rows [y0, y1) of the tiles' column tx (rows of one tile).
  void RenderTile(const ImageView& target, RasterId* ids, std::ptrdiff_t idRowStride, int tx,
    int y0, int y1, TileBuffers& buffers, RayTraceStatistics& statistics, float* pathLengths) const;

  std::vector<std::shared_ptr<const TraceMesh>> Meshes;
  std::vector<TextureView> Textures;
  LightSet Lights;
  Vec3 GlobalAmbient = Vec3::Zero();
  bool Shadows = false;
  RayScene Scene;
  std::size_t Builds = 0;
  std::size_t Refits = 0;
  Vec3 BoundsMin = Vec3::Zero();
  Vec3 BoundsMax = Vec3::Zero();
  Vec3 SphereCentre = Vec3::Zero(); ///< world; encloses the bounding box
  double SphereRadius = 0.0;
  bool HasScene = false;
  bool TileCulling = true;

  // The camera: rays in the camera frame for the lens, mirror, size and samples kept, and the
  // pose that moves them into the world.
  int Width = 0;
  int Height = 0;
  int Samples = 1;
  int TilesX = 0;
  int TilesY = 0;
  CameraModel RaysLens; // the lens and mirror the rays were made for
  std::size_t RayPreparations = 0;
  Mat3 CameraToWorld = Mat3::Identity(); ///< R^T
  Vec3 CameraCentre = Vec3::Zero();      ///< world
  Mat3 WorldToCamera = Mat3::Identity(); ///< R
  Vec3 Translation = Vec3::Zero();       ///< t
  std::vector<std::uint8_t> RayValid;    ///< per sample: 1 when the ray reflects off the mirror
  std::vector<Ray> Rays;                 ///< per sample, camera frame
  std::vector<Tile> Tiles;               ///< TilesX per tile row
  std::string Error;
};

} // namespace catar

#endif
