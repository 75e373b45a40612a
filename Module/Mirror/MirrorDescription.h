// CatadioptricAR Core: a mirror as data (Mirror.h models it): what calibration files, field data
// and the VTK camera carry.
#ifndef catarMirrorDescription_h
#define catarMirrorDescription_h

#include <string>
#include <vector>

namespace catar
{
/// A mirror type's name (see MirrorTypes() in Mirror.h) and its numbers, in the camera frame.
struct MirrorDescription
{
  /// The first type of MirrorTypes() with its default numbers.
  MirrorDescription();
  MirrorDescription(std::string type, std::vector<double> parameters);

  std::string type;               ///< a MirrorTypes() name
  std::vector<double> parameters; ///< its numbers, in its parameters' order (camera frame)

  bool operator==(const MirrorDescription& other) const
  {
    return this->type == other.type && this->parameters == other.parameters;
  }
  bool operator!=(const MirrorDescription& other) const { return !(*this == other); }
};
} // namespace catar

#endif
