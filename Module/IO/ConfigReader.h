// CatadioptricAR Core, private: reading scene and calibration files (YAML or JSON) with clear
// errors. Not installed; used by CalibrationIO.cxx and SceneDescription.cxx.
//
// Files are parsed by yaml-cpp (YAML 1.2, which reads JSON too). OpenCV FileStorage files load
// unchanged: their `%YAML:1.0` first line is read as a comment, and `!!opencv-matrix` maps
// (rows, cols, dt, data) are read as their data, row-major.
#ifndef catarConfigReader_h
#define catarConfigReader_h

#include "CameraModel.h"

#include <initializer_list>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace catar
{
namespace fs
{
/// Thrown by the helpers below; the message names the key.
struct ParseError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// A read-only node of a parsed file. An absent key gives an empty node (never an exception,
/// never an inserted key); every accessor is safe on every node.
class Node
{
public:
  Node();
  ~Node();
  Node(const Node&);
  Node& operator=(const Node&);

  /// The key was absent (or the node is an item of something that is not a map).
  bool empty() const;
  /// `~`, `null` or a key with no value.
  bool isNone() const;
  bool isMap() const;
  bool isSeq() const;
  /// A plain (unquoted) scalar that is a number ("1", "-2.5e3", ".5"; not "0x10").
  bool isNumber() const;
  /// A number without a fractional part that fits an int.
  bool isInt() const;
  /// Any other scalar (quoted, or plain but not a number).
  bool isString() const;
  /// `true` or `false` (plain, any case).
  bool isBool() const;

  /// The value of `key` in a map; an empty node otherwise.
  Node operator[](const std::string& key) const;
  /// A sequence's items (empty for anything else).
  std::vector<Node> items() const;
  /// A map's keys in file order (duplicates included); empty for anything else.
  std::vector<std::string> keys() const;
  /// Items of a sequence or entries of a map.
  std::size_t size() const;
  /// The text of a scalar ("" for anything else).
  std::string text() const;
  /// The value of a number node (NaN for anything else).
  double number() const;
  /// 1-based line of the node in the file (0 when unknown).
  int line() const;

private:
  struct Impl;
  explicit Node(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
  friend bool Parse(const std::string&, bool, const std::string&, Node&, std::string&);
};

/// Numbers of a node: a scalar, a sequence, or an !!opencv-matrix (row-major).
std::vector<double> Numbers(const Node& node, const std::string& key);
/// Exactly n numbers (throws otherwise).
std::vector<double> Numbers(const Node& node, const std::string& key, size_t n);
/// A number, or `fallback` if the key is absent.
double Number(const Node& parent, const std::string& key, double fallback);
/// A required number.
double Number(const Node& parent, const std::string& key);
/// A string, or `fallback` if absent.
std::string String(const Node& parent, const std::string& key, const std::string& fallback);
/// A flag: true/false or a number (non-zero is true), or `fallback` if absent.
bool Flag(const Node& parent, const std::string& key, bool fallback);

/// Throws when the map `node` has a key not in `known`: "unknown key 'objetcs' (did you mean
/// 'objects'?)" (the nearest known key within a few edits is suggested).
void CheckKeys(const Node& node, std::initializer_list<const char*> known);
void CheckKeys(const Node& node, const std::vector<std::string>& known);

/// The largest YAML/JSON file read (16 MiB) and the deepest nesting of maps and sequences (64):
/// the parser recurses once per level, and a file nested thousands deep would overflow its stack.
constexpr std::size_t kMaxTextBytes = std::size_t(16) << 20;
constexpr int kMaxNesting = 64;
/// The most values (scalars, maps and sequences) a parsed file may hold once its aliases are
/// expanded.
constexpr std::size_t kMaxValues = std::size_t(1) << 22;

/// Parses YAML or JSON: `source` is a file name, or the text itself when `isText`. The text is
/// read whole (at most kMaxTextBytes) and its nesting checked (at most kMaxNesting levels of flow
/// brackets and block indentation) before the parser sees it. On failure returns false with a
/// sentence in `error` that starts with `what` (and gives the line and column of a syntax error).
/// A key given twice in one map is an error, as is a tree past kMaxValues.
bool Parse(
  const std::string& source, bool isText, const std::string& what, Node& root, std::string& error);

/// Reads the calibration keys from a map node.
/// mirrorRequired false: a calibration of the lens alone (no `mirror` key) is read too, the model's
/// mirror left as it is.
void ReadCalibration(const Node& node, CameraModel& model, bool mirrorRequired = true);
} // namespace fs
} // namespace catar

#endif
