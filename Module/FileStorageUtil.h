// CatadioptricAR Core, private: helpers to read cv::FileStorage nodes with clear errors.
// Not installed; used by CalibrationIO.cxx and SceneDescription.cxx.
#ifndef catarFileStorageUtil_h
#define catarFileStorageUtil_h

#include "CameraModel.h"

#include <opencv2/core/persistence.hpp>

#include <initializer_list>
#include <stdexcept>
#include <string>
#include <vector>

namespace catar
{
namespace fs
{
/// Thrown by the helpers below; the message names the key.
struct ParseError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// Numbers of a node: a scalar, a sequence, or an !!opencv-matrix (row-major).
std::vector<double> Numbers(const cv::FileNode& node, const std::string& key);
/// Exactly n numbers (throws otherwise).
std::vector<double> Numbers(const cv::FileNode& node, const std::string& key, size_t n);
/// A number, or `fallback` if the key is absent.
double Number(const cv::FileNode& parent, const std::string& key, double fallback);
/// A required number.
double Number(const cv::FileNode& parent, const std::string& key);
/// A string, or `fallback` if absent.
std::string String(const cv::FileNode& parent, const std::string& key, const std::string& fallback);

/// Throws when the map `node` has a key not in `known`: "unknown key 'objetcs' (did you mean
/// 'objects'?)" (the nearest known key within a few edits is suggested).
void CheckKeys(const cv::FileNode& node, std::initializer_list<const char*> known);

/// The largest YAML/JSON file read (16 MiB) and the deepest nesting of maps and sequences (64):
/// the parser recurses once per level, and a file nested thousands deep would overflow its stack.
constexpr std::size_t kMaxTextBytes = std::size_t(16) << 20;
constexpr int kMaxNesting = 64;

/// Opens YAML or JSON for reading: `source` is a file name, or the text itself when `isText`.
/// The text is read whole (at most kMaxTextBytes) and its nesting checked (at most kMaxNesting
/// levels of flow brackets and block indentation) before the parser sees it. On failure returns
/// false with a sentence in `error` that starts with `what`.
bool OpenStorage(cv::FileStorage& storage, const std::string& source, bool isText,
  const std::string& what, std::string& error);

/// Reads the calibration keys from a map node.
void ReadCalibration(const cv::FileNode& node, CameraModel& model);
} // namespace fs
} // namespace catar

#endif
