#include "TriangleBins.h"

#include "Parallel.h"
#include "Polygons.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <numeric>

namespace catar
{
namespace
{
// Task sizes: large enough that a task's overhead is negligible, small enough that the bunny's
// 69k triangles make enough tasks (17) for the threads to finish together.
constexpr std::int64_t kPointsPerChunk = 16384;
constexpr std::int64_t kCellsPerChunk = 4096;
constexpr std::int64_t kTrianglesPerChunk = 16384;
constexpr std::int64_t kMaxIndex = std::numeric_limits<std::uint32_t>::max();

// An unsigned char colour component as the VTK colour arrays read it (value * (1.0 / 255.0) in
// double, then float). A 3-component array's alpha is 1: stored as the byte 255, which reads as
// exactly 1.
float ByteComponent(int b)
{
  return static_cast<float>(static_cast<double>(b) * (1.0 / 255.0));
}
static_assert(static_cast<float>(255.0 * (1.0 / 255.0)) == 1.0f, "255 must read as alpha 1");

bool Finite(const float c[4])
{
  return std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]) && std::isfinite(c[3]);
}

// Painter-sorted polygons visit their points in no particular order, and a large mesh's points
// do not fit the caches: MakeTriangles asks for the points of the polygon kAhead places ahead
// while it works on the current one, so that their loads overlap (measured on a 1M-triangle
// sphere: 23 -> 18 ms in one thread; no change on the bunny, whose points stay in the cache).
constexpr std::int64_t kAhead = 16;
} // namespace

TriangleBins::TriangleBins() = default;
TriangleBins::~TriangleBins() = default;

void TriangleBins::Start(const Options& options, int (*threadCount)())
{
  this->Opts = options;
  this->Opts.Samples = std::min(std::max(options.Samples, 1), catar::kMaxEdgeSamples);
  this->ThreadCount = threadCount;
  this->NumberOfBands = (options.Height + BandHeight - 1) / BandHeight;
  for (int b = 0; b < 256; ++b)
  {
    this->Bytes[b] = ByteComponent(b);
    this->AlphaBytes[b] = ByteComponent(b) * options.Opacity;
  }
  this->Meshes.clear();
  this->PointChunks.clear();
  this->CellChunks.clear();
}

int TriangleBins::AddMesh(MeshInfo mesh, std::int64_t points, std::int64_t cells)
{
  const int index = static_cast<int>(this->Meshes.size());
  std::copy(this->Opts.Solid, this->Opts.Solid + 4, mesh.Solid.C);
  mesh.Solid.C[3] *= this->Opts.Opacity;
  mesh.SolidValid = Finite(mesh.Solid.C);
  mesh.PointBase = this->Meshes.empty() ? 0 : this->Meshes.back().PointBase + this->LastPoints;
  mesh.CellBase = this->Meshes.empty() ? 0 : this->Meshes.back().CellBase + this->LastCells;
  for (std::int64_t b = 0; b < points; b += kPointsPerChunk)
  {
    this->PointChunks.push_back(Chunk{ index, b, std::min(points, b + kPointsPerChunk) });
  }
  for (std::int64_t b = 0; b < cells; b += kCellsPerChunk)
  {
    this->CellChunks.push_back(Chunk{ index, b, std::min(cells, b + kCellsPerChunk) });
  }
  this->LastPoints = points;
  this->LastCells = cells;
  this->Meshes.push_back(mesh);
  return index;
}

bool TriangleBins::Allocate(std::string& error)
{
  const std::int64_t nPoints =
    this->Meshes.empty() ? 0 : this->Meshes.back().PointBase + this->LastPoints;
  const std::int64_t nCells =
    this->Meshes.empty() ? 0 : this->Meshes.back().CellBase + this->LastCells;
  if (nPoints > kMaxIndex || nCells > kMaxIndex ||
    this->Meshes.size() > std::numeric_limits<std::uint16_t>::max())
  {
    error = "Too many points, polygons or meshes for one frame (at most 2^32 - 1 points and "
            "polygons and 65535 meshes).";
    return false;
  }
  bool anyPointFloats = false, anyCellColours = false, anyTexture = false;
  for (const MeshInfo& m : this->Meshes)
  {
    anyPointFloats = anyPointFloats || m.Colours == ColourSource::PointFloats;
    anyCellColours = anyCellColours || m.Colours == ColourSource::Cell;
    anyTexture = anyTexture || m.Texture >= 0;
  }
  const Options& options = this->Opts;
  this->Points.resize(static_cast<size_t>(nPoints));
  this->PointColours.resize(anyPointFloats ? static_cast<size_t>(nPoints) : 0);
  this->PointDepths.resize(options.Depths ? static_cast<size_t>(nPoints) : 0);
  this->PointTCoords.resize(anyTexture ? static_cast<size_t>(nPoints) : 0);
  this->CellStates.resize(static_cast<size_t>(nCells));
  this->CellColours.resize(anyCellColours ? static_cast<size_t>(nCells) : 0);
  this->CellIds.resize(options.Ids ? static_cast<size_t>(nCells) : 0);
  this->CellDepths.resize(options.MergeByDepth ? static_cast<size_t>(nCells) : 0);
  return true;
}

int TriangleBins::LoopThreads(std::int64_t n, std::int64_t grain) const
{
  // The thread count is asked for only when the loop can use threads (asking may cost).
  return n > std::max<std::int64_t>(grain, 1) && this->ThreadCount
    ? std::max(1, this->ThreadCount())
    : 1;
}

bool TriangleBins::Finish(const std::function<void(Chunk&)>& makeTriangles, std::string& error)
{
  // Each chunk's first triangle: the triangles keep the polygons' order. A chunk stores only the
  // triangles that can draw a pixel, from its first place on: the places after them stay unused.
  std::int64_t nTriangles = 0;
  this->NumberOfSkipped = 0;
  for (Chunk& c : this->CellChunks)
  {
    c.First = nTriangles;
    nTriangles += c.Count;
    this->NumberOfSkipped += c.Skipped;
  }
  this->NumberOfTriangles = nTriangles;
  if (nTriangles > kMaxIndex)
  {
    error = "Too many triangles for one frame (at most 2^32 - 1).";
    return false;
  }
  // Grown, never shrunk: the number of visible triangles changes from frame to frame, and
  // growing again would value-initialise the places again.
  if (this->Triangles.size() < static_cast<size_t>(nTriangles))
  {
    this->Triangles.resize(static_cast<size_t>(nTriangles));
    this->Sources.resize(static_cast<size_t>(nTriangles));
  }

  // The triangles; in cell order each task also bins its own (a part per chunk).
  this->Sequenced = this->Opts.MergeByDepth || this->Opts.DepthBuffer;
  if (!this->Sequenced)
  {
    this->Parts.resize(this->CellChunks.size());
  }
  // One chunk per task: a range of chunks per task left a thread idle for the last range's
  // length at the end.
  const std::int64_t nChunks = static_cast<std::int64_t>(this->CellChunks.size());
  parallel::ForEachIndex(0, nChunks, this->LoopThreads(nChunks, 0), [&](std::int64_t c) {
    Chunk& chunk = this->CellChunks[c];
    makeTriangles(chunk);
    if (!this->Sequenced)
    {
      const std::uint32_t first = static_cast<std::uint32_t>(chunk.First);
      this->BinPart(this->Parts[c], chunk.Drawable,
        [first](std::int64_t i) { return first + static_cast<std::uint32_t>(i); });
    }
  });

  // Any other order: made, then binned slice by slice.
  if (this->Sequenced)
  {
    this->OrderTriangles();
    const std::int64_t n = static_cast<std::int64_t>(this->Sequence.size());
    const std::int64_t nParts = (n + kTrianglesPerChunk - 1) / kTrianglesPerChunk;
    this->Parts.resize(static_cast<size_t>(nParts));
    parallel::For(
      0, nParts, 1, this->LoopThreads(nParts, 1), [&](std::int64_t p0, std::int64_t p1) {
        for (std::int64_t p = p0; p < p1; ++p)
        {
          const std::uint32_t* slice = this->Sequence.data() + p * kTrianglesPerChunk;
          this->BinPart(this->Parts[p], std::min(kTrianglesPerChunk, n - p * kTrianglesPerChunk),
            [slice](std::int64_t i) { return slice[i]; });
        }
      });
  }

  // Bands from most to fewest triangles.
  const int nBands = this->NumberOfBands;
  this->BandLoads.assign(static_cast<size_t>(nBands), 0);
  std::uint64_t total = 0;
  for (const Part& part : this->Parts)
  {
    for (int b = 0; b < nBands; ++b)
    {
      this->BandLoads[b] += part.Start[b + 1] - part.Start[b];
    }
    total += part.Refs.size();
  }
  if (total > kMaxIndex)
  {
    error = "Too many triangles in the bands for one frame (at most 2^32 - 1).";
    return false;
  }
  this->BandsByLoad.resize(static_cast<size_t>(nBands));
  std::iota(this->BandsByLoad.begin(), this->BandsByLoad.end(), 0);
  std::stable_sort(this->BandsByLoad.begin(), this->BandsByLoad.end(),
    [this](int a, int b) { return this->BandLoads[a] > this->BandLoads[b]; });
  return true;
}

// The triangles of the polygons of a chunk that can draw a pixel, each with the rows it can draw,
// from chunk.First on; chunk.Drawable receives their number.
template<typename Index>
void TriangleBins::MakeTriangles(Chunk& chunk, const Index* offsets, const Index* connectivity)
{
  const MeshInfo& m = this->Meshes[chunk.Mesh];
  const std::uint8_t* states = this->CellStates.data() + m.CellBase;
  const Point* points = this->Points.data();
  const catar::PixelRect image{ 0, 0, this->Opts.Width, this->Opts.Height };
  // Edge samples: the rows holding a sample or a pixel centre the triangle covers, samples found
  // on the grid of sub-pixel centres (catar::SampleGridPosition; at most 4 x 2^28 fits in 32
  // bits).
  const int samples = this->Opts.Samples;
  const catar::PixelRect fineImage{ 0, 0, samples * this->Opts.Width, samples * this->Opts.Height };
  const std::uint32_t pointBase = static_cast<std::uint32_t>(m.PointBase);
  const std::uint16_t mesh = static_cast<std::uint16_t>(chunk.Mesh);
  // Depth buffer: a triangle is opaque when alpha >= 1 at every vertex and its texture is opaque.
  const bool depthBuffer = this->Opts.DepthBuffer;
  const bool textureOpaque = m.Texture < 0 || m.TextureOpaque;
  const bool pointBytes = m.Colours == ColourSource::PointBytes;
  Triangle* const triangles = this->Triangles.data() + chunk.First;
  TriangleSource* const sources = this->Sources.data() + chunk.First;
  std::int64_t kept = 0;

  for (std::int64_t c = chunk.Begin; c < chunk.End; ++c)
  {
    const std::uint8_t cellState = states[c];
    const std::int64_t begin = offsets[c];
    const std::int64_t n = offsets[c + 1] - begin;
    if (c + kAhead < chunk.End)
    {
      const std::int64_t pb = offsets[c + kAhead];
      if (offsets[c + kAhead + 1] - pb >= 3)
      {
        parallel::Prefetch(points + pointBase + connectivity[pb]);
        parallel::Prefetch(points + pointBase + connectivity[pb + 1]);
        parallel::Prefetch(points + pointBase + connectivity[pb + 2]);
      }
    }
    if (cellState == kInvisible || n < 3)
    {
      continue;
    }
    const std::uint32_t cell = static_cast<std::uint32_t>(m.CellBase + c);
    catar::PolygonTriangles(
      connectivity + begin, static_cast<std::size_t>(n), [&](auto a, auto b, auto c3) {
        const std::uint32_t v[3] = { pointBase + static_cast<std::uint32_t>(a),
          pointBase + static_cast<std::uint32_t>(b), pointBase + static_cast<std::uint32_t>(c3) };
        const Point* p[3] = { points + v[0], points + v[1], points + v[2] };
        if ((cellState != kDrawable) | (p[0]->X == kBadPoint) | (p[1]->X == kBadPoint) |
          (p[2]->X == kBadPoint))
        {
          return;
        }
        const std::int32_t x[3] = { p[0]->X, p[1]->X, p[2]->X };
        const std::int32_t y[3] = { p[0]->Y, p[1]->Y, p[2]->Y };
        catar::PixelRect rows;
        if (samples == 1)
        {
          rows = catar::coveredPixelBounds(x, y, image);
        }
        else
        {
          std::int32_t fx[3], fy[3];
          catar::SampleGridPositions(x, samples, fx);
          catar::SampleGridPositions(y, samples, fy);
          // The rows of its samples and of its pixel centres (not samples when S is even).
          const catar::PixelRect fine = catar::coveredPixelBounds(fx, fy, fineImage);
          rows = catar::coveredPixelBounds(x, y, image);
          if (fine.y0 < fine.y1)
          {
            const int y0 = fine.y0 / samples, y1 = (fine.y1 - 1) / samples + 1;
            rows = rows.y0 < rows.y1
              ? catar::PixelRect{ 0, std::min(rows.y0, y0), 1, std::max(rows.y1, y1) }
              : catar::PixelRect{ 0, y0, 1, y1 };
          }
        }
        // Written whether or not it is kept, and kept by moving on: the test goes either way at
        // random, so a branch on it is mispredicted often (measured: 5% faster without).
        Triangle& t = triangles[kept];
        TriangleSource& source = sources[kept];
        kept += rows.y0 < rows.y1 ? 1 : 0;
        for (int i = 0; i < 3; ++i)
        {
          t.X[i] = x[i];
          t.Y[i] = y[i];
          source.V[i] = v[i];
          if (pointBytes)
          {
            // One 32-bit move; std::copy moved the four bytes one by one (~20% slower here).
            std::memcpy(t.Rgba[i], p[i]->Rgba, 4);
          }
        }
        source.Cell = cell;
        source.Row0 = rows.y0;
        source.Row1 = rows.y1 - 1;
        t.Mesh = mesh;
        t.Opaque = 0;
        if (depthBuffer)
        {
          bool opaque = textureOpaque;
          for (int i = 0; i < 3 && opaque; ++i)
          {
            const float alpha = m.Colours == ColourSource::PointBytes
              ? this->AlphaBytes[t.Rgba[i][3]]
              : m.Colours == ColourSource::PointFloats ? this->PointColours[v[i]].C[3]
              : m.Colours == ColourSource::Cell        ? this->CellColours[cell].C[3]
                                                       : m.Solid.C[3];
            opaque = alpha >= 1.0f;
          }
          t.Opaque = opaque ? 1 : 0;
        }
      });
  }
  chunk.Drawable = kept;
}

// The drawing order, when it is not the triangles' own (Sequenced): with several meshes, one
// far-to-near order by CentroidDepth in which each mesh keeps its order among equal depths (a
// stable sort of the concatenated meshes); with a depth buffer, the opaque triangles first, each
// part in that order.
void TriangleBins::OrderTriangles()
{
  std::vector<std::uint32_t>& seq = this->Sequence;
  seq.clear();
  for (const Chunk& chunk : this->CellChunks)
  {
    for (std::int64_t i = chunk.First; i < chunk.First + chunk.Drawable; ++i)
    {
      seq.push_back(static_cast<std::uint32_t>(i));
    }
  }
  if (this->Opts.MergeByDepth)
  {
    // A stable sort of the whole sequence, done as a stable sort of each mesh's run (meshes that
    // come painter-sorted are already in order) and stable merges of neighbouring runs.
    const double* depth = this->CellDepths.data();
    const auto farther = [this, depth](std::uint32_t a, std::uint32_t b) {
      return depth[this->Sources[a].Cell] > depth[this->Sources[b].Cell];
    };
    std::vector<size_t> runs{ 0 };
    for (size_t i = 1; i <= seq.size(); ++i)
    {
      if (i == seq.size() || this->Triangles[seq[i]].Mesh != this->Triangles[seq[i - 1]].Mesh)
      {
        const auto begin = seq.begin() + static_cast<std::ptrdiff_t>(runs.back());
        const auto end = seq.begin() + static_cast<std::ptrdiff_t>(i);
        if (!std::is_sorted(begin, end, farther))
        {
          std::stable_sort(begin, end, farther);
        }
        runs.push_back(i);
      }
    }
    std::vector<std::uint32_t>& merged = this->SequenceScratch;
    merged.resize(seq.size());
    while (runs.size() > 2)
    {
      std::vector<size_t> next{ 0 };
      for (size_t r = 0; r + 1 < runs.size(); r += 2)
      {
        const auto a = seq.begin() + static_cast<std::ptrdiff_t>(runs[r]);
        const auto b = seq.begin() + static_cast<std::ptrdiff_t>(runs[r + 1]);
        const size_t endIndex = r + 2 < runs.size() ? runs[r + 2] : runs[r + 1];
        const auto c = seq.begin() + static_cast<std::ptrdiff_t>(endIndex);
        // std::merge takes from the first run on ties: the earlier mesh stays first.
        std::merge(a, b, b, c, merged.begin() + static_cast<std::ptrdiff_t>(runs[r]), farther);
        next.push_back(endIndex);
      }
      seq.swap(merged);
      runs.swap(next);
    }
  }
  if (this->Opts.DepthBuffer)
  {
    std::stable_partition(
      seq.begin(), seq.end(), [this](std::uint32_t t) { return this->Triangles[t].Opaque != 0; });
  }
}

// Bins a part of the drawing order -- the triangles refAt(0), ..., refAt(n - 1) -- into the bands
// their rows meet, keeping their order: a count per band, offsets, and the same pass again
// writing each triangle at its place.
template<typename RefAt>
void TriangleBins::BinPart(Part& part, std::int64_t n, RefAt&& refAt) const
{
  const int nBands = this->NumberOfBands;
  const TriangleSource* sources = this->Sources.data();
  std::vector<std::uint32_t>& start = part.Start;
  start.assign(static_cast<size_t>(nBands) + 1, 0);
  for (std::int64_t i = 0; i < n; ++i)
  {
    const TriangleSource& t = sources[refAt(i)];
    for (int b = t.Row0 / BandHeight; b <= t.Row1 / BandHeight; ++b)
    {
      ++start[b + 1];
    }
  }
  for (int b = 0; b < nBands; ++b)
  {
    start[b + 1] += start[b];
  }
  part.Refs.resize(start[nBands]);
  // start[b] serves as band b's cursor, which leaves it at band b + 1's start: shifted back after.
  for (std::int64_t i = 0; i < n; ++i)
  {
    const std::uint32_t ref = refAt(i);
    const TriangleSource& t = sources[ref];
    for (int b = t.Row0 / BandHeight; b <= t.Row1 / BandHeight; ++b)
    {
      part.Refs[start[b]++] = ref;
    }
  }
  for (int b = nBands; b > 0; --b)
  {
    start[b] = start[b - 1];
  }
  start[0] = 0;
}

template void TriangleBins::MakeTriangles<int>(Chunk&, const int*, const int*);
template void TriangleBins::MakeTriangles<long>(Chunk&, const long*, const long*);
template void TriangleBins::MakeTriangles<long long>(Chunk&, const long long*, const long long*);
} // namespace catar
