// CatadioptricAR Core: frames in and out of sequences (OpenCV's VideoCapture and VideoWriter, and
// numbered image files).
//
// A sequence is named by a video file (anything OpenCV's FFmpeg backend reads; written: .mp4 as
// MPEG-4 part 2, .avi as Motion JPEG) or by a printf pattern with one integer conversion
// (`frames/frame_%05d.png`, `%d`, `%3d`; no other `%` but `%%`). Frames are RGBA, 8 bits a channel,
// the top row first (as OpenCV and image files have them).
#ifndef catarVideoIO_h
#define catarVideoIO_h

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace catar
{
/// An RGBA frame, the top row first.
struct Frame
{
  int width = 0;
  int height = 0;
  std::vector<std::uint8_t> rgba; ///< width * height * 4
};

/// True when name holds exactly one integer conversion (%d, %5d, %05d) and no other conversion
/// but %%; false with a sentence in error when it has a `%` that is not one of those.
bool IsFramePattern(const std::string& name, std::string* error = nullptr);
/// The pattern with its conversion filled in (name as it is when it is not a pattern).
std::string FrameFileName(const std::string& pattern, long long index);

/// Frames read from a video file or a numbered image sequence.
class FrameReader
{
public:
  FrameReader();
  ~FrameReader();
  /// Opens name: a pattern (the sequence starts at index 0, or 1 when there is no file 0, and
  /// runs while the files exist), one image file (one frame) or a video file. False with a
  /// sentence in error.
  bool Open(const std::string& name, std::string& error);
  /// The number of frames (for a video, what its container says).
  long long GetNumberOfFrames() const;
  /// What Open found worth telling the user ("" when nothing): a gap in numbered frames, after
  /// which the frames are not read.
  std::string GetNote() const;
  /// Frames a second: the video's, or 0 for an image sequence (no rate of its own).
  double GetFrameRate() const;
  /// Frame k (0-based). Reading in order is fastest; a video seeks back by reopening. False with
  /// a sentence in error (past the end, an unreadable file, a size that differs from frame 0's).
  bool Read(long long k, Frame& frame, std::string& error);

private:
  struct Internals;
  std::unique_ptr<Internals> Internal;
};

/// Whether name ends in the extension of an image format this build writes (.png, .jpg, .jpeg,
/// .tif, .tiff, .bmp, .webp; .exr where OpenCV's OpenEXR writer is enabled) or has none (PNG:
/// a device such as /dev/stdout); false with a sentence in error naming them.
bool IsImageFileName(const std::string& name, std::string* error = nullptr);
/// Writes frame as an image, the format by the file's extension (IsImageFileName): PNG, TIFF and
/// WebP keep alpha, the others get RGB. Encoded in memory, then written with every error checked
/// (a full disk is reported). False with a sentence in error.
bool WriteImageFile(const std::string& file, const Frame& frame, std::string& error);

/// Data images (not for viewing): values kept exactly, one value per pixel, rows top first.
/// A float image (a path length per pixel): .exr or .tif/.tiff, 32-bit float, one channel; NaN
/// is kept. False with a sentence in error (another extension, or no writer for it).
bool WriteFloatImageFile(
  const std::string& file, int width, int height, const float* values, std::string& error);
/// An 8-bit image of one channel (a mask: 0 or 255), `values` width x height, rows top first, in
/// any format IsImageFileName accepts (grey). False with a sentence in error.
bool WriteMaskFile(
  const std::string& file, int width, int height, const std::uint8_t* values, std::string& error);
/// An image of 16-bit unsigned words, `channels` (1 or 3, in R, G, B order) per pixel: .png or
/// .tif/.tiff. False with a sentence in error.
bool WriteImage16File(const std::string& file, int width, int height, int channels,
  const std::uint16_t* values, std::string& error);

/// Frames written as numbered image files (a pattern; the format from the extension, as
/// cv::imwrite; each file whole or absent) or a video (.mp4, .avi).
///
/// A video is whole or absent: it is written to a temporary name beside the target and moved
/// into place by Finish() only once it is closed and read back with every frame written (a full
/// disk, whose losses the encoder does not report, is found there). A video that is not finished
/// -- an error, an interruption -- is given up with Abandon(), which keeps what was written under
/// a name that says so (clip.partial.mp4) or removes it, and says which; the destructor of a
/// writer neither finished nor abandoned removes it.

class FrameWriter
{
public:
  FrameWriter();
  ~FrameWriter();
  /// Whether name is written as a video (by its extension: .mp4, .avi, .mov, .mkv).
  static bool IsVideo(const std::string& name);
  /// Prepares the output: a pattern, or a video of the given size and frame rate. False with a
  /// sentence in error (not a pattern nor a video name, no encoder, a folder that does not exist).
  bool Open(
    const std::string& name, int width, int height, double framesPerSecond, std::string& error);
  /// Writes a frame as number `index` (patterns) or as the video's next frame. Frames of another
  /// size than Open's are refused.
  bool Write(long long index, const Frame& frame, std::string& error);
  /// Finishes the output: a video is closed, read back and, with every frame written readable,
  /// moved into place (replacing an older file of that name). False with a sentence in error
  /// (the video is removed then: nothing at the name, or the older file left as it was).
  bool Finish(std::string& error);
  /// Finish(), the error dropped (for callers that read the output back themselves).
  void Close();
  /// Gives up an unfinished output. A video with readable frames is kept under PartialName(name),
  /// one without is removed; patterns keep the frames written. `what` receives a sentence that
  /// says which (for the user). Safe to call after Finish (nothing to do then).
  void Abandon(std::string& what);
  /// Frames written so far.
  long long GetNumberOfFramesWritten() const;
  /// After Finish: what is worth telling the user about the video written ("" when nothing):
  /// a size the codec changed (odd sizes are rounded to even ones).
  std::string GetNote() const;
  /// The name an abandoned video is kept under: clip.mp4 -> clip.partial.mp4.
  static std::string PartialName(const std::string& name);

private:
  struct Internals;
  std::unique_ptr<Internals> Internal;
};
} // namespace catar

#endif
