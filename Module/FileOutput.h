// CatadioptricAR Core: writing files honestly. A write that fails (no such folder, no
// permission, a full disk: the data is only known lost when the stream is flushed) returns false
// and says why; it never reports success for a file that was not written.
#ifndef catarFileOutput_h
#define catarFileOutput_h

#include <string>

namespace catar
{
/// Writes `bytes` to `path` (replacing it). False with a sentence in `error` when the file could
/// not be opened, written or closed, or when `path` is empty.
bool WriteWholeFile(const std::string& path, const std::string& bytes, std::string& error);
} // namespace catar

#endif
