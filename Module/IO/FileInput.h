// CatadioptricAR Core: reading files safely. An input must be a regular file of a bounded size:
// a FIFO or a device (/dev/zero) would block or never end.
#ifndef catarFileInput_h
#define catarFileInput_h

#include <cstdint>
#include <string>

namespace catar
{
/// True when `path` is a regular file of at most `maxBytes` bytes; false with a sentence in
/// `error` (missing, a folder, a FIFO, a device, too large), naming the file.
bool CheckInputFile(const std::string& path, std::uint64_t maxBytes, std::string& error);
} // namespace catar

#endif
