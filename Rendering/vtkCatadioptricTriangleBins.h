/**
 * @class   vtkCatadioptricTriangleBins
 * @brief   the compositor's triangles, gathered once per frame and binned into image bands
 *
 * Not a vtkObject (C++ only, not wrapped). vtkCatadioptricCompositor draws the triangles (fans of
 * the visible polygons) of its meshes in one order -- cell order; meshes merged far to near by
 * CentroidDepth; with a depth buffer, opaque triangles first -- in horizontal bands of the image
 * drawn in parallel. Build() prepares that drawing once per frame, in parallel, reading the
 * meshes' arrays with typed access (no virtual call per value for the array types the pipeline
 * makes; any other type is read through vtkDataArray, with the same values):
 *  - every point is read, checked (finite attributes, inside the rasteriser's guard band) and
 *    snapped to the rasteriser's grid once (catar::snapToGrid), with its colour, depth and
 *    texture coordinates, instead of once per triangle and band;
 *  - every triangle's rows are found (catar::coveredPixelBounds), so that a triangle that cannot
 *    draw a pixel (invalid attributes, degenerate, between pixel centres, outside the image) goes
 *    no further: seen from a catadioptric camera most triangles of a detailed mesh are smaller
 *    than a pixel, and most of those cover no pixel centre;
 *  - the others are stored with what drawing them reads (snapped vertices, and the colours of the
 *    usual unsigned char colour array), so the bands read them in sequence, and binned into the
 *    BandHeight-row bands they meet, keeping the drawing order within each band, so that a band
 *    visits only its own triangles. Each task bins its own part of the drawing order (a counting
 *    sort by band): a band's list is the concatenation of the parts' lists.
 * Get() then gives a triangle in the form catar::rasterizeSnappedTriangle draws, which draws
 * exactly what catar::rasterizeTriangle draws for the vertices as the compositor reads them: same
 * snapping, colours (ColorArrayName's array, or the solid colour, times Opacity), depths, texture
 * coordinates and ids.
 *
 * The bands stay BandHeight rows high: the rasteriser evaluates its attribute planes from the
 * clipped corner of each band, so the band boundaries are part of the pixels' exact values
 * (rounding of the last bit). The threads are balanced instead by drawing the bands from most to
 * fewest triangles (GetBandByLoad), the empty ones, which only write their background, last.
 * Indices are 32-bit: at most 2^32 - 1 points, polygons and triangles per frame.
 * The scratch memory is kept between calls (a frame reuses the last frame's buffers). Build()
 * makes at most two parallel loops (three when the order is not cell order), and reads small
 * meshes in the calling thread: with VTK 9.2's STDThread backend each loop starts its threads
 * anew (about 0.1 ms), so the passes are fused where they can be.
 */
#ifndef vtkCatadioptricTriangleBins_h
#define vtkCatadioptricTriangleBins_h

#include "CatadioptricARRenderingModule.h" // for export macro
#include "Rasterizer.h"                    // for catar::SnappedTriangle
#include "vtkCatadioptricColorArray.h"     // for vtkCatadioptricColorArray
#include "vtkType.h"                       // for vtkIdType

#include <algorithm> // for std::copy
#include <cstdint>   // for std::uint32_t
#include <optional>  // for std::optional
#include <string>    // for std::string
#include <vector>    // for std::vector

class vtkCellArray;
class vtkDataArray;
class vtkPolyData;

class CATADIOPTRICARRENDERING_EXPORT vtkCatadioptricTriangleBins
{
public:
  /// Rows per band.
  static constexpr int BandHeight = 32;

  /// One mesh, its arrays found and checked by the caller.
  struct Mesh
  {
    vtkPolyData* Data = nullptr;
    vtkDataArray* Pixels = nullptr;        ///< point data ImageCoordinates (2 components)
    vtkDataArray* Visible = nullptr;       ///< cell data Visible (0: skipped)
    vtkDataArray* CentroidDepth = nullptr; ///< cell data CentroidDepth (merging meshes)
    vtkDataArray* PathLength = nullptr;    ///< point data depth (depth buffer), else null
    vtkDataArray* OriginalIds = nullptr;   ///< cell data OriginalCellId (ids), or null
    vtkDataArray* TCoords = nullptr;       ///< texture coordinates (>= 2 components), or null
    int Texture = -1;                      ///< texture index (with TCoords), else -1
    bool TextureOpaque = true;             ///< the texture has no alpha below 255
    int Key = 0;                           ///< mesh index in the ids (id = Key * 2^32 + cell)
  };

  /// How the meshes are drawn.
  struct Options
  {
    int Width = 0;                           ///< image columns
    int Height = 0;                          ///< image rows
    const char* ColorArrayName = nullptr;    ///< point or cell colour array (may be null)
    float Solid[4] = { 0.f, 0.f, 0.f, 1.f }; ///< RGBA of meshes without that array
    float Opacity = 1.f;                     ///< multiplies every alpha
    bool MergeByDepth = false; ///< one far-to-near order across meshes (stable: CentroidDepth)
    bool DepthBuffer = false;  ///< a depth test: opaque triangles first (needs Depths)
    bool Depths = false;       ///< per-vertex depths (PathLength): DepthBuffer, or depth output
    bool Ids = false;          ///< per-triangle ids
    /// Samples per pixel side of anti-aliased edges (1: none, at most 4). Above 1 a triangle is
    /// kept when it covers one of the S x S sample points of a pixel (the centres of the pixel's
    /// S x S sub-pixels) as well as when it covers a pixel centre (not a sample when S is even),
    /// so that the edge samples see the triangles smaller than a pixel.
    int Samples = 1;
  };

  /// A triangle's drawing state besides its vertices.
  struct Info
  {
    int Texture = -1;       ///< index of its texture, -1 for none
    bool Opaque = false;    ///< alpha 1 at every vertex and an opaque texture (depth buffer)
    catar::RasterId Id = 0; ///< Key * 2^32 + cell id (with Options::Ids)
  };

  vtkCatadioptricTriangleBins();
  ~vtkCatadioptricTriangleBins();

  /// Gathers, orders and bins the triangles of `meshes`. False with `error` set when they do not
  /// fit the 32-bit indices.
  bool Build(const std::vector<Mesh>& meshes, const Options& options, std::string& error);

  /// Triangles of visible polygons (whether or not they draw a pixel), and triangles of polygons
  /// whose Visible flag is 0.
  vtkIdType GetNumberOfTriangles() const { return this->NumberOfTriangles; }
  vtkIdType GetNumberOfSkippedTriangles() const { return this->NumberOfSkipped; }

  /// Number of bands, and band b's rows (full image width).
  int GetNumberOfBands() const { return this->NumberOfBands; }
  catar::PixelRect GetBand(int b) const
  {
    const int y0 = b * BandHeight;
    const int y1 = y0 + BandHeight < this->Opts.Height ? y0 + BandHeight : this->Opts.Height;
    return catar::PixelRect{ 0, y0, this->Opts.Width, y1 };
  }
  /// The bands from most to fewest triangles: drawing them in this order balances the threads
  /// (the bands of a small object come first and are shared out before the empty ones).
  int GetBandByLoad(int i) const { return this->BandsByLoad[i]; }
  /// Number of triangles binned into band b.
  std::uint32_t GetBandLoad(int b) const { return this->BandLoads[b]; }
  /// Samples per pixel side the triangles were kept for (Options::Samples, clamped).
  int GetSamples() const { return this->Opts.Samples; }

  /// Calls f(ref) for the triangles of band b in drawing order (ref is for Get()).
  template<typename F>
  void ForEachTriangle(int b, F&& f) const
  {
    for (const Part& part : this->Parts)
    {
      for (std::uint32_t i = part.Start[b], e = part.Start[b + 1]; i < e; ++i)
      {
        f(part.Refs[i]);
      }
    }
  }

  /// ForEachTriangle in the reverse order (nearest first in painter order).
  template<typename F>
  void ForEachTriangleReverse(int b, F&& f) const
  {
    for (auto part = this->Parts.rbegin(); part != this->Parts.rend(); ++part)
    {
      for (std::uint32_t i = part->Start[b + 1]; i > part->Start[b]; --i)
      {
        f(part->Refs[i - 1]);
      }
    }
  }

  /// Triangle `ref`: its vertices as rasterizeSnappedTriangle takes them, and its drawing state.
  void Get(std::uint32_t ref, catar::SnappedTriangle& t, Info& info) const;
  /// Triangle `ref`'s snapped vertex positions only (1/256 px).
  void GetPositions(std::uint32_t ref, std::int32_t x[3], std::int32_t y[3]) const
  {
    const Triangle& tri = this->Triangles[ref];
    std::copy(tri.X, tri.X + 3, x);
    std::copy(tri.Y, tri.Y + 3, y);
  }

private:
  vtkCatadioptricTriangleBins(const vtkCatadioptricTriangleBins&) = delete;
  void operator=(const vtkCatadioptricTriangleBins&) = delete;

  enum class ColourSource : std::uint8_t
  {
    PointBytes,  // unsigned char point colours (vtkCatadioptricLighting's): Point::Rgba
    PointFloats, // any other point colour array: PointColours
    Cell,        // cell colour array: CellColours
    Solid        // no colour array: MeshInfo::Solid
  };
  struct Rgba
  {
    float C[4];
  };
  struct TCoord
  {
    float U, V;
  };
  // A snapped point, with its colour bytes (PointBytes meshes: RGBA, alpha 255 for RGB) in the
  // same cache line: finding the triangles that can draw reads three points at random places
  // per triangle. X == kBadPoint (in the .cxx) when it cannot be drawn (a non-finite attribute,
  // or outside the rasteriser's guard band).
  struct Point
  {
    std::int32_t X, Y;
    std::uint8_t Rgba[4];
  };
  // A triangle that can draw a pixel, in two parts. What drawing reads of every triangle: its
  // snapped vertices and colour bytes (PointBytes meshes), copied from its points so that the
  // bands read the triangles in sequence, in 40 bytes (the bands' threads read what the
  // triangles' threads wrote, so every byte here crosses between cores).
  struct Triangle
  {
    std::int32_t X[3], Y[3];
    std::uint8_t Rgba[3][4];
    std::uint16_t Mesh;
    std::uint8_t Opaque;
  };
  // The rest, read when binning and for the other attributes: global point indices in the fan's
  // order, global polygon index, and the rows the triangle can draw.
  struct TriangleSource
  {
    std::uint32_t V[3];
    std::uint32_t Cell;
    std::int32_t Row0, Row1;
  };
  struct MeshInfo
  {
    const Mesh* Input = nullptr;
    std::optional<vtkCatadioptricColorArray> Colour; // the colour array, when there is one
    ColourSource Colours = ColourSource::Solid;
    Rgba Solid{};           // Options::Solid with Opacity
    bool SolidValid = true; // Solid is finite
    int Texture = -1;       // Input->Texture
    vtkCellArray* Polys = nullptr;
    vtkIdType FirstCellId = 0; // cell id of the first polygon (after verts and lines)
    vtkIdType PointBase = 0;   // global index of the first point
    vtkIdType CellBase = 0;    // global index of the first polygon
  };
  // A range of a mesh's points or polygons read by one task; for polygons, also the number of
  // triangles they make (Count) or skip (Skipped), the place of the first one (First), and how
  // many of them can draw a pixel (Drawable, stored from First on).
  struct Chunk
  {
    int Mesh = 0;
    vtkIdType Begin = 0, End = 0;
    vtkIdType Count = 0, Skipped = 0, First = 0, Drawable = 0;
  };
  // One task's part of the drawing order, binned: band b's triangles are
  // Refs[Start[b], Start[b + 1]).
  struct Part
  {
    std::vector<std::uint32_t> Refs;
    std::vector<std::uint32_t> Start;
  };

  void ReadPoints(const Chunk& chunk);
  void ReadCells(Chunk& chunk);
  void MakeTriangles(Chunk& chunk);
  void OrderTriangles();
  template<typename RefAt>
  void BinPart(Part& part, vtkIdType n, RefAt&& refAt) const;

  Options Opts;
  int NumberOfBands = 0;
  vtkIdType NumberOfTriangles = 0;
  vtkIdType NumberOfSkipped = 0;
  float Bytes[256];      // unsigned char colour components as floats
  float AlphaBytes[256]; // unsigned char alpha as a float, times Opacity

  std::vector<MeshInfo> Meshes;
  std::vector<Chunk> PointChunks;
  std::vector<Chunk> CellChunks;
  // Per point (global index): position (and colour bytes), float colour (PointFloats meshes),
  // depth (depth buffer), texture coordinates (textured meshes).
  std::vector<Point> Points;
  std::vector<Rgba> PointColours;
  std::vector<float> PointDepths;
  std::vector<TCoord> PointTCoords;
  // Per polygon (global index): 0 invisible, 1 visible but nothing to draw, 2 drawable; colour
  // (Cell meshes), id, CentroidDepth (merging meshes).
  std::vector<std::uint8_t> CellStates;
  std::vector<Rgba> CellColours;
  std::vector<catar::RasterId> CellIds;
  std::vector<double> CellDepths;
  // The triangles that can draw, each chunk's from its First on, in (mesh, polygon, fan) order;
  // and the drawing order when it is another (Sequenced): merged by depth and/or opaque first.
  std::vector<Triangle> Triangles;
  std::vector<TriangleSource> Sources;
  bool Sequenced = false;
  std::vector<std::uint32_t> Sequence;
  std::vector<std::uint32_t> SequenceScratch;
  // The bins: one part per cell chunk (cell order) or per slice of Sequence.
  std::vector<Part> Parts;
  std::vector<std::uint32_t> BandLoads;
  std::vector<int> BandsByLoad;
};

inline void vtkCatadioptricTriangleBins::Get(
  std::uint32_t ref, catar::SnappedTriangle& t, Info& info) const
{
  const Triangle& tri = this->Triangles[ref];
  const TriangleSource& src = this->Sources[ref];
  const MeshInfo& mesh = this->Meshes[tri.Mesh];
  for (int k = 0; k < 3; ++k)
  {
    t.x[k] = tri.X[k];
    t.y[k] = tri.Y[k];
    const float* c = mesh.Solid.C;
    switch (mesh.Colours)
    {
      case ColourSource::PointBytes:
        t.rgba[k][0] = this->Bytes[tri.Rgba[k][0]];
        t.rgba[k][1] = this->Bytes[tri.Rgba[k][1]];
        t.rgba[k][2] = this->Bytes[tri.Rgba[k][2]];
        t.rgba[k][3] = this->AlphaBytes[tri.Rgba[k][3]];
        c = nullptr;
        break;
      case ColourSource::PointFloats:
        c = this->PointColours[src.V[k]].C;
        break;
      case ColourSource::Cell:
        c = this->CellColours[src.Cell].C;
        break;
      case ColourSource::Solid:
        break;
    }
    if (c)
    {
      std::copy(c, c + 4, t.rgba[k]);
    }
    if (this->Opts.Depths)
    {
      t.depth[k] = this->PointDepths[src.V[k]];
    }
    if (mesh.Texture >= 0)
    {
      t.u[k] = this->PointTCoords[src.V[k]].U;
      t.v[k] = this->PointTCoords[src.V[k]].V;
    }
  }
  info.Texture = mesh.Texture;
  info.Opaque = tri.Opaque != 0;
  info.Id = this->Opts.Ids ? this->CellIds[src.Cell] : 0;
}

#endif
