#include "FileInput.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

namespace catar
{
bool CheckInputFile(const std::string& path, std::uint64_t maxBytes, std::string& error)
{
  struct stat st;
  if (path.empty() || ::stat(path.c_str(), &st) != 0)
  {
    error =
      "cannot open '" + path + "' (" + (path.empty() ? "no name" : std::strerror(errno)) + ")";
    return false;
  }
  if (!S_ISREG(st.st_mode))
  {
    error = "'" + path + "' is not a regular file (" +
      (S_ISDIR(st.st_mode)                             ? "a folder"
          : S_ISFIFO(st.st_mode)                       ? "a FIFO"
          : S_ISCHR(st.st_mode) || S_ISBLK(st.st_mode) ? "a device"
                                                       : "not a file") +
      "): inputs are read from files";
    return false;
  }
  if (static_cast<std::uint64_t>(st.st_size) > maxBytes)
  {
    error = "'" + path + "' is " + std::to_string(static_cast<long long>(st.st_size)) +
      " bytes, more than the " + std::to_string(maxBytes) + " read from such a file";
    return false;
  }
  return true;
}
} // namespace catar
