// Image accuracy metrics: silhouettes (colour and triangle ids), IoU against the analytic value of
// two shifted discs, boundary distances (exact values on squares, the distance transform against
// brute force), PSNR of a known offset, SSIM, triangle id differences, empty masks, row order, the
// difference image, and invalid input.
#include "ImageMetrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

using namespace catar;

namespace
{
constexpr double kPi = 3.14159265358979323846;

struct Image
{
  int w = 0;
  int h = 0;
  std::vector<std::uint8_t> buf; // top-down rows, RGBA

  Image(int width, int height, std::uint8_t r = 0, std::uint8_t g = 0, std::uint8_t b = 0,
    std::uint8_t a = 255)
    : w(width)
    , h(height)
    , buf(static_cast<std::size_t>(4 * width * height))
  {
    for (int y = 0; y < h; ++y)
    {
      for (int x = 0; x < w; ++x)
      {
        set(x, y, r, g, b, a);
      }
    }
  }

  void set(int x, int y, std::uint8_t r, std::uint8_t g, std::uint8_t b, std::uint8_t a = 255)
  {
    std::uint8_t* p = &buf[4 * (static_cast<std::size_t>(y) * w + x)];
    p[0] = r;
    p[1] = g;
    p[2] = b;
    p[3] = a;
  }

  const std::uint8_t* at(int x, int y) const
  {
    return &buf[4 * (static_cast<std::size_t>(y) * w + x)];
  }

  ConstImageView view() const
  {
    return ConstImageView{ buf.data(), w, h, 4 * static_cast<std::ptrdiff_t>(w) };
  }

  // The same logical image stored bottom-up (memory row h-1-y holds logical row y).
  Image flippedStorage() const
  {
    Image f(w, h);
    for (int y = 0; y < h; ++y)
    {
      std::copy(at(0, y), at(0, y) + 4 * w, &f.buf[4 * static_cast<std::size_t>(h - 1 - y) * w]);
    }
    return f;
  }
  ConstImageView flippedView() const
  {
    return ConstImageView{ buf.data() + 4 * static_cast<std::ptrdiff_t>(w) * (h - 1), w, h,
      -4 * static_cast<std::ptrdiff_t>(w) };
  }
};

ImageInput Input(const Image& image)
{
  ImageInput in;
  in.color = image.view();
  return in;
}

// A filled disc: pixel centres within radius r of (cx, cy).
void Disc(Image& image, double cx, double cy, double r, std::uint8_t v)
{
  for (int y = 0; y < image.h; ++y)
  {
    for (int x = 0; x < image.w; ++x)
    {
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r)
      {
        image.set(x, y, v, v, v);
      }
    }
  }
}

// A filled square [x0, x1] x [y0, y1] (inclusive).
void Square(Image& image, int x0, int y0, int x1, int y1, std::uint8_t v)
{
  for (int y = y0; y <= y1; ++y)
  {
    for (int x = x0; x <= x1; ++x)
    {
      image.set(x, y, v, v, v);
    }
  }
}

// A smooth, non-constant test picture.
Image Gradient(int w, int h)
{
  Image image(w, h);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      image.set(x, y, static_cast<std::uint8_t>(40 + 2 * x), static_cast<std::uint8_t>(30 + 3 * y),
        static_cast<std::uint8_t>(100 + (x + y) % 50));
    }
  }
  return image;
}

// A disc painted with the colours of Gradient on a black background.
Image TexturedDisc(int w, int h, double cx, double cy, double r)
{
  const Image gradient = Gradient(w, h);
  Image image(w, h);
  for (int y = 0; y < h; ++y)
  {
    for (int x = 0; x < w; ++x)
    {
      if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r)
      {
        const std::uint8_t* p = gradient.at(x, y);
        image.set(x, y, p[0], p[1], p[2]);
      }
    }
  }
  return image;
}

const double kInf = std::numeric_limits<double>::infinity();
} // namespace

TEST(ImageMetrics, IdenticalImages)
{
  const Image a = TexturedDisc(64, 48, 30, 20, 12);
  const ImageComparison r = CompareImages(Input(a), Input(a));
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.silhouetteIoU, 1.0);
  EXPECT_EQ(r.psnr, kInf);
  EXPECT_DOUBLE_EQ(r.ssim, 1.0);
  EXPECT_EQ(r.meanBoundaryDistance, 0.0);
  EXPECT_EQ(r.maxBoundaryDistance, 0.0);
  EXPECT_EQ(r.pixels, 64u * 48u);
  EXPECT_EQ(r.psnrPixels, 64u * 48u);
  EXPECT_GT(r.boundaryPixelsA, 0u);
  EXPECT_EQ(r.boundaryPixelsA, r.boundaryPixelsB);
  EXPECT_FALSE(r.trianglesCompared);
  EXPECT_EQ(r.comparedTrianglePixels, 0u);
}

TEST(ImageMetrics, ShiftedDisc)
{
  const double radius = 25;
  const double shift = 3;
  Image a(100, 100);
  Image b(100, 100);
  Disc(a, 48, 50, radius, 200);
  Disc(b, 48 + shift, 50, radius, 200);
  const ImageComparison r = CompareImages(Input(a), Input(b));
  ASSERT_TRUE(r.ok()) << r.error;

  const double lens = 2 * radius * radius * std::acos(shift / (2 * radius)) -
    0.5 * shift * std::sqrt(4 * radius * radius - shift * shift);
  const double iou = lens / (2 * kPi * radius * radius - lens);
  EXPECT_NEAR(r.silhouetteIoU, iou, 0.02 * iou);
  EXPECT_NEAR(r.maxBoundaryDistance, shift, 0.5);
  EXPECT_GT(r.meanBoundaryDistance, 1.0);
  EXPECT_LT(r.meanBoundaryDistance, 3.0);
  EXPECT_EQ(r.silhouettePixelsA, r.silhouettePixelsB);
}

TEST(ImageMetrics, SquareOnePixelLarger)
{
  // A: 20x20 square; B: the same grown by one pixel on each side.
  Image a(60, 60);
  Image b(60, 60);
  Square(a, 20, 20, 39, 39, 255);
  Square(b, 19, 19, 40, 40, 255);
  const PixelMask ba = BoundaryMask(SilhouetteMask(Input(a), CompareOptions()));
  const PixelMask bb = BoundaryMask(SilhouetteMask(Input(b), CompareOptions()));
  const BoundaryDistances d = ComputeBoundaryDistances(ba, bb);
  EXPECT_EQ(d.countA, 76u);
  EXPECT_EQ(d.countB, 84u);
  // Every boundary pixel of A is exactly 1 px from B's boundary, and so is every boundary pixel of
  // B except its four corners, which are sqrt(2) from A's corners.
  EXPECT_EQ(d.meanAToB, 1.0);
  EXPECT_EQ(d.maxAToB, 1.0);
  EXPECT_EQ(d.maxBToA, std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(d.meanBToA, (80.0 + 4 * std::sqrt(2.0)) / 84.0);

  const ImageComparison r = CompareImages(Input(a), Input(b));
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_EQ(r.maxBoundaryDistance, std::sqrt(2.0));
  EXPECT_DOUBLE_EQ(r.meanBoundaryDistance, (76.0 + 80.0 + 4 * std::sqrt(2.0)) / 160.0);
  EXPECT_DOUBLE_EQ(r.silhouetteIoU, 400.0 / 484.0);
}

TEST(ImageMetrics, DistanceTransformMatchesBruteForce)
{
  std::mt19937 rng(7);
  for (int trial = 0; trial < 5; ++trial)
  {
    PixelMask sites;
    sites.width = 37 + trial;
    sites.height = 23 + 3 * trial;
    sites.data.assign(static_cast<std::size_t>(sites.width) * sites.height, 0);
    for (auto& v : sites.data)
    {
      v = (rng() % 50) == 0 ? 1 : 0;
    }
    sites.data[rng() % sites.data.size()] = 1;
    const std::vector<double> dt = SquaredDistanceTransform(sites);
    ASSERT_EQ(dt.size(), sites.data.size());
    for (int y = 0; y < sites.height; ++y)
    {
      for (int x = 0; x < sites.width; ++x)
      {
        double best = kInf;
        for (int v = 0; v < sites.height; ++v)
        {
          for (int u = 0; u < sites.width; ++u)
          {
            if (sites.at(u, v))
            {
              best = std::min(best, static_cast<double>((x - u) * (x - u) + (y - v) * (y - v)));
            }
          }
        }
        ASSERT_EQ(dt[static_cast<std::size_t>(y) * sites.width + x], best) << x << "," << y;
      }
    }
  }
  PixelMask none;
  none.width = 5;
  none.height = 4;
  none.data.assign(20, 0);
  for (double v : SquaredDistanceTransform(none))
  {
    EXPECT_EQ(v, kInf);
  }
}

TEST(ImageMetrics, PsnrOfUniformOffset)
{
  Image a(33, 17, 100, 120, 140);
  Image b(33, 17, 110, 130, 150);
  const ImageComparison r = CompareImages(Input(a), Input(b));
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_NEAR(r.psnr, 20 * std::log10(255.0 / 10.0), 1e-9);
  // Alpha does not enter the PSNR.
  Image c(33, 17, 100, 120, 140, 0);
  EXPECT_EQ(ComputePSNR(a.view(), c.view()), kInf);
}

TEST(ImageMetrics, PsnrOverSilhouette)
{
  // The disc is (100,100,100) in A and (110,100,100) in B on a black background.
  Image a(40, 40);
  Image b(40, 40);
  Disc(a, 20, 20, 8, 100);
  Disc(b, 20, 20, 8, 100);
  std::size_t disc = 0;
  for (int y = 0; y < 40; ++y)
  {
    for (int x = 0; x < 40; ++x)
    {
      if (a.at(x, y)[0] == 100)
      {
        b.set(x, y, 110, 100, 100);
        ++disc;
      }
    }
  }
  CompareOptions options;
  options.psnrOverSilhouette = true;
  const ImageComparison inside = CompareImages(Input(a), Input(b), options);
  ASSERT_TRUE(inside.ok()) << inside.error;
  EXPECT_EQ(inside.psnrPixels, disc);
  EXPECT_NEAR(inside.psnr, 10 * std::log10(255.0 * 255.0 * 3.0 / 100.0), 1e-9);
  const ImageComparison all = CompareImages(Input(a), Input(b));
  EXPECT_EQ(all.psnrPixels, 1600u);
  EXPECT_NEAR(all.psnr, 10 * std::log10(255.0 * 255.0 * 3.0 * 1600.0 / (100.0 * disc)), 1e-9);
}

TEST(ImageMetrics, SsimDropsWithNoise)
{
  const Image a = Gradient(80, 60);
  Image b = a;
  std::mt19937 rng(3);
  std::normal_distribution<double> noise(0.0, 12.0);
  for (std::size_t i = 0; i < b.buf.size(); ++i)
  {
    if (i % 4 != 3)
    {
      b.buf[i] = static_cast<std::uint8_t>(std::clamp(b.buf[i] + noise(rng), 0.0, 255.0));
    }
  }
  const double same = ComputeSSIM(a.view(), a.view());
  EXPECT_DOUBLE_EQ(same, 1.0);
  const double noisy = ComputeSSIM(a.view(), b.view());
  EXPECT_LT(noisy, 0.99);
  EXPECT_GT(noisy, 0.0);
  // Symmetric.
  EXPECT_NEAR(ComputeSSIM(b.view(), a.view()), noisy, 1e-12);
  // Tiny images (smaller than the window) are accepted.
  Image tiny(1, 1, 10, 20, 30);
  EXPECT_DOUBLE_EQ(ComputeSSIM(tiny.view(), tiny.view()), 1.0);
}

TEST(ImageMetrics, TriangleIdDifferences)
{
  // 4x3 buffers; the colours are pure background, so the silhouettes come from the ids only.
  const std::vector<catar::RasterId> idsA = { -1, 0, 1, 2, 3, 3, -1, 4, 5, 6, 7, -1 };
  const std::vector<catar::RasterId> idsB = { -1, 0, 9, -1, 3, 4, 5, 4, -1, 6, 8, -1 };
  Image a(4, 3);
  Image b(4, 3);
  ImageInput ia = Input(a);
  ImageInput ib = Input(b);
  ia.triangleIds = TriangleIdView{ idsA.data(), 4, 3, 4 };
  ib.triangleIds = TriangleIdView{ idsB.data(), 4, 3, 4 };
  const ImageComparison r = CompareImages(ia, ib);
  ASSERT_TRUE(r.ok()) << r.error;
  EXPECT_TRUE(r.trianglesCompared);
  EXPECT_EQ(r.comparedTrianglePixels, 7u);
  EXPECT_EQ(r.differentTrianglePixels, 3u);
  EXPECT_EQ(r.silhouettePixelsA, 9u);
  EXPECT_EQ(r.silhouettePixelsB, 8u);
  EXPECT_DOUBLE_EQ(r.silhouetteIoU, 7.0 / 10.0);

  // The same buffers stored bottom-up with a negative stride.
  std::vector<catar::RasterId> flippedA(12), flippedB(12);
  for (int y = 0; y < 3; ++y)
  {
    for (int x = 0; x < 4; ++x)
    {
      flippedA[(2 - y) * 4 + x] = idsA[y * 4 + x];
      flippedB[(2 - y) * 4 + x] = idsB[y * 4 + x];
    }
  }
  std::size_t different = 0, compared = 0;
  EXPECT_TRUE(CountTriangleDifferences(TriangleIdView{ flippedA.data() + 8, 4, 3, -4 },
    TriangleIdView{ flippedB.data() + 8, 4, 3, -4 }, different, compared));
  EXPECT_EQ(compared, 7u);
  EXPECT_EQ(different, 3u);

  // Only one input with ids: no triangle comparison; B's silhouette comes from its colour.
  ImageInput noIds = Input(b);
  const ImageComparison one = CompareImages(ia, noIds);
  ASSERT_TRUE(one.ok()) << one.error;
  EXPECT_FALSE(one.trianglesCompared);
  EXPECT_EQ(one.comparedTrianglePixels, 0u);
  EXPECT_EQ(one.silhouettePixelsB, 0u);
}

TEST(ImageMetrics, EmptyMasks)
{
  Image empty(20, 20, 10, 20, 30);
  CompareOptions options;
  options.background = { { 10, 20, 30, 255 } };
  const ImageComparison both = CompareImages(Input(empty), Input(empty), options);
  ASSERT_TRUE(both.ok()) << both.error;
  EXPECT_EQ(both.silhouettePixelsA, 0u);
  EXPECT_EQ(both.silhouetteIoU, 1.0);
  EXPECT_EQ(both.meanBoundaryDistance, 0.0);
  EXPECT_EQ(both.maxBoundaryDistance, 0.0);

  Image object = empty;
  Square(object, 5, 5, 9, 9, 200);
  const ImageComparison one = CompareImages(Input(empty), Input(object), options);
  ASSERT_TRUE(one.ok()) << one.error;
  EXPECT_EQ(one.silhouettePixelsB, 25u);
  EXPECT_EQ(one.silhouetteIoU, 0.0);
  EXPECT_EQ(one.meanBoundaryDistance, kInf);
  EXPECT_EQ(one.maxBoundaryDistance, kInf);
  EXPECT_LT(one.psnr, kInf);
}

TEST(ImageMetrics, BackgroundToleranceAndImage)
{
  Image a(10, 10);
  a.set(2, 3, 3, 0, 0);
  a.set(5, 5, 0, 0, 0, 200); // differs in alpha only
  CompareOptions options;
  options.colorTolerance = 2;
  EXPECT_EQ(SilhouetteMask(Input(a), options).count(), 2u);
  options.colorTolerance = 3;
  EXPECT_EQ(SilhouetteMask(Input(a), options).count(), 1u);
  options.colorTolerance = 55;
  EXPECT_EQ(SilhouetteMask(Input(a), options).count(), 0u);

  // A background image instead of a colour.
  Image background = Gradient(10, 10);
  Image b = background;
  Square(b, 4, 4, 6, 6, 255);
  CompareOptions withImage;
  withImage.backgroundImage = background.view();
  const PixelMask mask = SilhouetteMask(Input(b), withImage);
  EXPECT_EQ(mask.count(), 9u);
  EXPECT_TRUE(mask.at(5, 5));
  EXPECT_FALSE(mask.at(3, 5));
}

TEST(ImageMetrics, RowOrderIndependent)
{
  const Image a = TexturedDisc(50, 40, 20, 18, 9);
  const Image b = TexturedDisc(50, 40, 22, 19, 10);
  const ImageComparison top = CompareImages(Input(a), Input(b));
  const Image fa = a.flippedStorage();
  const Image fb = b.flippedStorage();
  ImageInput ia;
  ia.color = fa.flippedView();
  ImageInput ib;
  ib.color = fb.flippedView();
  CompareOptions options;
  const ImageComparison bottom = CompareImages(ia, ib, options);
  ASSERT_TRUE(top.ok() && bottom.ok());
  EXPECT_EQ(top.silhouetteIoU, bottom.silhouetteIoU);
  EXPECT_EQ(top.meanBoundaryDistance, bottom.meanBoundaryDistance);
  EXPECT_EQ(top.maxBoundaryDistance, bottom.maxBoundaryDistance);
  EXPECT_EQ(top.psnr, bottom.psnr);
  EXPECT_EQ(top.ssim, bottom.ssim);
  EXPECT_LT(top.ssim, 1.0);
  EXPECT_GT(top.maxBoundaryDistance, 1.0);
  EXPECT_LT(top.silhouetteIoU, 1.0);
}

TEST(ImageMetrics, DifferenceImage)
{
  Image a(3, 2, 10, 200, 0);
  Image b(3, 2, 12, 100, 0);
  Image out(3, 2, 1, 1, 1, 1);
  ImageView outView{ out.buf.data(), 3, 2, 12 };
  EXPECT_EQ(DifferenceImage(a.view(), b.view(), outView), "");
  for (int y = 0; y < 2; ++y)
  {
    for (int x = 0; x < 3; ++x)
    {
      EXPECT_EQ(out.at(x, y)[0], 8);
      EXPECT_EQ(out.at(x, y)[1], 255);
      EXPECT_EQ(out.at(x, y)[2], 0);
      EXPECT_EQ(out.at(x, y)[3], 255);
    }
  }
  Image small(2, 2);
  ImageView smallView{ small.buf.data(), 2, 2, 8 };
  EXPECT_NE(DifferenceImage(a.view(), b.view(), smallView), "");
}

TEST(ImageMetrics, InvalidInput)
{
  Image a(10, 8);
  Image b(8, 10);
  const ImageComparison mismatch = CompareImages(Input(a), Input(b));
  EXPECT_FALSE(mismatch.ok());
  EXPECT_NE(mismatch.error.find("sizes differ"), std::string::npos) << mismatch.error;

  ImageInput null;
  EXPECT_FALSE(CompareImages(null, Input(a)).ok());
  EXPECT_FALSE(CompareImages(Input(a), null).ok());
  ImageInput nullData = Input(a);
  nullData.color.data = nullptr;
  EXPECT_FALSE(CompareImages(Input(a), nullData).ok());

  ImageInput zero = Input(a);
  zero.color.width = 0;
  EXPECT_FALSE(CompareImages(zero, zero).ok());

  ImageInput shortStride = Input(a);
  shortStride.color.rowStride = 4;
  EXPECT_FALSE(CompareImages(shortStride, Input(a)).ok());

  const std::vector<catar::RasterId> ids(10 * 7, 0);
  ImageInput wrongIds = Input(a);
  wrongIds.triangleIds = TriangleIdView{ ids.data(), 10, 7, 10 };
  EXPECT_FALSE(CompareImages(wrongIds, Input(a)).ok());
  wrongIds.triangleIds = TriangleIdView{ ids.data(), 10, 8, 0 };
  EXPECT_FALSE(CompareImages(Input(a), wrongIds).ok());

  CompareOptions badTolerance;
  badTolerance.colorTolerance = -1;
  EXPECT_FALSE(CompareImages(Input(a), Input(a), badTolerance).ok());
  badTolerance.colorTolerance = 256;
  EXPECT_FALSE(CompareImages(Input(a), Input(a), badTolerance).ok());

  Image bg(3, 3);
  CompareOptions badBackground;
  badBackground.backgroundImage = bg.view();
  EXPECT_FALSE(CompareImages(Input(a), Input(a), badBackground).ok());

  // The lower-level functions report NaN / false rather than crash.
  EXPECT_TRUE(std::isnan(ComputePSNR(a.view(), b.view())));
  EXPECT_TRUE(std::isnan(ComputeSSIM(a.view(), ConstImageView())));
  std::size_t different = 1, compared = 1;
  EXPECT_FALSE(CountTriangleDifferences(TriangleIdView(), TriangleIdView(), different, compared));
  EXPECT_EQ(different, 0u);
  EXPECT_EQ(compared, 0u);
  PixelMask m1;
  m1.width = 2;
  m1.height = 2;
  m1.data.assign(4, 1);
  PixelMask m2;
  EXPECT_TRUE(std::isnan(SilhouetteIoU(m1, m2)));
  EXPECT_TRUE(std::isnan(ComputeBoundaryDistances(m1, m2).max));
  EXPECT_EQ(SilhouetteMask(null, CompareOptions()).data.size(), 0u);
}
