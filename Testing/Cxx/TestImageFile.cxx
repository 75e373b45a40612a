// Image files checked before decoding (ImageFile.h): the header's size read without decoding,
// and a file cut short refused by name. The files are OpenCV's encoder's (libpng, libjpeg,
// OpenCV's BMP writer), then cut or altered here.
#include "CameraModel.h"
#include "ImageFile.h"

#include <gtest/gtest.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include <zlib.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

using namespace catar;

namespace
{
std::vector<unsigned char> Encoded(const std::string& ext, int width, int height)
{
  cv::Mat image(height, width, CV_8UC3);
  cv::randu(image, 0, 255);
  std::vector<unsigned char> bytes;
  EXPECT_TRUE(cv::imencode(ext, image, bytes)) << ext;
  return bytes;
}

void PutBigEndian32(unsigned char* p, std::uint32_t v)
{
  p[0] = static_cast<unsigned char>(v >> 24);
  p[1] = static_cast<unsigned char>(v >> 16);
  p[2] = static_cast<unsigned char>(v >> 8);
  p[3] = static_cast<unsigned char>(v);
}
} // namespace

TEST(ImageFile, WholeFilesGiveTheirSize)
{
  for (const std::string ext : { ".png", ".jpg", ".bmp" })
  {
    const std::vector<unsigned char> bytes = Encoded(ext, 37, 23);
    ImageHeader header;
    std::string error;
    ASSERT_TRUE(CheckImageBytes(bytes.data(), bytes.size(), "x" + ext, 1 << 20, header, error))
      << ext << ": " << error;
    EXPECT_EQ(header.width, 37) << ext;
    EXPECT_EQ(header.height, 23) << ext;
    EXPECT_FALSE(header.format.empty()) << ext;
  }
  // A format not read here is left to the decoder.
  const std::vector<unsigned char> tiff = Encoded(".tif", 8, 8);
  ImageHeader header;
  std::string error;
  EXPECT_TRUE(CheckImageBytes(tiff.data(), tiff.size(), "x.tif", 1 << 20, header, error));
  EXPECT_EQ(header.format, "");
}

// Every prefix of a PNG, JPEG or BMP shorter than the file is refused, with a sentence that says
// it is cut short (or corrupt), never passed on to the decoder.
TEST(ImageFile, EveryCutIsRefused)
{
  for (const std::string ext : { ".png", ".jpg", ".bmp" })
  {
    const std::vector<unsigned char> bytes = Encoded(ext, 40, 30);
    int refused = 0;
    for (std::size_t n = 3; n < bytes.size(); ++n)
    {
      ImageHeader header;
      std::string error;
      if (!CheckImageBytes(bytes.data(), n, "cut" + ext, 1 << 20, header, error))
      {
        ++refused;
        EXPECT_TRUE(error.find("cut short") != std::string::npos ||
          error.find("corrupt") != std::string::npos)
          << ext << " " << n << ": " << error;
      }
      else
      {
        ADD_FAILURE() << ext << ": the first " << n << " of " << bytes.size()
                      << " bytes were accepted";
      }
    }
    EXPECT_EQ(refused, static_cast<int>(bytes.size()) - 3) << ext;
  }
}

// A PNG whose header announces 20000 x 20000 pixels (1.2 GB decoded) is refused from its header;
// a changed byte fails the chunk's checksum; a JPEG with bytes after its end marker is whole.
TEST(ImageFile, BombsAndCorruption)
{
  std::vector<unsigned char> png = Encoded(".png", 16, 16);
  // IHDR: 8 bytes of signature, 4 of length, 4 of type, then width and height; its CRC follows
  // the 13 bytes of data.
  PutBigEndian32(&png[16], 20000);
  PutBigEndian32(&png[20], 20000);
  const uLong crc = crc32(crc32(0L, Z_NULL, 0), &png[12], 17);
  PutBigEndian32(&png[29], static_cast<std::uint32_t>(crc));
  ImageHeader header;
  std::string error;
  EXPECT_FALSE(CheckImageBytes(png.data(), png.size(), "bomb.png", kMaxImagePixels, header, error));
  EXPECT_NE(error.find("20000x20000 pixels, over the limit of 268435456 pixels (found in its "
                       "header, before decoding)"),
    std::string::npos)
    << error;
  EXPECT_TRUE(CheckImageBytes(png.data(), png.size(), "bomb.png", 400000000LL, header, error))
    << error;

  std::vector<unsigned char> altered = Encoded(".png", 16, 16);
  altered[40] ^= 0x10; // inside the IDAT chunk
  EXPECT_FALSE(CheckImageBytes(altered.data(), altered.size(), "a.png", 1 << 20, header, error));
  EXPECT_NE(error.find("fails its checksum"), std::string::npos) << error;

  std::vector<unsigned char> jpeg = Encoded(".jpg", 16, 16);
  jpeg.insert(jpeg.end(), { 0, 0, 0, 0 });
  EXPECT_TRUE(CheckImageBytes(jpeg.data(), jpeg.size(), "padded.jpg", 1 << 20, header, error))
    << error;
  EXPECT_FALSE(CheckImageBytes(jpeg.data(), 2, "tiny.jpg", 1 << 20, header, error));
}

TEST(ImageFile, ReadFromDisk)
{
  const std::string path = ::testing::TempDir() + "/catar_image_file.png";
  const std::vector<unsigned char> png = Encoded(".png", 9, 7);
  std::ofstream(path, std::ios::binary)
    .write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
  std::vector<unsigned char> bytes;
  ImageHeader header;
  std::string error;
  ASSERT_TRUE(ReadImageFileBytes(path, bytes, header, error)) << error;
  EXPECT_EQ(bytes, png);
  EXPECT_EQ(header.width, 9);
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(png.data()), 20);
  EXPECT_FALSE(ReadImageFileBytes(path, bytes, header, error));
  EXPECT_NE(error.find(path), std::string::npos) << error;
  std::ofstream(path, std::ios::trunc);
  EXPECT_FALSE(ReadImageFileBytes(path, bytes, header, error));
  EXPECT_NE(error.find("empty"), std::string::npos) << error;
  EXPECT_FALSE(ReadImageFileBytes("/nonexistent/x.png", bytes, header, error));
  std::remove(path.c_str());
}
