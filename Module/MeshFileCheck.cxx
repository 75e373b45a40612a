#include "MeshFileCheck.h"

#include <algorithm>
#include <cctype>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace catar
{
namespace
{
bool FileSize(const std::string& path, std::uint64_t& size, std::string& error)
{
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in)
  {
    error = path + ": cannot open the mesh file";
    return false;
  }
  const std::streamoff end = in.tellg();
  if (end < 0)
  {
    error = path + ": cannot read the mesh file";
    return false;
  }
  size = static_cast<std::uint64_t>(end);
  if (size > kMaxMeshFileBytes)
  {
    error = path + ": the mesh file is larger than the limit of " +
      std::to_string(kMaxMeshFileBytes) + " bytes";
    return false;
  }
  return true;
}

std::string Lower(std::string s)
{
  std::transform(s.begin(), s.end(), s.begin(),
    [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// Size in bytes of a PLY scalar type; 0 when unknown.
int PlyTypeSize(const std::string& t)
{
  static const std::map<std::string, int> sizes = { { "char", 1 }, { "uchar", 1 }, { "int8", 1 },
    { "uint8", 1 }, { "short", 2 }, { "ushort", 2 }, { "int16", 2 }, { "uint16", 2 }, { "int", 4 },
    { "uint", 4 }, { "int32", 4 }, { "uint32", 4 }, { "float", 4 }, { "float32", 4 },
    { "double", 8 }, { "float64", 8 } };
  const auto it = sizes.find(t);
  return it == sizes.end() ? 0 : it->second;
}

// A count as written in a header: digits only, at most `limit`.
bool ParseCount(const std::string& word, std::uint64_t limit, std::uint64_t& value)
{
  if (word.empty() || word.size() > 19 ||
    !std::all_of(word.begin(), word.end(), [](unsigned char c) { return std::isdigit(c); }))
  {
    return false;
  }
  value = std::stoull(word);
  return value <= limit;
}
} // namespace

bool CheckPlyFile(const std::string& path, std::string& error)
{
  std::uint64_t size = 0;
  if (!FileSize(path, size, error))
  {
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  std::string line;
  auto fail = [&](const std::string& why) {
    error = path + ": not a valid PLY file: " + why;
    return false;
  };
  if (!std::getline(in, line) || line.substr(0, 3) != "ply")
  {
    return fail("it does not start with 'ply'");
  }
  struct Element
  {
    std::string name;
    std::uint64_t count = 0;
    std::uint64_t minBytes = 0; // binary: the fixed sizes plus the lists' count fields
    std::uint64_t properties = 0;
  };
  std::vector<Element> elements;
  bool ascii = false, haveFormat = false, ended = false;
  // A header of more than 64 KiB or 10,000 lines is not a PLY header.
  for (int lines = 0; lines < 10000 && std::getline(in, line); ++lines)
  {
    if (static_cast<std::uint64_t>(in.tellg()) > 65536)
    {
      break;
    }
    if (!line.empty() && line.back() == '\r')
    {
      line.pop_back();
    }
    std::istringstream words(line);
    std::string key;
    words >> key;
    if (key == "end_header")
    {
      ended = true;
      break;
    }
    if (key == "format")
    {
      std::string format;
      words >> format;
      if (format != "ascii" && format != "binary_little_endian" && format != "binary_big_endian")
      {
        return fail("unknown format '" + format + "'");
      }
      ascii = format == "ascii";
      haveFormat = true;
    }
    else if (key == "element")
    {
      Element e;
      std::string count;
      words >> e.name >> count;
      // VTK's reader keeps counts in an int.
      if (!ParseCount(count, 0x7fffffff, e.count))
      {
        return fail("element '" + e.name + "' has a bad count '" + count + "'");
      }
      elements.push_back(e);
    }
    else if (key == "property")
    {
      if (elements.empty())
      {
        return fail("a property before any element");
      }
      std::string type;
      words >> type;
      Element& e = elements.back();
      ++e.properties;
      if (type == "list")
      {
        std::string countType, itemType;
        words >> countType >> itemType;
        if (PlyTypeSize(countType) == 0 || PlyTypeSize(itemType) == 0)
        {
          return fail("unknown list types '" + countType + "', '" + itemType + "'");
        }
        e.minBytes += PlyTypeSize(countType);
      }
      else
      {
        if (PlyTypeSize(type) == 0)
        {
          return fail("unknown property type '" + type + "'");
        }
        e.minBytes += PlyTypeSize(type);
      }
    }
    else if (key != "comment" && key != "obj_info" && !key.empty())
    {
      return fail("unknown header line '" + line.substr(0, 40) + "'");
    }
  }
  if (!ended)
  {
    return fail("no 'end_header' in its first 64 KiB");
  }
  if (!haveFormat)
  {
    return fail("no 'format' line");
  }
  const std::uint64_t body = size - std::min<std::uint64_t>(size, in.tellg());
  if (ascii)
  {
    // One element a line: the file must have that many more lines.
    std::uint64_t needed = 0;
    for (const Element& e : elements)
    {
      needed += e.properties > 0 ? e.count : 0;
    }
    std::uint64_t found = 0;
    while (found < needed && std::getline(in, line))
    {
      found += line.find_first_not_of(" \t\r") != std::string::npos;
    }
    if (found < needed)
    {
      std::ostringstream s;
      s << "its header announces " << needed << " elements but it has " << found
        << " lines of data";
      return fail(s.str());
    }
    return true;
  }
  std::uint64_t needed = 0;
  for (const Element& e : elements)
  {
    needed += e.count * e.minBytes;
  }
  if (needed > body)
  {
    std::ostringstream s;
    s << "its header announces at least " << needed << " bytes of data but " << body
      << " follow it";
    return fail(s.str());
  }
  return true;
}

bool CheckLegacyVtkFile(const std::string& path, std::string& error)
{
  std::uint64_t size = 0;
  if (!FileSize(path, size, error))
  {
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  std::string line;
  // Section keywords and which of their numbers count values that the reader allocates.
  static const char* sections[] = { "POINTS", "VERTICES", "LINES", "POLYGONS", "TRIANGLE_STRIPS",
    "POINT_DATA", "CELL_DATA", "OFFSETS", "CONNECTIVITY" };
  while (std::getline(in, line))
  {
    std::istringstream words(line);
    std::string key;
    words >> key;
    key = Lower(key);
    for (const char* s : sections)
    {
      if (key != Lower(s))
      {
        continue;
      }
      std::string word;
      for (int k = 0; k < 2 && words >> word; ++k)
      {
        if (!std::isdigit(static_cast<unsigned char>(word[0])))
        {
          break;
        }
        // A point takes at least 3 bytes (three numbers), any other value at least one.
        std::uint64_t n = 0;
        if (!ParseCount(word, key == "points" ? size / 3 : size, n))
        {
          error = path + ": not a valid VTK file: " + s + " announces " + word +
            " values, more than the file's " + std::to_string(size) + " bytes can hold";
          return false;
        }
      }
    }
  }
  return true;
}

bool CheckStlFile(const std::string& path, std::string& error)
{
  std::uint64_t size = 0;
  if (!FileSize(path, size, error))
  {
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  char header[84] = {};
  in.read(header, 84);
  if (in.gcount() < 84 || std::string(header, 5) == "solid")
  {
    return true; // ASCII, or too short to be binary: the reader reports it
  }
  const auto* b = reinterpret_cast<const unsigned char*>(header + 80);
  const std::uint64_t triangles = std::uint64_t(b[0]) | (std::uint64_t(b[1]) << 8) |
    (std::uint64_t(b[2]) << 16) | (std::uint64_t(b[3]) << 24);
  if (84 + 50 * triangles > size)
  {
    error = path + ": not a valid binary STL file: it announces " + std::to_string(triangles) +
      " triangles but has room for " + std::to_string((size - 84) / 50);
    return false;
  }
  return true;
}

bool CheckMeshFile(const std::string& path, std::string& error)
{
  const std::size_t dot = path.find_last_of('.');
  const std::string ext = dot == std::string::npos ? "" : Lower(path.substr(dot));
  if (ext == ".ply")
  {
    return CheckPlyFile(path, error);
  }
  if (ext == ".vtk")
  {
    return CheckLegacyVtkFile(path, error);
  }
  if (ext == ".stl")
  {
    return CheckStlFile(path, error);
  }
  std::uint64_t size = 0;
  return FileSize(path, size, error);
}
} // namespace catar
