#include "ImageFile.h"

#include "CameraModel.h" // kMaxImagePixels
#include "FileInput.h"

#include <zlib.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <fstream>

namespace catar
{
namespace
{
std::uint32_t BigEndian32(const unsigned char* p)
{
  return (std::uint32_t(p[0]) << 24) | (std::uint32_t(p[1]) << 16) | (std::uint32_t(p[2]) << 8) |
    std::uint32_t(p[3]);
}

std::uint32_t LittleEndian32(const unsigned char* p)
{
  return std::uint32_t(p[0]) | (std::uint32_t(p[1]) << 8) | (std::uint32_t(p[2]) << 16) |
    (std::uint32_t(p[3]) << 24);
}

bool CheckPng(const unsigned char* data, std::size_t size, const std::string& name,
  ImageHeader& header, std::string& error)
{
  std::size_t at = 8; // the signature
  bool first = true;
  for (;;)
  {
    if (size - at < 12)
    {
      error = "'" + name + "' is a PNG cut short (it ends before its IEND chunk)";
      return false;
    }
    const std::uint32_t length = BigEndian32(data + at);
    const unsigned char* type = data + at + 4;
    if (length > size - at - 12)
    {
      error = "'" + name + "' is a PNG cut short (its chunk '" +
        std::string(reinterpret_cast<const char*>(type), 4) + "' ends past the end of the file)";
      return false;
    }
    const uLong crc = crc32(crc32(0L, Z_NULL, 0), type, static_cast<uInt>(length + 4));
    if (crc != BigEndian32(type + 4 + length))
    {
      error = "'" + name + "' is a corrupt PNG (its chunk '" +
        std::string(reinterpret_cast<const char*>(type), 4) + "' fails its checksum)";
      return false;
    }
    if (first)
    {
      if (std::memcmp(type, "IHDR", 4) != 0 || length != 13)
      {
        error = "'" + name + "' is a corrupt PNG (it does not start with its IHDR chunk)";
        return false;
      }
      header.width = BigEndian32(type + 4);
      header.height = BigEndian32(type + 8);
      first = false;
    }
    at += 12 + std::size_t(length);
    if (std::memcmp(type, "IEND", 4) == 0)
    {
      return true;
    }
  }
}

bool CheckJpeg(const unsigned char* data, std::size_t size, const std::string& name,
  ImageHeader& header, std::string& error)
{
  std::size_t at = 2; // SOI
  const std::string cut = "'" + name + "' is a JPEG cut short";
  while (true)
  {
    // Fill bytes (0xFF) may precede a marker.
    while (at < size && data[at] == 0xFF && at + 1 < size && data[at + 1] == 0xFF)
    {
      ++at;
    }
    if (size - at < 4 || data[at] != 0xFF)
    {
      error = size - at < 4 ? cut + " (in its header)" : "'" + name + "' is a corrupt JPEG";
      return false;
    }
    const unsigned char marker = data[at + 1];
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7))
    {
      at += 2; // no length
      continue;
    }
    const std::size_t length = (std::size_t(data[at + 2]) << 8) | data[at + 3];
    if (length < 2 || length > size - at - 2)
    {
      error = cut + " (a header segment ends past the end of the file)";
      return false;
    }
    const bool frame =
      marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (frame)
    {
      if (length < 7)
      {
        error = "'" + name + "' is a corrupt JPEG (a frame header too short)";
        return false;
      }
      header.height = (static_cast<long long>(data[at + 5]) << 8) | data[at + 6];
      header.width = (static_cast<long long>(data[at + 7]) << 8) | data[at + 8];
    }
    at += 2 + length;
    if (marker == 0xDA) // start of scan: the entropy-coded data follows
    {
      break;
    }
  }
  if (header.width == 0 && header.height == 0)
  {
    error = "'" + name + "' is a corrupt JPEG (no frame header before its scan)";
    return false;
  }
  // The end-of-image marker, possibly followed by padding or trailing data of a few bytes.
  for (std::size_t end = size; end >= at + 2 && size - end <= 4096; --end)
  {
    if (data[end - 2] == 0xFF && data[end - 1] == 0xD9)
    {
      return true;
    }
  }
  error = cut + " (it has no end-of-image marker)";
  return false;
}

bool CheckBmp(const unsigned char* data, std::size_t size, const std::string& name,
  ImageHeader& header, std::string& error)
{
  if (size < 26)
  {
    error = "'" + name + "' is a BMP cut short (in its header)";
    return false;
  }
  const std::uint32_t fileSize = LittleEndian32(data + 2);
  if (fileSize > size)
  {
    error = "'" + name + "' is a BMP cut short (" + std::to_string(size) + " of its " +
      std::to_string(fileSize) + " bytes)";
    return false;
  }
  const auto width = static_cast<std::int32_t>(LittleEndian32(data + 18));
  const auto height = static_cast<std::int32_t>(LittleEndian32(data + 22));
  header.width = width < 0 ? -static_cast<long long>(width) : width;
  header.height = height < 0 ? -static_cast<long long>(height) : height; // negative: top-down
  return true;
}
} // namespace

bool CheckImageBytes(const unsigned char* data, std::size_t size, const std::string& name,
  long long maxPixels, ImageHeader& header, std::string& error)
{
  header = ImageHeader();
  bool ok = true;
  static const unsigned char png[8] = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n' };
  // A file cut inside its signature counts as its format (then as cut short).
  if (size >= 3 && std::memcmp(data, png, std::min<std::size_t>(size, 8)) == 0)
  {
    header.format = "png";
    ok = size >= 8 ? CheckPng(data, size, name, header, error) : false;
    if (!ok && size < 8)
    {
      error = "'" + name + "' is a PNG cut short (in its signature)";
    }
  }
  else if (size >= 2 && data[0] == 0xFF && data[1] == 0xD8 && (size == 2 || data[2] == 0xFF))
  {
    header.format = "jpeg";
    ok = CheckJpeg(data, size, name, header, error);
  }
  else if (size >= 2 && data[0] == 'B' && data[1] == 'M')
  {
    header.format = "bmp";
    ok = CheckBmp(data, size, name, header, error);
  }
  else
  {
    return true; // another format: the decoder's own checks
  }
  if (!ok)
  {
    return false;
  }
  if (header.width <= 0 || header.height <= 0)
  {
    error = "'" + name + "' is an image of " + std::to_string(header.width) + "x" +
      std::to_string(header.height) + " pixels (its header is corrupt)";
    return false;
  }
  if (header.width > maxPixels / header.height)
  {
    error = "'" + name + "' is " + std::to_string(header.width) + "x" +
      std::to_string(header.height) + " pixels, over the limit of " + std::to_string(maxPixels) +
      " pixels (found in its header, before decoding)";
    return false;
  }
  return true;
}

bool ReadImageFileBytes(const std::string& path, std::vector<unsigned char>& bytes,
  ImageHeader& header, std::string& error)
{
  bytes.clear();
  if (!CheckInputFile(path, std::uint64_t(1) << 32, error))
  {
    return false;
  }
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  const std::streamoff size = in ? static_cast<std::streamoff>(in.tellg()) : -1;
  if (size < 0)
  {
    error = "cannot open '" + path + "'";
    return false;
  }
  bytes.resize(static_cast<std::size_t>(size));
  in.seekg(0);
  if (size > 0 && !in.read(reinterpret_cast<char*>(bytes.data()), size))
  {
    error = "cannot read '" + path + "'";
    return false;
  }
  if (bytes.empty())
  {
    error = "'" + path + "' is empty, not an image";
    return false;
  }
  return CheckImageBytes(bytes.data(), bytes.size(), path, kMaxImagePixels, header, error);
}
} // namespace catar
