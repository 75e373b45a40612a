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

bool WriteNpyInt64(const std::string& path, long long rows, long long cols, const long long* values,
  std::string& error)
{
  if (rows < 0 || cols < 0 || (rows * cols > 0 && !values))
  {
    error = "'" + path + "': no array to write";
    return false;
  }
  // Magic, version 1.0, the header's length (little-endian), the header padded with spaces to a
  // multiple of 64 bytes in all and ended by a newline, then the values little-endian.
  std::string header = "{'descr': '<i8', 'fortran_order': False, 'shape': (" +
    std::to_string(rows) + ", " + std::to_string(cols) + "), }";
  const std::size_t unpadded = 10 + header.size() + 1;
  header.append((64 - unpadded % 64) % 64, ' ');
  header += '\n';
  std::string bytes = "\x93NUMPY";
  bytes += '\x01';
  bytes += '\x00';
  bytes += static_cast<char>(header.size() & 0xff);
  bytes += static_cast<char>((header.size() >> 8) & 0xff);
  bytes += header;
  const std::size_t n = static_cast<std::size_t>(rows * cols);
  bytes.reserve(bytes.size() + 8 * n);
  for (std::size_t i = 0; i < n; ++i)
  {
    const unsigned long long v = static_cast<unsigned long long>(values[i]);
    for (int b = 0; b < 8; ++b)
    {
      bytes += static_cast<char>((v >> (8 * b)) & 0xff);
    }
  }
  return WriteWholeFile(path, bytes, error);
}
} // namespace catar
