#include "VideoIO.h"

#include "CameraModel.h" // kMaxImagePixels
#include "FileOutput.h"  // WriteWholeFile
#include "ImageFile.h"   // ReadImageFileBytes

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <initializer_list>

namespace catar
{
namespace
{
constexpr long long kMaxFrames = 10000000;

// Whether `path` names something (never opened: opening a FIFO would wait for a writer).
bool FileExists(const std::string& path)
{
  struct stat st;
  return !path.empty() && ::stat(path.c_str(), &st) == 0;
}

std::string Lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string Extension(const std::string& name)
{
  const std::size_t dot = name.find_last_of('.');
  const std::size_t slash = name.find_last_of('/');
  if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
  {
    return "";
  }
  return Lower(name.substr(dot));
}

std::string DirName(const std::string& path)
{
  const std::size_t slash = path.find_last_of('/');
  return slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
}

// BGR(A) or grey, 8 or 16 bits, to RGBA 8 bits.
bool ToRGBA(const cv::Mat& in, Frame& frame, std::string& error)
{
  if (in.empty() || in.dims != 2)
  {
    error = "an empty frame";
    return false;
  }
  if (static_cast<long long>(in.cols) * in.rows > kMaxImagePixels)
  {
    error = "a frame of " + std::to_string(in.cols) + "x" + std::to_string(in.rows) +
      " pixels, over the limit of " + std::to_string(kMaxImagePixels);
    return false;
  }
  cv::Mat eight = in;
  if (in.depth() == CV_16U)
  {
    in.convertTo(eight, CV_8U, 1.0 / 257.0);
  }
  else if (in.depth() != CV_8U)
  {
    error = "frames must have 8 or 16 bits a channel";
    return false;
  }
  cv::Mat rgba;
  switch (eight.channels())
  {
    case 1:
      cv::cvtColor(eight, rgba, cv::COLOR_GRAY2RGBA);
      break;
    case 3:
      cv::cvtColor(eight, rgba, cv::COLOR_BGR2RGBA);
      break;
    case 4:
      cv::cvtColor(eight, rgba, cv::COLOR_BGRA2RGBA);
      break;
    default:
      error = "frames must have 1, 3 or 4 channels";
      return false;
  }
  frame.width = rgba.cols;
  frame.height = rgba.rows;
  frame.rgba.assign(rgba.data, rgba.data + rgba.total() * 4);
  return true;
}
} // namespace

bool IsFramePattern(const std::string& name, std::string* error)
{
  int conversions = 0;
  for (std::size_t i = 0; i < name.size(); ++i)
  {
    if (name[i] != '%')
    {
      continue;
    }
    if (i + 1 < name.size() && name[i + 1] == '%')
    {
      ++i;
      continue;
    }
    std::size_t j = i + 1;
    while (j < name.size() && std::isdigit(static_cast<unsigned char>(name[j])) && j - i <= 2)
    {
      ++j;
    }
    if (j >= name.size() || name[j] != 'd')
    {
      if (error)
      {
        *error = "'" + name + "': a '%' must start %d, %5d or %05d (at most two digits), or be %%";
      }
      return false;
    }
    ++conversions;
    i = j;
  }
  if (conversions > 1 && error)
  {
    *error = "'" + name + "' has " + std::to_string(conversions) + " frame numbers; give one";
  }
  return conversions == 1;
}

std::string FrameFileName(const std::string& pattern, long long index)
{
  if (!IsFramePattern(pattern))
  {
    return pattern;
  }
  // Checked above: one integer conversion of at most two digits' width, and %%.
  std::string out;
  for (std::size_t i = 0; i < pattern.size(); ++i)
  {
    if (pattern[i] != '%')
    {
      out += pattern[i];
      continue;
    }
    if (pattern[i + 1] == '%')
    {
      out += '%';
      ++i;
      continue;
    }
    const std::size_t d = pattern.find('d', i);
    const std::string spec = pattern.substr(i, d - i) + "lld";
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, spec.c_str(), index);
    out += buffer;
    i = d;
  }
  return out;
}

struct FrameReader::Internals
{
  std::string name;
  bool pattern = false;
  long long first = 0; // the pattern's first index
  long long count = 0;
  double fps = 0.0;
  int width = 0, height = 0;
  cv::VideoCapture capture;
  long long next = 0; // the video frame the capture reads next
  std::string note;   // what Open found worth saying (a gap in numbered frames)
};

FrameReader::FrameReader()
  : Internal(new Internals)
{
}

FrameReader::~FrameReader() = default;

bool FrameReader::Open(const std::string& name, std::string& error)
{
  Internals& in = *this->Internal;
  in = Internals();
  in.name = name;
  std::string patternError;
  in.pattern = IsFramePattern(name, &patternError);
  if (!patternError.empty())
  {
    error = patternError;
    return false;
  }
  if (in.pattern)
  {
    in.first = FileExists(FrameFileName(name, 0)) ? 0 : 1;
    while (in.count < kMaxFrames && FileExists(FrameFileName(name, in.first + in.count)))
    {
      ++in.count;
    }
    if (in.count == 0)
    {
      error = "no frames: neither " + FrameFileName(name, 0) + " nor " + FrameFileName(name, 1) +
        " exists";
      return false;
    }
    // A gap: the sequence stops at the first missing number; say so when files follow it.
    const long long missing = in.first + in.count;
    for (long long k = missing + 1; k <= missing + 1000; ++k)
    {
      if (FileExists(FrameFileName(name, k)))
      {
        in.note = "the frames " + name + " stop at " + FrameFileName(name, missing - 1) + ": " +
          FrameFileName(name, missing) + " is missing, though " + FrameFileName(name, k) +
          " exists (frames after a gap are not read)";
        break;
      }
    }
    return true;
  }
  if (!FileExists(name))
  {
    error = "cannot open '" + name + "'";
    return false;
  }
  if (!FrameWriter::IsVideo(name) && cv::haveImageReader(name))
  {
    // One image: a sequence of one frame.
    in.pattern = true;
    in.count = 1;
    return true;
  }
  try
  {
    in.capture.open(name, cv::CAP_FFMPEG);
  }
  catch (const cv::Exception& e)
  {
    error = "cannot read '" + name + "' as a video: " + e.msg;
    return false;
  }
  if (!in.capture.isOpened())
  {
    error = "cannot read '" + name + "' as a video (not a video file, or no decoder for it)";
    return false;
  }
  in.count = static_cast<long long>(in.capture.get(cv::CAP_PROP_FRAME_COUNT));
  in.fps = in.capture.get(cv::CAP_PROP_FPS);
  if (!(in.count > 0) || in.count > kMaxFrames)
  {
    error = "'" + name + "' says it has " + std::to_string(in.count) + " frames";
    return false;
  }
  if (!(in.fps > 0.0 && in.fps < 1e6))
  {
    in.fps = 0.0;
  }
  return true;
}

std::string FrameReader::GetNote() const
{
  return this->Internal->note;
}

long long FrameReader::GetNumberOfFrames() const
{
  return this->Internal->count;
}

double FrameReader::GetFrameRate() const
{
  return this->Internal->fps;
}

bool FrameReader::Read(long long k, Frame& frame, std::string& error)
{
  Internals& in = *this->Internal;
  if (k < 0 || k >= in.count)
  {
    error = "frame " + std::to_string(k) + " of '" + in.name + "' does not exist (it has " +
      std::to_string(in.count) + ")";
    return false;
  }
  cv::Mat image;
  try
  {
    if (in.pattern)
    {
      const std::string file = FrameFileName(in.name, in.first + k);
      std::vector<unsigned char> bytes;
      ImageHeader header;
      if (!ReadImageFileBytes(file, bytes, header, error))
      {
        return false;
      }
      image = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
      if (image.empty())
      {
        error = "cannot read '" + file + "' as an image";
        return false;
      }
    }
    else
    {
      if (k < in.next)
      {
        in.capture.open(in.name, cv::CAP_FFMPEG);
        in.next = 0;
      }
      for (; in.next < k; ++in.next)
      {
        if (!in.capture.grab())
        {
          break;
        }
      }
      if (in.next != k || !in.capture.read(image))
      {
        error = "cannot decode frame " + std::to_string(k) + " of '" + in.name + "'";
        return false;
      }
      ++in.next;
    }
  }
  catch (const cv::Exception& e)
  {
    error = "cannot read frame " + std::to_string(k) + " of '" + in.name + "': " + e.msg;
    return false;
  }
  if (!ToRGBA(image, frame, error))
  {
    error = "frame " + std::to_string(k) + " of '" + in.name + "': " + error;
    return false;
  }
  if (in.width == 0)
  {
    in.width = frame.width;
    in.height = frame.height;
  }
  else if (frame.width != in.width || frame.height != in.height)
  {
    error = "frame " + std::to_string(k) + " of '" + in.name + "' is " +
      std::to_string(frame.width) + "x" + std::to_string(frame.height) + ", the first was " +
      std::to_string(in.width) + "x" + std::to_string(in.height);
    return false;
  }
  return true;
}

struct FrameWriter::Internals
{
  std::string name;
  std::string temporary; // the video being written (empty: none, or moved into place)
  bool video = false;
  int width = 0, height = 0;
  long long written = 0;
  std::string note; // what Finish found worth saying (a size the codec changed)
  cv::VideoWriter writer;
};

namespace
{
// Frames of the video file `name` that can be read: the container's count when it says so, else
// (or when it differs from `expected`) counted by reading through.
long long ReadableFrames(
  const std::string& name, long long expected, int* width = nullptr, int* height = nullptr)
{
  cv::VideoCapture capture;
  try
  {
    if (!capture.open(name, cv::CAP_FFMPEG))
    {
      return 0;
    }
    if (width && height)
    {
      *width = static_cast<int>(capture.get(cv::CAP_PROP_FRAME_WIDTH));
      *height = static_cast<int>(capture.get(cv::CAP_PROP_FRAME_HEIGHT));
    }
    const long long said = static_cast<long long>(capture.get(cv::CAP_PROP_FRAME_COUNT));
    long long n = 0;
    while (n <= expected && capture.grab())
    {
      ++n;
    }
    return said == n || said <= 0 ? n : std::min(said, n);
  }
  catch (const cv::Exception&)
  {
    return 0;
  }
}
} // namespace

FrameWriter::FrameWriter()
  : Internal(new Internals)
{
}

FrameWriter::~FrameWriter()
{
  Internals& in = *this->Internal;
  if (!in.temporary.empty())
  {
    in.writer.release();
    std::remove(in.temporary.c_str());
  }
}

std::string FrameWriter::PartialName(const std::string& name)
{
  const std::string ext = Extension(name);
  return name.substr(0, name.size() - ext.size()) + ".partial" + ext;
}

long long FrameWriter::GetNumberOfFramesWritten() const
{
  return this->Internal->written;
}

std::string FrameWriter::GetNote() const
{
  return this->Internal->note;
}

bool FrameWriter::Finish(std::string& error)
{
  Internals& in = *this->Internal;
  if (in.temporary.empty())
  {
    return true;
  }
  in.writer.release();
  const std::string temporary = in.temporary;
  in.temporary.clear();
  int width = 0, height = 0;
  const long long readable = ReadableFrames(temporary, in.written, &width, &height);
  in.note.clear();
  if (readable > 0 && (width != in.width || height != in.height))
  {
    in.note = "the video '" + in.name + "' is " + std::to_string(width) + "x" +
      std::to_string(height) + ", not " + std::to_string(in.width) + "x" +
      std::to_string(in.height) +
      ": its codec takes even sizes only (numbered images keep the size)";
  }
  if (readable != in.written)
  {
    std::remove(temporary.c_str());
    error = "the video '" + in.name + "' could not be written whole: " + std::to_string(readable) +
      " of its " + std::to_string(in.written) +
      " frames could be read back (a full disk?); nothing was written there";
    return false;
  }
  return CommitTemporary(temporary, in.name, error);
}

void FrameWriter::Close()
{
  std::string ignored;
  this->Finish(ignored);
}

void FrameWriter::Abandon(std::string& what)
{
  Internals& in = *this->Internal;
  if (!in.video)
  {
    what = in.written > 0 ? std::to_string(in.written) + " frames were written as '" + in.name + "'"
                          : "no frame was written";
    return;
  }
  if (in.temporary.empty())
  {
    what = "";
    return;
  }
  in.writer.release();
  const std::string temporary = in.temporary;
  in.temporary.clear();
  const long long readable = ReadableFrames(temporary, in.written);
  const std::string partial = PartialName(in.name);
  std::string error;
  if (readable > 0 && CommitTemporary(temporary, partial, error))
  {
    what = "the " + std::to_string(readable) + " frames written were kept as '" + partial + "'; '" +
      in.name + "' was not written";
    return;
  }
  std::remove(temporary.c_str());
  what = "the unfinished video was removed; '" + in.name + "' was not written";
}

bool FrameWriter::IsVideo(const std::string& name)
{
  const std::string ext = Extension(name);
  return ext == ".mp4" || ext == ".avi" || ext == ".mov" || ext == ".mkv";
}

bool FrameWriter::Open(
  const std::string& name, int width, int height, double framesPerSecond, std::string& error)
{
  Internals& in = *this->Internal;
  if (!in.temporary.empty())
  {
    in.writer.release();
    std::remove(in.temporary.c_str());
  }
  in = Internals();
  in.name = name;
  in.width = width;
  in.height = height;
  if (!(width > 0 && height > 0) || static_cast<long long>(width) * height > kMaxImagePixels)
  {
    error = "cannot write frames of " + std::to_string(width) + "x" + std::to_string(height);
    return false;
  }
  const std::string folder = DirName(name);
  if (!FileExists(folder))
  {
    error = "the folder '" + folder + "' of '" + name + "' does not exist";
    return false;
  }
  std::string patternError;
  const bool pattern = IsFramePattern(name, &patternError);
  if (!patternError.empty())
  {
    error = patternError;
    return false;
  }
  in.video = IsVideo(name);
  if (in.video && FileExists(name) && ::access(name.c_str(), W_OK) != 0)
  {
    error = "cannot write '" + name + "' (" + std::strerror(errno) + ")";
    return false;
  }
  if (pattern && in.video)
  {
    error = "'" + name + "' is both a frame pattern and a video name";
    return false;
  }
  if (pattern)
  {
    if (!cv::haveImageWriter(FrameFileName(name, 0)))
    {
      error = "no image writer for the extension of '" + name + "' (use .png or .jpg)";
      return false;
    }
    return true;
  }
  if (!in.video)
  {
    error = "'" + name + "' is neither a frame pattern (frame_%05d.png) nor a video (.mp4, .avi)";
    return false;
  }
  if (!(framesPerSecond > 0.0 && framesPerSecond <= 1000.0))
  {
    error = "a video needs a frame rate in (0, 1000] frames a second";
    return false;
  }
  const std::string ext = Extension(name);
  const int fourcc = ext == ".avi" ? cv::VideoWriter::fourcc('M', 'J', 'P', 'G')
                                   : cv::VideoWriter::fourcc('m', 'p', '4', 'v');
  // Written beside the target, moved into place by Finish(), and read back: a target that is
  // not a regular file (a FIFO, a device, or a link to one) could be neither.
  if (IsSpecialFile(name))
  {
    error = "'" + name + "' is not a regular file (a FIFO or a device): a video is written whole " +
      "to a file and then checked; write it to a file, or write numbered frames";
    return false;
  }
  in.temporary = TemporaryNameBeside(name);
  try
  {
    in.writer.open(in.temporary, cv::CAP_FFMPEG, fourcc, framesPerSecond, cv::Size(width, height));
  }
  catch (const cv::Exception& e)
  {
    error = "cannot write '" + name + "': " + e.msg;
    std::remove(in.temporary.c_str());
    in.temporary.clear();
    return false;
  }
  if (!in.writer.isOpened())
  {
    error = "cannot write '" + name + "' (no encoder for it, or the file cannot be created)";
    std::remove(in.temporary.c_str());
    in.temporary.clear();
    return false;
  }
  return true;
}

bool FrameWriter::Write(long long index, const Frame& frame, std::string& error)
{
  Internals& in = *this->Internal;
  if (frame.width != in.width || frame.height != in.height ||
    frame.rgba.size() != static_cast<std::size_t>(in.width) * in.height * 4)
  {
    error = "a frame of " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
      " for an output of " + std::to_string(in.width) + "x" + std::to_string(in.height);
    return false;
  }
  cv::Mat rgba(frame.height, frame.width, CV_8UC4, const_cast<std::uint8_t*>(frame.rgba.data()));
  try
  {
    if (in.video)
    {
      cv::Mat bgr;
      cv::cvtColor(rgba, bgr, cv::COLOR_RGBA2BGR);
      in.writer.write(bgr);
      ++in.written;
      return true;
    }
    if (!WriteImageFile(FrameFileName(in.name, index), frame, error))
    {
      return false;
    }
    ++in.written;
    return true;
  }
  catch (const cv::Exception& e)
  {
    error = "cannot write frame " + std::to_string(index) + " of '" + in.name + "': " + e.msg;
    return false;
  }
  return true;
}

namespace
{
const char* const kImageExtensions[] = { ".png", ".jpg", ".jpeg", ".tif", ".tiff", ".bmp", ".webp",
  ".exr" };
}

bool IsImageFileName(const std::string& name, std::string* error)
{
  const std::string ext = Extension(name);
  if (ext.empty())
  {
    return true; // written as PNG (a device such as /dev/stdout)
  }
  std::string known;
  for (const char* e : kImageExtensions)
  {
    bool writes = false;
    try
    {
      writes = cv::haveImageWriter(std::string("x") + e);
    }
    catch (const cv::Exception&)
    {
    }
    if (!writes)
    {
      continue;
    }
    if (ext == e)
    {
      return true;
    }
    known += std::string(known.empty() ? "" : ", ") + e;
  }
  if (error)
  {
    *error = "'" + name +
      "': " + (ext.empty() ? std::string("no extension") : "unknown image format '" + ext + "'") +
      " (this build writes " + known + ")";
  }
  return false;
}

bool WriteImageFile(const std::string& file, const Frame& frame, std::string& error)
{
  if (!IsImageFileName(file, &error))
  {
    return false;
  }
  if (frame.width <= 0 || frame.height <= 0 ||
    frame.rgba.size() != 4 * static_cast<std::size_t>(frame.width) * frame.height)
  {
    error = "'" + file + "': no image to write";
    return false;
  }
  std::vector<uchar> bytes;
  try
  {
    // Alpha where the format keeps it (PNG, TIFF, WebP); JPEG and the others get BGR. No
    // extension: PNG.
    const std::string ext = Extension(file).empty() ? ".png" : Extension(file);
    const bool alpha = ext == ".png" || ext == ".tif" || ext == ".tiff" || ext == ".webp";
    cv::Mat rgba(frame.height, frame.width, CV_8UC4, const_cast<std::uint8_t*>(frame.rgba.data()));
    cv::Mat out;
    cv::cvtColor(rgba, out, alpha ? cv::COLOR_RGBA2BGRA : cv::COLOR_RGBA2BGR);
    if (ext == ".exr")
    {
      out.convertTo(out, CV_32F, 1.0 / 255.0);
    }
    if (!cv::imencode(ext, out, bytes) || bytes.empty())
    {
      error = "'" + file + "': the image could not be encoded";
      return false;
    }
  }
  catch (const cv::Exception& e)
  {
    error = "'" + file + "': " + e.msg;
    return false;
  }
  return WriteWholeFile(
    file, std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size()), error);
}

namespace
{
// Encodes `image` in the format of the extension `ext` (one of `allowed`) and writes it.
bool WriteDataImage(const std::string& file, const cv::Mat& image,
  std::initializer_list<const char*> allowed, const char* what, std::string& error)
{
  const std::string ext = Extension(file);
  std::string names;
  bool known = false;
  for (const char* e : allowed)
  {
    names += std::string(names.empty() ? "" : ", ") + e;
    known = known || ext == e;
  }
  if (!known)
  {
    error = "'" + file + "': " + what + " are written as " + names;
    return false;
  }
  std::vector<uchar> bytes;
  try
  {
    if (!cv::haveImageWriter(file) || !cv::imencode(ext, image, bytes) || bytes.empty())
    {
      error = "'" + file + "': this build cannot write " + what + " as " + ext;
      return false;
    }
  }
  catch (const cv::Exception& e)
  {
    error = "'" + file + "': " + e.msg;
    return false;
  }
  return WriteWholeFile(
    file, std::string(reinterpret_cast<const char*>(bytes.data()), bytes.size()), error);
}
} // namespace

bool WriteFloatImageFile(
  const std::string& file, int width, int height, const float* values, std::string& error)
{
  if (width <= 0 || height <= 0 || !values)
  {
    error = "'" + file + "': no image to write";
    return false;
  }
  const cv::Mat image(height, width, CV_32FC1, const_cast<float*>(values));
  return WriteDataImage(
    file, image, { ".exr", ".tif", ".tiff" }, "float images (32-bit, one channel)", error);
}

bool WriteMaskFile(
  const std::string& file, int width, int height, const std::uint8_t* values, std::string& error)
{
  if (!IsImageFileName(file, &error))
  {
    return false;
  }
  if (width <= 0 || height <= 0 || !values)
  {
    error = "'" + file + "': no image to write";
    return false;
  }
  const cv::Mat image(height, width, CV_8UC1, const_cast<std::uint8_t*>(values));
  const std::string ext = Extension(file).empty() ? ".png" : Extension(file);
  std::vector<uchar> bytes;
  try
  {
    if (!cv::imencode(ext, image, bytes) || bytes.empty())
    {
      error = "'" + file + "': this build cannot write a mask as " + ext;
      return false;
    }
  }
  catch (const cv::Exception& e)
  {
    error = "'" + file + "': " + e.msg;
    return false;
  }
  return WriteWholeFile(file, std::string(bytes.begin(), bytes.end()), error);
}

bool WriteImage16File(const std::string& file, int width, int height, int channels,
  const std::uint16_t* values, std::string& error)
{
  if (width <= 0 || height <= 0 || !values || (channels != 1 && channels != 3))
  {
    error = "'" + file + "': no image to write";
    return false;
  }
  cv::Mat image(height, width, CV_16UC(channels), const_cast<std::uint16_t*>(values));
  cv::Mat bgr;
  if (channels == 3)
  {
    cv::cvtColor(image, bgr, cv::COLOR_RGB2BGR); // OpenCV writes BGR as the file's RGB
  }
  return WriteDataImage(
    file, channels == 3 ? bgr : image, { ".png", ".tif", ".tiff" }, "16-bit images", error);
}
} // namespace catar
