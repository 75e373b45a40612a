// CatadioptricAR Core: the compositor's triangles, gathered once per frame and binned into image
// bands.
//
// A frame's triangles -- the fans of the visible polygons of its meshes, in one drawing order (cell
// order; meshes merged far to near by CentroidDepth; with a depth buffer, opaque triangles first)
// -- are drawn in horizontal bands of the image, in parallel. TriangleBins holds what drawing
// reads, prepared once per frame:
//  - every point checked (finite attributes, inside the rasteriser's guard band) and snapped to
//    the rasteriser's grid once (catar::snapToGrid), with its colour, depth and texture
//    coordinates, instead of once per triangle and band;
//  - every triangle's rows found (catar::coveredPixelBounds), so that a triangle that cannot draw
//    a pixel (invalid attributes, degenerate, between pixel centres, outside the image) goes no
//    further: seen from a catadioptric camera most triangles of a detailed mesh are smaller than a
//    pixel, and most of those cover no pixel centre;
//  - the others stored with what drawing them reads (snapped vertices, and the colours of the
//    usual unsigned char colour array), so the bands read them in sequence, and binned into the
//    BandHeight-row bands they meet, keeping the drawing order within each band, so that a band
//    visits only its own triangles. Each task bins its own part of the drawing order (a counting
//    sort by band): a band's list is the concatenation of the parts' lists.
// Get() then gives a triangle in the form rasterizeSnappedTriangle draws, which draws exactly what
// rasterizeTriangle draws for the vertices as read: same snapping, colours, depths, texture
// coordinates and ids.
//
// This class is the VTK-free part: the storage, the triangles (MakeTriangles), their order, the
// bins and the bands' loads. A reader fills the points and polygons (vtkCatadioptricTriangleBins
// reads vtkPolyData) between Start() and Finish().
//
// The bands stay BandHeight rows high: the rasteriser evaluates its attribute planes from the
// clipped corner of each band, so the band boundaries are part of the pixels' exact values
// (rounding of the last bit). The threads are balanced instead by drawing the bands from most to
// fewest triangles (GetBandByLoad), the empty ones, which only write their background, last.
// Indices are 32-bit: at most 2^32 - 1 points, polygons and triangles per frame. The scratch
// memory is kept between calls (a frame reuses the last frame's buffers).
#ifndef catarTriangleBins_h
#define catarTriangleBins_h

#include "Rasterizer.h" // for catar::SnappedTriangle

#include <algorithm>  // for std::copy
#include <cstdint>    // for std::uint32_t
#include <functional> // for std::function
#include <limits>     // for std::numeric_limits
#include <string>     // for std::string
#include <vector>     // for std::vector

namespace catar
{
class TriangleBins
{
public:
  /// Rows per band.
  static constexpr int BandHeight = 32;

  /// How the meshes are drawn.
  struct Options
  {
    int Width = 0;                           ///< image columns
    int Height = 0;                          ///< image rows
    float Solid[4] = { 0.f, 0.f, 0.f, 1.f }; ///< RGBA of meshes without a colour array
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

  TriangleBins();
  ~TriangleBins();
  TriangleBins(const TriangleBins&) = delete;
  TriangleBins& operator=(const TriangleBins&) = delete;

  /// Triangles of visible polygons (whether or not they draw a pixel), and triangles of polygons
  /// whose Visible flag is 0.
  std::int64_t GetNumberOfTriangles() const { return this->NumberOfTriangles; }
  std::int64_t GetNumberOfSkippedTriangles() const { return this->NumberOfSkipped; }

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

protected:
  // ---- For the reader (between Start and Finish) ----
  enum class ColourSource : std::uint8_t
  {
    PointBytes,  // unsigned char point colours, kept with the points: Point::Rgba
    PointFloats, // any other point colours: PointColours
    Cell,        // cell colours: CellColours
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
  // per triangle. X == kBadPoint when it cannot be drawn (a non-finite attribute, or outside the
  // rasteriser's guard band).
  struct Point
  {
    std::int32_t X, Y;
    std::uint8_t Rgba[4];
  };
  /// Snapped coordinates lie within +-2^28 + 1, so this is never one.
  static constexpr std::int32_t kBadPoint = std::numeric_limits<std::int32_t>::min();
  // CellStates values.
  static constexpr std::uint8_t kInvisible = 0; // Visible == 0: skipped
  static constexpr std::uint8_t kNothing = 1;   // visible, colour not finite: draws nothing
  static constexpr std::uint8_t kDrawable = 2;
  // A mesh as drawing reads it.
  struct MeshInfo
  {
    ColourSource Colours = ColourSource::Solid;
    Rgba Solid{};               // Options::Solid with Opacity
    bool SolidValid = true;     // Solid is finite
    int Texture = -1;           // texture index, or -1
    bool TextureOpaque = true;  // the texture has no alpha below 255
    std::int64_t PointBase = 0; // global index of the first point
    std::int64_t CellBase = 0;  // global index of the first polygon
  };
  // A range of a mesh's points or polygons read by one task; for polygons, also the number of
  // triangles they make (Count) or skip (Skipped), the place of the first one (First), and how
  // many of them can draw a pixel (Drawable, stored from First on).
  struct Chunk
  {
    int Mesh = 0;
    std::int64_t Begin = 0, End = 0;
    std::int64_t Count = 0, Skipped = 0, First = 0, Drawable = 0;
  };

  /// Starts a frame: the options (Samples clamped), the bands, the byte tables; no meshes.
  /// threadCount: the loops' thread count, asked for only when a loop has work to share.
  void Start(const Options& options, int (*threadCount)());
  /// Adds a mesh of `points` points and `cells` polygons (its chunks, its global bases); returns
  /// its index.
  int AddMesh(MeshInfo mesh, std::int64_t points, std::int64_t cells);
  /// Sizes the per-point and per-polygon arrays for the meshes added. False with `error` when
  /// they do not fit the 32-bit indices.
  bool Allocate(std::string& error);
  /// The threads of a loop of n tasks of `grain` (1 when they cannot be shared).
  int LoopThreads(std::int64_t n, std::int64_t grain) const;
  /// Makes the triangles (makeTriangles(chunk) for each polygon chunk, in parallel: it calls
  /// MakeTriangles with the chunk's polygons), orders and bins them. False with `error` when
  /// they do not fit the 32-bit indices.
  bool Finish(const std::function<void(Chunk&)>& makeTriangles, std::string& error);
  /// The triangles of the polygons of chunk that can draw a pixel, from chunk.First on (polygon c
  /// of the mesh: connectivity[offsets[c]] ... connectivity[offsets[c + 1] - 1]);
  /// chunk.Drawable receives their number. Instantiated for int, long and long long indices.
  template<typename Index>
  void MakeTriangles(Chunk& chunk, const Index* offsets, const Index* connectivity);

  Options Opts;
  float Bytes[256];      // unsigned char colour components as floats
  float AlphaBytes[256]; // unsigned char alpha as a float, times Opacity
  std::vector<MeshInfo> Meshes;
  std::vector<Chunk> PointChunks;
  std::vector<Chunk> CellChunks;
  // Per point (global index): position (and colour bytes), float colour (PointFloats meshes),
  // depth (Options::Depths), texture coordinates (textured meshes).
  std::vector<Point> Points;
  std::vector<Rgba> PointColours;
  std::vector<float> PointDepths;
  std::vector<TCoord> PointTCoords;
  // Per polygon (global index): state (kInvisible, kNothing, kDrawable); colour (Cell meshes),
  // id, CentroidDepth (merging meshes).
  std::vector<std::uint8_t> CellStates;
  std::vector<Rgba> CellColours;
  std::vector<catar::RasterId> CellIds;
  std::vector<double> CellDepths;

private:
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
  // One task's part of the drawing order, binned: band b's triangles are
  // Refs[Start[b], Start[b + 1]).
  struct Part
  {
    std::vector<std::uint32_t> Refs;
    std::vector<std::uint32_t> Start;
  };

  void OrderTriangles();
  template<typename RefAt>
  void BinPart(Part& part, std::int64_t n, RefAt&& refAt) const;

  int (*ThreadCount)() = nullptr;
  std::int64_t LastPoints = 0; // points and polygons of the last mesh added
  std::int64_t LastCells = 0;
  int NumberOfBands = 0;
  std::int64_t NumberOfTriangles = 0;
  std::int64_t NumberOfSkipped = 0;
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

inline void TriangleBins::Get(std::uint32_t ref, catar::SnappedTriangle& t, Info& info) const
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

} // namespace catar

#endif
