#include "FileOutput.h"

#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace catar
{
std::string TemporaryNameBeside(const std::string& path)
{
  static std::atomic<unsigned long> counter{ 0 };
  const std::size_t slash = path.find_last_of('/');
  const std::string dir = slash == std::string::npos ? "" : path.substr(0, slash + 1);
  const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  const std::size_t dot = base.find_last_of('.');
  const std::string ext = dot == std::string::npos || dot == 0 ? "" : base.substr(dot);
  return dir + "." + base + ".partial-" + std::to_string(static_cast<long>(::getpid())) + "-" +
    std::to_string(counter++) + ext;
}

bool CommitTemporary(const std::string& from, const std::string& to, std::string& error)
{
  if (std::rename(from.c_str(), to.c_str()) != 0)
  {
    error = to + ": cannot move the written file into place (" + std::strerror(errno) + ")";
    std::remove(from.c_str());
    return false;
  }
  return true;
}

bool IsSpecialFile(const std::string& path)
{
  struct stat st;
  return ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
}

void FileIdentities::Add(const std::string& path)
{
  struct stat st;
  if (!path.empty() && ::stat(path.c_str(), &st) == 0)
  {
    this->Ids.emplace(
      static_cast<unsigned long long>(st.st_dev), static_cast<unsigned long long>(st.st_ino));
  }
}

bool FileIdentities::Contains(const std::string& path) const
{
  struct stat st;
  return !path.empty() && ::stat(path.c_str(), &st) == 0 &&
    this->Ids.count({ static_cast<unsigned long long>(st.st_dev),
      static_cast<unsigned long long>(st.st_ino) }) > 0;
}

bool WriteWholeFile(const std::string& path, const std::string& bytes, std::string& error)
{
  if (path.empty())
  {
    error = "no file name given";
    return false;
  }
  // A device or a FIFO is written in place; a file through a temporary name beside it.
  const bool inPlace = IsSpecialFile(path);
  if (!inPlace && ::access(path.c_str(), F_OK) == 0 && ::access(path.c_str(), W_OK) != 0)
  {
    error = path + ": cannot open for writing (" + std::strerror(errno) + ")";
    return false;
  }
  const std::string target = inPlace ? path : TemporaryNameBeside(path);
  std::FILE* file = std::fopen(target.c_str(), "wb");
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
    if (!inPlace)
    {
      std::remove(target.c_str());
    }
    return false;
  }
  return inPlace || CommitTemporary(target, path, error);
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
