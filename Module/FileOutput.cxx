#include "FileOutput.h"

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace catar
{
bool WriteWholeFile(const std::string& path, const std::string& bytes, std::string& error)
{
  if (path.empty())
  {
    error = "no file name given";
    return false;
  }
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (!file)
  {
    error = path + ": cannot open for writing (" + std::strerror(errno) + ")";
    return false;
  }
  errno = 0;
  const std::size_t written = bytes.empty() ? 0 : std::fwrite(bytes.data(), 1, bytes.size(), file);
  const bool flushed = std::fflush(file) == 0;
  const int flushErrno = errno;
  const bool closed = std::fclose(file) == 0;
  if (written != bytes.size() || !flushed || !closed)
  {
    const int e = flushErrno != 0 ? flushErrno : errno;
    error = path + ": writing failed" + (e != 0 ? std::string(" (") + std::strerror(e) + ")" : "");
    return false;
  }
  return true;
}
} // namespace catar
