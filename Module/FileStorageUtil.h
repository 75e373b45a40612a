// CatadioptricAR Core, private: helpers to read cv::FileStorage nodes with clear errors.
// Not installed; used by CalibrationIO.cxx and SceneDescription.cxx.
#ifndef catarFileStorageUtil_h
#define catarFileStorageUtil_h

#include "CameraModel.h"

#include <opencv2/core/persistence.hpp>

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

/// Reads the calibration keys from a map node.
void ReadCalibration(const cv::FileNode& node, CameraModel& model);
} // namespace fs
} // namespace catar

#endif
