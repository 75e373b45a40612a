// CatadioptricAR Core: the polygons of a projected mesh -- their centroids' projection, depth and
// visibility -- from the projections of their vertices.
//
// A polygon is visible when all its vertices have a reflection, its centroid has one too, it
// overlaps the image and (with back-face culling) it faces the viewer, i.e. the point of the
// mirror it is seen at. Its depth is the centroid's path length (the painter's order sorts on
// it), and the centroid's reflection point is kept (CentroidMirrorPoint). The centroid reflects
// next to its vertices: Newton from the mean of their reflection points converges in one or two
// steps, to the same answer as either solver; centroids are solved a batch at a time, side by
// side (Projector::ProjectWorldNear). vtkCatadioptricProjection marshals the arrays.
#ifndef catarPolygonProjection_h
#define catarPolygonProjection_h

#include "ImageTessellation.h"
#include "Projector.h"

#include <atomic>
#include <cstdint>

namespace catar
{
/// What the polygons read of each vertex, in one cache line: the polygons visit their vertices in
/// no particular order, and four arrays would cost four cache misses per vertex.
struct alignas(64) VertexRecord
{
  double point[3]; ///< world
  double pixel[2]; ///< image coordinates
  float mirror[3]; ///< reflection point (camera frame): where the centroids' Newton starts
  unsigned char visible;

  /// The record of world point p projected as q.
  void Set(const Vec3& p, const ProjectedPoint& q)
  {
    for (int k = 0; k < 3; ++k)
    {
      this->point[k] = p[k];
      this->mirror[k] = static_cast<float>(q.mirrorPoint[k]);
    }
    this->pixel[0] = q.pixel.x();
    this->pixel[1] = q.pixel.y();
    this->visible = HasProjection(q.status) ? 1 : 0;
  }
};

/// Where the polygons' values go: polygon c writes element cellOffset + c of each (three of
/// centroidMirror).
struct PolygonOutputs
{
  double* depth = nullptr;          ///< the centroid's path length; 0 when not visible
  double* centroidMirror = nullptr; ///< the centroid's reflection point; 0 when none
  unsigned char* visible = nullptr; ///< 1: drawn
  std::int64_t cellOffset = 0;      ///< cell-data index of the first polygon
};

/// Polygon c of a mesh: its point ids connectivity[offsets[c]] ... connectivity[offsets[c + 1] -
/// 1] (Index: int, long or long long, as a cell array stores them); vertices[i] the record of
/// point i.
template<typename Index>
struct PolygonsView
{
  const Index* offsets = nullptr;
  const Index* connectivity = nullptr;
  std::int64_t numberOfPolygons = 0;
  const VertexRecord* vertices = nullptr;
};

class PolygonProjection
{
public:
  /// For the camera of `projector` (its image size and pose).
  PolygonProjection(const Projector& projector, bool cullBackFaces);

  /// The per-frame tessellation's options: the quick check (NeedsFateCheck) Project() can do on
  /// the vertices it reads anyway.
  TessellationOptions Tessellation;

  /// Projects every polygon on `threads` threads (Parallel.h). needsFateCheck (may be null):
  /// set when a triangle needs the tessellation's closer look (catar::NeedsFateCheck with
  /// Tessellation), the quick pass of catar::ChooseTriangles done here.
  template<typename Index>
  void Project(const PolygonsView<Index>& polygons, const PolygonOutputs& out, int threads,
    std::atomic<bool>* needsFateCheck = nullptr) const;

  /// A refined mesh's polygons: element c (of nCells) of `out` copies element sources[c] of
  /// `from` when sources[c] >= 0 (a cell kept as it was), and the polygons whose cell is a piece
  /// (sources[out.cellOffset + c] < 0) are projected.
  template<typename Index>
  void ProjectPieces(const PolygonsView<Index>& polygons, std::int64_t nCells,
    const std::int64_t* sources, const PolygonOutputs& from, const PolygonOutputs& out,
    int threads) const;

private:
  struct Batch;
  template<typename Index>
  void ProjectRange(const PolygonsView<Index>& polygons, const PolygonOutputs& out,
    std::int64_t begin, std::int64_t end, std::atomic<bool>* needsFateCheck) const;
  void Finish(Batch& batch, const PolygonOutputs& out) const;

  const Projector* TheProjector;
  double Width;
  double Height;
  bool CullBackFaces;
  Mat3 CameraToWorldRotation; // R^T
  Vec3 CameraCentre;          // -R^T T: the camera centre in world coordinates
};
} // namespace catar

#endif
