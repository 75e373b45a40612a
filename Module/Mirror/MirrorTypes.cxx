// The catalogue of mirror types: the one place a new shape is added (its own files hold the rest).
#include "Mirror.h"

#include "QuadricMirror.h"
#include "SphereMirror.h"

namespace catar
{
const std::vector<MirrorType>& MirrorTypes()
{
  // The first is the default.
  static const std::vector<MirrorType> types = [] {
    std::vector<MirrorType> all = { SphereMirrorType() };
    for (MirrorType& t : QuadricMirrorTypes())
    {
      all.push_back(std::move(t));
    }
    return all;
  }();
  return types;
}
} // namespace catar
