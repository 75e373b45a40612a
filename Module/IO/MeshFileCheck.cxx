#include "MeshFileCheck.h"

#include <algorithm>
#include <cctype>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

namespace catar
{
bool MeshFileSize(const std::string& path, std::uint64_t& size, std::string& error)
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

namespace
{
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
  if (!MeshFileSize(path, size, error))
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
    std::vector<std::string> scalars; // names of the scalar properties
    std::vector<std::string> lists;   // names of the list properties
    std::vector<bool> isList;         // the properties in order: a list or a scalar
    struct Property
    {
      std::string type;      // scalar type, or the list items' type
      std::string countType; // lists only
      std::string name;
    };
    std::vector<Property> props; // in order
  };
  std::vector<Element> elements;
  bool ascii = false, haveFormat = false, ended = false;
  std::string format;
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
    if (line.size() >= 4000 || line.find('\0') != std::string::npos)
    {
      return fail("a header line is longer than 4000 bytes or holds a NUL byte");
    }
    // The reader splits header lines at spaces and tabs only: another control character (a
    // vertical tab, ...) joins two words for it, which it does not survive.
    const auto control = std::find_if(line.begin(), line.end(),
      [](unsigned char c) { return (c < 0x20 && c != '\t') || c == 0x7f; });
    if (control != line.end())
    {
      std::ostringstream s;
      s << "header line " << lines + 2 << " holds the control character 0x" << std::hex
        << static_cast<int>(static_cast<unsigned char>(*control));
      return fail(s.str());
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
        std::string name;
        words >> name;
        e.lists.push_back(name);
        e.isList.push_back(true);
        e.props.push_back({ itemType, countType, name });
      }
      else
      {
        if (PlyTypeSize(type) == 0)
        {
          return fail("unknown property type '" + type + "'");
        }
        e.minBytes += PlyTypeSize(type);
        std::string name;
        words >> name;
        e.scalars.push_back(name);
        e.isList.push_back(false);
        e.props.push_back({ type, "", name });
      }
    }
    else if (key.empty())
    {
      return fail("a blank header line"); // the reader loses its place on one
    }
    else if (key != "comment" && key != "obj_info")
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
  // What the reader needs (it does not check all of it): one 'vertex' element with scalar x, y
  // and z, and one 'face' element with a list 'vertex_indices' (or 'vertex_index').
  auto count = [&](const std::string& name) {
    return std::count_if(
      elements.begin(), elements.end(), [&](const Element& e) { return e.name == name; });
  };
  auto has = [](const std::vector<std::string>& names, const char* name) {
    return std::find(names.begin(), names.end(), name) != names.end();
  };
  if (count("vertex") != 1 || count("face") != 1)
  {
    return fail("it needs one 'vertex' and one 'face' element");
  }
  for (const Element& e : elements)
  {
    if (e.name == "vertex" && !(has(e.scalars, "x") && has(e.scalars, "y") && has(e.scalars, "z")))
    {
      return fail("its 'vertex' element lacks scalar properties x, y and z");
    }
    if (e.name == "face" && !has(e.lists, "vertex_indices") && !has(e.lists, "vertex_index"))
    {
      return fail("its 'face' element has no list property 'vertex_indices'");
    }
    if (e.name == "face" && (has(e.scalars, "vertex_indices") || has(e.scalars, "vertex_index")))
    {
      return fail("its 'face' property 'vertex_indices' must be a list");
    }
  }
  const std::uint64_t body = size - std::min<std::uint64_t>(size, in.tellg());
  std::uint64_t vertices = 0;
  for (const Element& e : elements)
  {
    vertices = e.name == "vertex" ? e.count : vertices;
  }
  if (ascii)
  {
    // One element a line, with a word for each scalar property and, for each list, a count and
    // that many words (the reader reads missing words through a null pointer).
    std::uint64_t lineNumber = 0;
    for (const Element& e : elements)
    {
      for (std::uint64_t k = 0; k < e.count; ++k)
      {
        if (!std::getline(in, line))
        {
          std::ostringstream s;
          s << "its data ends before element " << k << " of '" << e.name << "' (" << e.count
            << " announced)";
          return fail(s.str());
        }
        ++lineNumber;
        if (in.eof())
        {
          return fail("its last data line has no line end"); // the reader then runs past it
        }
        // The reader reads a line into 4096 bytes and its words as C strings.
        if (line.size() >= 4000 || line.find('\0') != std::string::npos)
        {
          std::ostringstream s;
          s << "data line " << lineNumber << " is longer than 4000 bytes or holds a NUL byte";
          return fail(s.str());
        }
        std::istringstream words(line);
        std::string word;
        for (bool list : e.isList)
        {
          if (!(words >> word))
          {
            std::ostringstream s;
            s << "data line " << lineNumber << " has too few values for element '" << e.name << "'";
            return fail(s.str());
          }
          std::uint64_t n = 0;
          if (list)
          {
            if (!ParseCount(word, 1u << 20, n))
            {
              std::ostringstream s;
              s << "data line " << lineNumber << " has a bad list count '" << word.substr(0, 20)
                << "'";
              return fail(s.str());
            }
            for (std::uint64_t j = 0; j < n; ++j)
            {
              if (!(words >> word))
              {
                std::ostringstream s;
                s << "data line " << lineNumber << " has fewer list values than its count";
                return fail(s.str());
              }
              std::uint64_t id = 0;
              if (e.name == "face" && !(ParseCount(word, vertices - 1, id) && vertices > 0))
              {
                std::ostringstream s;
                s << "data line " << lineNumber << ": face " << k << " names vertex '"
                  << word.substr(0, 20) << "', but there are " << vertices << " vertices";
                return fail(s.str());
              }
            }
          }
        }
      }
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
  // Walk the data: every list's count must fit in the file, and every face's vertex ids must
  // name a vertex (the reader builds cells from them before any check).
  std::string data(static_cast<std::size_t>(body), '\0');
  in.read(&data[0], static_cast<std::streamsize>(body));
  if (static_cast<std::uint64_t>(in.gcount()) != body)
  {
    return fail("its data cannot be read");
  }
  const bool big = format == "binary_big_endian";
  std::size_t at = 0;
  // The value of type `type` at `at` (integers only: list counts and vertex ids).
  auto integer = [&](const std::string& type, std::int64_t& v) {
    const int n = PlyTypeSize(type);
    if (at + n > data.size())
    {
      return false;
    }
    std::uint64_t u = 0;
    for (int b = 0; b < n; ++b)
    {
      const std::uint64_t byte = static_cast<unsigned char>(data[at + (big ? b : n - 1 - b)]);
      u = (u << 8) | byte;
    }
    const bool isSigned = type == "char" || type == "int8" || type == "short" || type == "int16" ||
      type == "int" || type == "int32";
    v = static_cast<std::int64_t>(u);
    if (isSigned && n < 8 && (u >> (8 * n - 1)) != 0)
    {
      v -= std::int64_t(1) << (8 * n);
    }
    at += n;
    return true;
  };
  for (const Element& e : elements)
  {
    for (std::uint64_t k = 0; k < e.count; ++k)
    {
      for (const Element::Property& prop : e.props)
      {
        if (prop.countType.empty())
        {
          at += PlyTypeSize(prop.type);
          continue;
        }
        std::int64_t n = 0;
        if (!integer(prop.countType, n) || n < 0 ||
          static_cast<std::uint64_t>(n) * PlyTypeSize(prop.type) > data.size() - at)
        {
          std::ostringstream s;
          s << "element " << k << " of '" << e.name << "' has a list count that does not fit";
          return fail(s.str());
        }
        const bool ids =
          e.name == "face" && (prop.name == "vertex_indices" || prop.name == "vertex_index");
        const bool floating = prop.type == "float" || prop.type == "float32" ||
          prop.type == "double" || prop.type == "float64";
        for (std::int64_t j = 0; j < n; ++j)
        {
          if (!ids || floating)
          {
            at += PlyTypeSize(prop.type);
            continue;
          }
          std::int64_t id = 0;
          integer(prop.type, id);
          if (id < 0 || static_cast<std::uint64_t>(id) >= vertices)
          {
            std::ostringstream s;
            s << "face " << k << " names vertex " << id << ", but there are " << vertices
              << " vertices";
            return fail(s.str());
          }
        }
      }
      if (at > data.size())
      {
        std::ostringstream s;
        s << "its data ends before element " << k << " of '" << e.name << "'";
        return fail(s.str());
      }
    }
  }
  return true;
}

bool CheckLegacyVtkFile(const std::string& path, std::string& error)
{
  std::uint64_t size = 0;
  if (!MeshFileSize(path, size, error))
  {
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  // Section keywords whose next numbers count values that the reader allocates. The reader reads
  // words, not lines, and compares only a keyword's length ("POINTS-1" is POINTS to it).
  static const char* sections[] = { "points", "vertices", "lines", "polygons", "triangle_strips",
    "point_data", "cell_data", "offsets", "connectivity" };
  std::string word;
  const char* pending = nullptr; // the section whose counts come next
  int counts = 0;
  // A word the reader takes for a number (it reads counts with operator>>, so a sign counts: a
  // negative count turns into a huge one). ParseCount then refuses what is not a count.
  const auto numeric = [](const std::string& w) {
    const std::size_t first = !w.empty() && (w[0] == '-' || w[0] == '+') ? 1 : 0;
    return first < w.size() && std::isdigit(static_cast<unsigned char>(w[first]));
  };
  while (in >> word)
  {
    if (pending && counts < 2 && numeric(word))
    {
      // A point takes at least 3 bytes (three numbers), any other value at least one.
      std::uint64_t n = 0;
      if (!ParseCount(word, std::string(pending) == "points" ? size / 3 : size, n))
      {
        std::string keyword = pending;
        std::transform(keyword.begin(), keyword.end(), keyword.begin(),
          [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
        error = path + ": not a valid VTK file: " + keyword + " announces " + word.substr(0, 24) +
          (std::isdigit(static_cast<unsigned char>(word[0]))
              ? " values, more than the file's " + std::to_string(size) + " bytes can hold"
              : " values, which is not a count");
        return false;
      }
      ++counts;
      continue;
    }
    pending = nullptr;
    const std::string key = Lower(word);
    // Attribute headers whose component counts the reader allocates by: SCALARS name type [n]
    // (1 to 4), COLOR_SCALARS name n (1 to 4), TEXTURE_COORDINATES name n type (1 to 3).
    // Matched as the reader matches them: by the keyword's length ("SCALARS-1" is SCALARS).
    const auto is = [&key](const char* keyword) {
      return key.compare(0, std::strlen(keyword), keyword) == 0;
    };
    const int skip = is("scalars")                         ? 2
      : (is("color_scalars") || is("texture_coordinates")) ? 1
                                                           : -1;
    if (skip >= 0)
    {
      // The reader reads every part as a word, wherever the lines break: the name (and SCALARS'
      // type), then the count (for SCALARS the next word unless it is LOOKUP_TABLE), with atoi:
      // a sign and the digits that lead the word count.
      std::string w;
      for (int k = 0; k < skip && in >> w; ++k)
      {
      }
      if (in >> w && numeric(w))
      {
        const std::size_t sign = w[0] == '-' || w[0] == '+' ? 1 : 0;
        const std::size_t digits = std::find_if(w.begin() + sign, w.end(),
                                     [](unsigned char c) { return !std::isdigit(c); }) -
          w.begin();
        const std::size_t plus = w[0] == '+' ? 1 : 0; // atoi's "+3" is 3; "-3" is refused below
        w = w.substr(plus, digits - plus);
        std::uint64_t n = 0;
        const std::uint64_t most = is("texture_coordinates") ? 3 : 4;
        if (!ParseCount(w, most, n) || n < 1)
        {
          error = path + ": not a valid VTK file: " + word + " has " + w.substr(0, 24) +
            " components (1 to " + std::to_string(most) + ")";
          return false;
        }
      }
      continue;
    }
    for (const char* s : sections)
    {
      if (key.compare(0, std::strlen(s), s) == 0)
      {
        pending = s;
        counts = 0;
      }
    }
  }
  return true;
}

bool CheckObjFile(const std::string& path, std::string& error)
{
  std::uint64_t size = 0;
  if (!MeshFileSize(path, size, error))
  {
    return false;
  }
  // Two passes: the counts of v, vt and vn, then every reference of f, l and p (1-based, or
  // negative: relative to the ones read so far). The reader reads through them unchecked.
  std::ifstream in(path, std::ios::binary);
  std::string line;
  std::int64_t total[3] = { 0, 0, 0 };
  while (std::getline(in, line))
  {
    std::istringstream words(line);
    std::string key;
    words >> key;
    total[0] += key == "v";
    total[1] += key == "vt";
    total[2] += key == "vn";
  }
  in.clear();
  in.seekg(0);
  std::int64_t sofar[3] = { 0, 0, 0 };
  std::uint64_t number = 0;
  while (std::getline(in, line))
  {
    ++number;
    std::istringstream words(line);
    std::string key;
    words >> key;
    sofar[0] += key == "v";
    sofar[1] += key == "vt";
    sofar[2] += key == "vn";
    if (key != "f" && key != "l" && key != "p")
    {
      continue;
    }
    std::string ref;
    while (words >> ref)
    {
      // v, v/vt, v//vn, v/vt/vn
      std::size_t at = 0;
      for (int k = 0; k < 3 && at <= ref.size(); ++k)
      {
        const std::size_t slash = std::min(ref.find('/', at), ref.size());
        const std::string part = ref.substr(at, slash - at);
        at = slash + 1;
        if (part.empty() && k > 0)
        {
          continue;
        }
        char* end = nullptr;
        const long long id = std::strtoll(part.c_str(), &end, 10);
        const bool isNumber = !part.empty() && end && *end == '\0';
        // LLONG_MIN (what strtoll gives for any smaller number) cannot be negated: out of range.
        const bool valid =
          isNumber && id != 0 && id != LLONG_MIN && (id > 0 ? id <= total[k] : -id <= sofar[k]);
        if (!valid)
        {
          static const char* kinds[] = { "vertex", "texture coordinate", "normal" };
          error = path + ": not a valid OBJ file: line " + std::to_string(number) + " names " +
            kinds[k] + " '" + part.substr(0, 24) + "', but the file has " +
            std::to_string(total[k]) + " of them";
          return false;
        }
        if (slash == ref.size())
        {
          break;
        }
      }
    }
  }
  return true;
}

bool CheckStlFile(const std::string& path, std::string& error)
{
  std::uint64_t size = 0;
  if (!MeshFileSize(path, size, error))
  {
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  char header[256] = {};
  in.read(header, 256);
  const std::streamsize got = in.gcount();
  // As the reader decides: ASCII when it starts with "solid" and its first 256 bytes are text.
  const bool text = std::all_of(header, header + got, [](char c) {
    const unsigned char u = static_cast<unsigned char>(c);
    return (u >= 32 && u < 127) || u == '\n' || u == '\r' || u == '\t';
  });
  if (got >= 5 && std::string(header, 5) == "solid" && text)
  {
    return true;
  }
  if (got < 84)
  {
    error = path + ": not a valid STL file: too short for a binary STL header";
    return false;
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
  if (ext == ".vtp")
  {
    return CheckVtpFile(path, error);
  }
  if (ext == ".obj")
  {
    return CheckObjFile(path, error);
  }
  std::uint64_t size = 0;
  return MeshFileSize(path, size, error);
}
double EstimatedMeshTriangles(const std::string& path)
{
  std::uint64_t size = 0;
  std::string error;
  if (!MeshFileSize(path, size, error))
  {
    return 0.0;
  }
  const std::string ext = Lower(path.substr(std::min(path.size(), path.rfind('.'))));
  if (ext == ".stl")
  {
    std::ifstream in(path, std::ios::binary);
    char header[84] = {};
    const bool binary = in.read(header, sizeof(header)) && std::string(header, 5) != "solid";
    if (binary)
    {
      return size >= 84 ? std::floor(static_cast<double>(size - 84) / 50.0) : 0.0;
    }
    return static_cast<double>(size) / 250.0;
  }
  return static_cast<double>(size) / (ext == ".obj" ? 40.0 : 20.0);
}
} // namespace catar
