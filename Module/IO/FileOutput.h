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

/// Writes a rows x cols array of 64-bit integers (row-major, `values`) as a NumPy .npy file
/// (format 1.0, dtype '<i8'), which numpy.load reads. False with a sentence in `error`.
bool WriteNpyInt64(const std::string& path, long long rows, long long cols, const long long* values,
  std::string& error);
} // namespace catar

#endif
