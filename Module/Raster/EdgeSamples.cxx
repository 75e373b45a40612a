#include "EdgeSamples.h"

#include "Parallel.h"
#include "TriangleBins.h"

#include <algorithm>
#include <cstdlib>
#include <limits>
#include <optional>

namespace catar
{
namespace
{
// Whether pixels p and q (RGBA) that show triangles ip and iq make an edge.
bool IsEdge(catar::RasterId ip, catar::RasterId iq, const std::uint8_t* p, const std::uint8_t* q)
{
  if (ip == iq)
  {
    return false;
  }
  if (ip < 0 || iq < 0)
  {
    return true;
  }
  for (int k = 0; k < 3; ++k)
  {
    if (std::abs(int(p[k]) - int(q[k])) > EdgeSamples::ContrastThreshold)
    {
      return true;
    }
  }
  return false;
}

// The pixels of band `rect` whose area a triangle's bounding box meets (a sample lies inside its
// pixel), inclusive bounds; empty when x0 > x1 or y0 > y1.
struct PixelBox
{
  int x0, y0, x1, y1;
};
PixelBox Box(
  const std::int32_t x[3], const std::int32_t y[3], const catar::PixelRect& rect, int width)
{
  constexpr int kHalf = 1 << (catar::kRasterSubPixelBits - 1);
  const auto pixel = [](std::int32_t c) {
    return static_cast<int>((static_cast<std::int64_t>(c) + kHalf) >> catar::kRasterSubPixelBits);
  };
  return PixelBox{ std::max(0, pixel(std::min({ x[0], x[1], x[2] }))),
    std::max(rect.y0, pixel(std::min({ y[0], y[1], y[2] }))),
    std::min(width - 1, pixel(std::max({ x[0], x[1], x[2] }))),
    std::min(rect.y1 - 1, pixel(std::max({ y[0], y[1], y[2] }))) };
}

// An opaque untextured triangle's colour as linear functions of the pixel position (the
// rasteriser's Gouraud planes, through the snapped vertices and their clamped colours).
struct ColourPlanes
{
  double x0, y0;              // vertex 0, pixels
  double c0[3], dx[3], dy[3]; // value at vertex 0 and steps, per channel

  explicit ColourPlanes(const catar::SnappedTriangle& t)
  {
    const double inv = 1.0 / (1 << catar::kRasterSubPixelBits);
    x0 = t.x[0] * inv;
    y0 = t.y[0] * inv;
    const double x10 = (t.x[1] - t.x[0]) * inv, y10 = (t.y[1] - t.y[0]) * inv;
    const double x20 = (t.x[2] - t.x[0]) * inv, y20 = (t.y[2] - t.y[0]) * inv;
    const double area = 1.0 / (x10 * y20 - y10 * x20);
    for (int ch = 0; ch < 3; ++ch)
    {
      const auto clamp = [](float v) { return std::min(1.0, std::max(0.0, double(v))); };
      c0[ch] = clamp(t.rgba[0][ch]);
      const double d1 = clamp(t.rgba[1][ch]) - c0[ch], d2 = clamp(t.rgba[2][ch]) - c0[ch];
      dx[ch] = (d1 * y20 - d2 * y10) * area;
      dy[ch] = (d2 * x10 - d1 * x20) * area;
    }
  }

  // The bytes the rasteriser writes for an opaque triangle at (x, y).
  void At(double x, double y, std::uint8_t* rgba) const
  {
    for (int ch = 0; ch < 3; ++ch)
    {
      const double v = std::min(1.0, std::max(0.0, c0[ch] + dx[ch] * (x - x0) + dy[ch] * (y - y0)));
      rgba[ch] =
        static_cast<std::uint8_t>(std::min(static_cast<int>(255.0f * float(v) + 0.5f), 255));
    }
    rgba[3] = 255;
  }
};

// Calls f(x, y, e) for the edge pixels (columns, row starts `rows` for the rows of rect) inside
// box, e their index.
template<typename F>
void ForEdgePixels(const PixelBox& box, const catar::PixelRect& rect,
  const std::vector<int>& columns, const std::vector<int>& rows, F&& f)
{
  for (int y = box.y0; y <= box.y1; ++y)
  {
    const int* first = columns.data() + rows[y - rect.y0];
    const int* last = columns.data() + rows[y - rect.y0 + 1];
    for (const int* c = std::lower_bound(first, last, box.x0); c != last && *c <= box.x1; ++c)
    {
      f(*c, y, static_cast<size_t>(c - columns.data()));
    }
  }
}
} // namespace

// What drawing a band's samples reads.
struct EdgeSamples::Context
{
  const TriangleBins& Bins;
  const std::vector<catar::TextureView>& Textures;
  const std::vector<char>& OpaqueTextures;
  const Background& Fill;
  int Samples;
  int Width;
};

// Every sample starts as the background; the band's triangles are drawn in drawing order.
void EdgeSamples::DrawInOrder(const Context& c, int b, Band& band, bool depth)
{
  const int samples = c.Samples;
  const int perPixel = samples * samples;
  const size_t n = band.Columns.size();
  const catar::PixelRect rect = c.Bins.GetBand(b);
  band.Skip.assign(n, 0);
  if (depth)
  {
    band.Depths.assign(n * perPixel, std::numeric_limits<float>::infinity());
  }
  for (int r = 0; r + rect.y0 < rect.y1; ++r)
  {
    for (int e = band.Rows[r]; e < band.Rows[r + 1]; ++e)
    {
      std::uint8_t rgba[4];
      c.Fill(band.Columns[e], rect.y0 + r, rgba);
      std::uint8_t* s = band.Samples.data() + static_cast<size_t>(e) * perPixel * 4;
      for (int k = 0; k < perPixel; ++k)
      {
        std::copy(rgba, rgba + 4, s + 4 * k);
      }
    }
  }
  catar::ImageView block{ nullptr, samples, samples, 4 * samples };
  catar::DepthView blockDepth{ nullptr, samples, samples, samples };
  catar::SnappedTriangle t;
  TriangleBins::Info info;
  c.Bins.ForEachTriangle(b, [&](std::uint32_t ref) {
    std::int32_t tx[3], ty[3];
    c.Bins.GetPositions(ref, tx, ty);
    bool got = false; // the rest of the triangle read only when it meets an edge pixel
    const catar::TextureView* texture = nullptr;
    ForEdgePixels(
      Box(tx, ty, rect, c.Width), rect, band.Columns, band.Rows, [&](int x, int y, size_t e) {
        if (!got)
        {
          c.Bins.Get(ref, t, info);
          texture = info.Texture >= 0 ? &c.Textures[info.Texture] : nullptr;
          blockDepth.write = info.Opaque;
          got = true;
        }
        block.data = band.Samples.data() + e * perPixel * 4;
        blockDepth.data = depth ? band.Depths.data() + e * perPixel : nullptr;
        catar::RasterResult result;
        if (!catar::rasterizeSamples(
              block, t, x, y, samples, depth ? &blockDepth : nullptr, texture, result))
        {
          band.Skip[e] = 1;
        }
      });
  });
}

// Painter order with opaque triangles only: the nearest triangle (last in the order) that covers
// a sample is the one it shows, so the triangles are visited nearest first and each sample is
// drawn once, by the first that covers it; hidden triangles cost a coverage test. The samples no
// triangle covers are the background. False, at the first triangle that is not opaque (which
// blends with what is behind it): the band is then drawn in order.
bool EdgeSamples::DrawFrontToBack(const Context& c, int b, Band& band)
{
  const int samples = c.Samples;
  const int perPixel = samples * samples;
  const std::uint32_t full = (1u << perPixel) - 1u; // at most 16 samples
  const size_t n = band.Columns.size();
  const catar::PixelRect rect = c.Bins.GetBand(b);
  band.Skip.assign(n, 0);
  band.Done.assign(n, 0);
  std::uint8_t scratch[4 * catar::kMaxEdgeSamples * catar::kMaxEdgeSamples];
  const catar::ImageView block{ scratch, samples, samples, 4 * samples };
  catar::SnappedTriangle t;
  TriangleBins::Info info;
  bool opaque = true;
  c.Bins.ForEachTriangleReverse(b, [&](std::uint32_t ref) {
    if (!opaque)
    {
      return;
    }
    std::int32_t tx[3], ty[3];
    c.Bins.GetPositions(ref, tx, ty);
    bool got = false;
    const catar::TextureView* texture = nullptr;
    std::optional<ColourPlanes> planes;
    ForEdgePixels(
      Box(tx, ty, rect, c.Width), rect, band.Columns, band.Rows, [&](int x, int y, size_t e) {
        if (band.Done[e] == full || !opaque)
        {
          return;
        }
        if (!got)
        {
          c.Bins.Get(ref, t, info);
          texture = info.Texture >= 0 ? &c.Textures[info.Texture] : nullptr;
          opaque = (info.Texture < 0 || c.OpaqueTextures[info.Texture]) && t.rgba[0][3] >= 1.0f &&
            t.rgba[1][3] >= 1.0f && t.rgba[2][3] >= 1.0f;
          if (!texture)
          {
            planes.emplace(t);
          }
          got = true;
          if (!opaque)
          {
            return;
          }
        }
        bool reachable = false;
        const std::uint32_t mask =
          catar::sampleCoverage(t, x, y, samples, reachable) & ~band.Done[e];
        if (!reachable)
        {
          band.Skip[e] = 1;
          band.Done[e] = full;
          return;
        }
        if (!mask)
        {
          return;
        }
        // Opaque: the covered samples get the triangle's colour whatever was under them; an
        // untextured one's found at the samples themselves.
        std::uint8_t* s = band.Samples.data() + e * perPixel * 4;
        if (texture)
        {
          catar::RasterResult result;
          catar::rasterizeSamples(block, t, x, y, samples, nullptr, texture, result);
        }
        for (int k = 0; k < perPixel; ++k)
        {
          if ((mask >> k) & 1u)
          {
            if (texture)
            {
              std::copy(scratch + 4 * k, scratch + 4 * k + 4, s + 4 * k);
            }
            else
            {
              const int column = k % samples; // the sample's place in the pixel's grid
              const int row = k / samples;
              planes->At(
                x - 0.5 + (column + 0.5) / samples, y - 0.5 + (row + 0.5) / samples, s + 4 * k);
            }
          }
        }
        band.Done[e] |= mask;
      });
  });
  if (!opaque)
  {
    return false;
  }
  for (int r = 0; r + rect.y0 < rect.y1; ++r)
  {
    for (int e = band.Rows[r]; e < band.Rows[r + 1]; ++e)
    {
      if (band.Done[e] == full)
      {
        continue;
      }
      std::uint8_t rgba[4];
      c.Fill(band.Columns[e], rect.y0 + r, rgba);
      std::uint8_t* s = band.Samples.data() + static_cast<size_t>(e) * perPixel * 4;
      for (int k = 0; k < perPixel; ++k)
      {
        if (!((band.Done[e] >> k) & 1u))
        {
          std::copy(rgba, rgba + 4, s + 4 * k);
        }
      }
    }
  }
  return true;
}

void EdgeSamples::Draw(const catar::ImageView& view, const catar::IdView& ids,
  const TriangleBins& bins, const std::vector<catar::TextureView>& textures,
  const std::vector<char>& opaqueTextures, const Background& background, bool depth, int threads)
{
  const int width = view.width;
  const int height = view.height;
  const int nBands = bins.GetNumberOfBands();
  const int samples = bins.GetSamples();
  const int perPixel = samples * samples;
  this->Bands.resize(static_cast<size_t>(nBands));
  this->NumberOfEdgePixels = 0;
  this->NumberOfUnsampled = 0;
  if (samples < 2)
  {
    return;
  }

  // The edge pixels of the bands that hold triangles (a pixel of another band has no sample any
  // triangle covers). Read-only on the image: every pixel looks at its four neighbours.
  parallel::ForEachIndex(0, nBands, nBands > 1 ? threads : 1, [&](std::int64_t i) {
    const int b = bins.GetBandByLoad(static_cast<int>(i));
    Band& band = this->Bands[b];
    band.Columns.clear();
    band.Rows.clear();
    if (bins.GetBandLoad(b) == 0)
    {
      return;
    }
    const catar::PixelRect rect = bins.GetBand(b);
    band.Mask.assign(static_cast<size_t>(width) * (rect.y1 - rect.y0), 0);
    // A pixel whose centre shows the frame and one of whose samples a triangle covers: the tips
    // and slivers that reach into a pixel without covering its centre nor any neighbour's. And
    // the columns the band's triangles reach (no edge outside them but next to them).
    int x0 = width, x1 = -1;
    bins.ForEachTriangle(b, [&](std::uint32_t ref) {
      std::int32_t tx[3], ty[3];
      bins.GetPositions(ref, tx, ty);
      const PixelBox box = Box(tx, ty, rect, width);
      x0 = std::min(x0, box.x0);
      x1 = std::max(x1, box.x1);
      std::int32_t fx[3], fy[3];
      catar::SampleGridPositions(tx, samples, fx);
      catar::SampleGridPositions(ty, samples, fy);
      for (int y = box.y0; y <= box.y1; ++y)
      {
        std::uint8_t* mask = band.Mask.data() + static_cast<size_t>(width) * (y - rect.y0);
        const catar::RasterId* row = ids.at(0, y);
        for (int x = box.x0; x <= box.x1; ++x)
        {
          if (mask[x] || row[x] >= 0)
          {
            continue;
          }
          // coveredPixelBounds is exact for up to 2 x 2 samples: the block, 2 x 2 at a time.
          for (int j = 0; j < samples && !mask[x]; j += 2)
          {
            for (int i = 0; i < samples && !mask[x]; i += 2)
            {
              const catar::PixelRect block{ samples * x + i, samples * y + j,
                std::min(samples * x + i + 2, samples * x + samples),
                std::min(samples * y + j + 2, samples * y + samples) };
              const catar::PixelRect covered = catar::coveredPixelBounds(fx, fy, block);
              mask[x] = covered.x0 < covered.x1 && covered.y0 < covered.y1 ? 1 : 0;
            }
          }
        }
      }
    });
    // Neighbours showing different triangles (every pixel looks at its eight neighbours).
    for (int y = rect.y0; y < rect.y1; ++y)
    {
      std::uint8_t* mask = band.Mask.data() + static_cast<size_t>(width) * (y - rect.y0);
      const catar::RasterId* row = ids.at(0, y);
      const catar::RasterId* up = y > 0 ? ids.at(0, y - 1) : nullptr;
      const catar::RasterId* down = y + 1 < height ? ids.at(0, y + 1) : nullptr;
      for (int x = std::max(0, x0 - 1); x <= std::min(width - 1, x1 + 1); ++x)
      {
        const catar::RasterId id = row[x];
        const int xa = x > 0 ? x - 1 : x, xb = x + 1 < width ? x + 1 : x;
        bool same = row[xa] == id && row[xb] == id;
        for (const catar::RasterId* r : { up, down })
        {
          same = same && (!r || (r[xa] == id && r[x] == id && r[xb] == id));
        }
        if (same || mask[x])
        {
          continue;
        }
        // The eight neighbours: a corner of an object can reach into a pixel diagonally.
        const std::uint8_t* p = view.pixel(x, y);
        bool edge = false;
        for (int dy = -1; dy <= 1 && !edge; ++dy)
        {
          const catar::RasterId* r = dy < 0 ? up : dy > 0 ? down : row;
          for (int nx = xa; r && nx <= xb && !edge; ++nx)
          {
            edge = IsEdge(id, r[nx], p, view.pixel(nx, y + dy));
          }
        }
        mask[x] = edge ? 1 : 0;
      }
    }
    for (int y = rect.y0; y < rect.y1; ++y)
    {
      band.Rows.push_back(static_cast<int>(band.Columns.size()));
      const std::uint8_t* mask = band.Mask.data() + static_cast<size_t>(width) * (y - rect.y0);
      for (int x = 0; x < width; ++x)
      {
        if (mask[x])
        {
          band.Columns.push_back(x);
        }
      }
    }
    band.Rows.push_back(static_cast<int>(band.Columns.size()));
  });

  // The samples of each band's edge pixels, then their mean. Writes only the band's own pixels.
  const Context context{ bins, textures, opaqueTextures, background, samples, width };
  parallel::ForEachIndex(0, nBands, nBands > 1 ? threads : 1, [&](std::int64_t i) {
    const int b = bins.GetBandByLoad(static_cast<int>(i));
    Band& band = this->Bands[b];
    const size_t n = band.Columns.size();
    if (n == 0)
    {
      return;
    }
    band.Samples.resize(n * perPixel * 4);
    if (depth || !DrawFrontToBack(context, b, band))
    {
      DrawInOrder(context, b, band, depth);
    }
    const catar::PixelRect rect = bins.GetBand(b);
    for (int r = 0; r + rect.y0 < rect.y1; ++r)
    {
      for (int e = band.Rows[r]; e < band.Rows[r + 1]; ++e)
      {
        if (band.Skip[e])
        {
          continue;
        }
        const std::uint8_t* s = band.Samples.data() + static_cast<size_t>(e) * perPixel * 4;
        std::uint8_t* out = view.pixel(band.Columns[e], rect.y0 + r);
        for (int ch = 0; ch < 4; ++ch)
        {
          int sum = 0;
          for (int k = 0; k < perPixel; ++k)
          {
            sum += s[4 * k + ch];
          }
          out[ch] = static_cast<std::uint8_t>((sum + perPixel / 2) / perPixel);
        }
      }
    }
  });
  for (const Band& band : this->Bands)
  {
    this->NumberOfEdgePixels += static_cast<std::int64_t>(band.Columns.size());
    if (!band.Columns.empty())
    {
      this->NumberOfUnsampled += std::count(band.Skip.begin(), band.Skip.end(), std::uint8_t(1));
    }
  }
}
} // namespace catar
