// CatadioptricAR Core: image files checked before they are decoded. The header's size is read
// without decoding (an "image bomb" — a small file that announces a huge image — is refused
// before any pixel is allocated), and a PNG, JPEG or BMP that is cut short is refused by name
// instead of reaching the decoder (whose libraries print their own lines on standard error).
#ifndef catarImageFile_h
#define catarImageFile_h

#include <cstddef>
#include <string>
#include <vector>

namespace catar
{
/// What an image file's header says.
struct ImageHeader
{
  std::string format; ///< "png", "jpeg", "bmp", or "" for a format not read here
  long long width = 0;
  long long height = 0;
};

/// Reads the header of the image file held in `data` (`size` bytes, the whole file) and checks
/// that the file is whole: a PNG's chunks up to IEND complete and their checksums right, a JPEG's
/// segments up to the scan and its end-of-image marker present, a BMP as long as its header says.
/// A size of zero or over `maxPixels` pixels is an error. Other formats: true, `format` "" (the
/// decoder's own checks apply). `name` names the file in `error`.
bool CheckImageBytes(const unsigned char* data, std::size_t size, const std::string& name,
  long long maxPixels, ImageHeader& header, std::string& error);

/// Reads the image file `path` into `bytes` after CheckInputFile (a regular file, at most 4 GiB)
/// and CheckImageBytes with the largest image the project handles (kMaxImagePixels). The bytes
/// are then decoded by the caller (cv::imdecode).
bool ReadImageFileBytes(const std::string& path, std::vector<unsigned char>& bytes,
  ImageHeader& header, std::string& error);
} // namespace catar

#endif
