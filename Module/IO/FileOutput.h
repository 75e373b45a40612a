// CatadioptricAR Core: writing files honestly. A write that fails (no such folder, no
// permission, a full disk: the data is only known lost when the stream is flushed) returns false
// and says why; it never reports success for a file that was not written. A regular file is
// written whole or not at all: to a temporary name beside it, renamed over the target only once
// every byte is written and closed (so a failed or interrupted write leaves the old file, or
// none, and two writers of one file leave one of them whole).
#ifndef catarFileOutput_h
#define catarFileOutput_h

#include <set>
#include <string>
#include <utility>

namespace catar
{
/// Writes `bytes` to `path` (replacing it). False with a sentence in `error` when the file could
/// not be opened, written or closed, or when `path` is empty.
bool WriteWholeFile(const std::string& path, const std::string& bytes, std::string& error);

/// A temporary name beside `path`, unique to this process and call (hidden, ending in `path`'s
/// extension so that writers that pick a format by the extension still do): where a file is
/// written before it is renamed to `path`.
std::string TemporaryNameBeside(const std::string& path);

/// Renames the written temporary file `from` to `to` (atomic on one file system). False with a
/// sentence in `error`; `from` is removed then.
bool CommitTemporary(const std::string& from, const std::string& to, std::string& error);

/// Whether `path` names something that is not a regular file that can be replaced by renaming
/// (a device such as /dev/stdout, a FIFO): such outputs are written in place.
bool IsSpecialFile(const std::string& path);

/// The identities (device and inode) of existing files: to refuse an output that is one of the
/// inputs, whatever name it is given (a link, "./", another path to the same file).
class FileIdentities
{
public:
  /// Adds the file `path` when it exists (nothing otherwise).
  void Add(const std::string& path);
  /// Whether `path` exists and is one of the files added.
  bool Contains(const std::string& path) const;
  bool Empty() const { return this->Ids.empty(); }

private:
  std::set<std::pair<unsigned long long, unsigned long long>> Ids;
};

/// Writes a rows x cols array of 64-bit integers (row-major, `values`) as a NumPy .npy file
/// (format 1.0, dtype '<i8'), which numpy.load reads. False with a sentence in `error`.
bool WriteNpyInt64(const std::string& path, long long rows, long long cols, const long long* values,
  std::string& error);
} // namespace catar

#endif
