// CatadioptricAR Core: the check of VTK XML PolyData files (.vtp) before vtkXMLPolyDataReader
// sees them. The reader trusts what a file says: a piece that announces 10^9 points makes it
// allocate them before it finds the data missing, and a compressed block table that lies makes
// it copy past its buffers. Here every array of every piece is walked as the reader will walk
// it: its values must be there (ASCII numbers counted; binary headers read and, when compressed,
// every block decompressed to the size its table gives), and the cell offsets must rise and end
// inside the connectivity.
#include "MeshFileCheck.h"

#include <lz4.h>
#include <lzma.h>
#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <fstream>
#include <map>
#include <memory>
#include <stdexcept>
#include <vector>

namespace catar
{
namespace
{
// Thrown inside the check; the message becomes the error's sentence.
struct VtpError : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

// ---- A small XML reader: enough for the files VTK writes, strict about the rest. ----

struct Element
{
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text; // character data directly inside the element (not its children's)
  std::vector<Element> children;

  const std::string* Attribute(const std::string& key) const
  {
    const auto it = attributes.find(key);
    return it == attributes.end() ? nullptr : &it->second;
  }
};

class XmlReader
{
public:
  explicit XmlReader(const std::string& text)
    : Text(text)
  {
  }

  // Parses the root element. Stops at <AppendedData ...>: `appendedStart` is then the position
  // just after its '_' marker (npos when the file has none) and `appendedEncoding` its encoding.
  Element Parse()
  {
    this->SkipProlog();
    Element root;
    if (!this->ParseElement(root, 0))
    {
      throw VtpError("the root element ends early");
    }
    return root;
  }

  std::size_t appendedStart = std::string::npos;
  std::string appendedEncoding;

private:
  static constexpr int kMaxDepth = 32;

  bool AtEnd() const { return this->Pos >= this->Text.size(); }

  void SkipSpace()
  {
    while (!this->AtEnd() && std::isspace(static_cast<unsigned char>(this->Text[this->Pos])))
    {
      ++this->Pos;
    }
  }

  void Expect(const char* what)
  {
    if (this->Text.compare(this->Pos, std::strlen(what), what) != 0)
    {
      throw VtpError(std::string("expected '") + what + "' at byte " + std::to_string(this->Pos));
    }
    this->Pos += std::strlen(what);
  }

  void SkipPast(const char* end)
  {
    const std::size_t at = this->Text.find(end, this->Pos);
    if (at == std::string::npos)
    {
      throw VtpError(std::string("unterminated markup (no '") + end + "')");
    }
    this->Pos = at + std::strlen(end);
  }

  // The XML declaration, comments and processing instructions before the root.
  void SkipProlog()
  {
    for (;;)
    {
      this->SkipSpace();
      if (this->Text.compare(this->Pos, 2, "<?") == 0)
      {
        this->SkipPast("?>");
      }
      else if (this->Text.compare(this->Pos, 4, "<!--") == 0)
      {
        this->SkipPast("-->");
      }
      else
      {
        return;
      }
    }
  }

  std::string Name()
  {
    const std::size_t start = this->Pos;
    while (!this->AtEnd())
    {
      const unsigned char c = this->Text[this->Pos];
      if (!(std::isalnum(c) || c == '_' || c == '-' || c == ':' || c == '.'))
      {
        break;
      }
      ++this->Pos;
    }
    if (this->Pos == start)
    {
      throw VtpError("expected a name at byte " + std::to_string(start));
    }
    return this->Text.substr(start, this->Pos - start);
  }

  // Returns false for "</..." (the caller's end tag); fills `e` otherwise.
  bool ParseElement(Element& e, int depth)
  {
    if (depth > kMaxDepth)
    {
      throw VtpError("elements nested more than " + std::to_string(kMaxDepth) + " deep");
    }
    this->Expect("<");
    e.name = this->Name();
    for (;;)
    {
      this->SkipSpace();
      if (this->AtEnd())
      {
        throw VtpError("the file ends inside <" + e.name + ">");
      }
      if (this->Text.compare(this->Pos, 2, "/>") == 0)
      {
        this->Pos += 2;
        return true;
      }
      if (this->Text[this->Pos] == '>')
      {
        ++this->Pos;
        break;
      }
      const std::string key = this->Name();
      this->SkipSpace();
      this->Expect("=");
      this->SkipSpace();
      if (this->AtEnd() || (this->Text[this->Pos] != '"' && this->Text[this->Pos] != '\''))
      {
        throw VtpError("attribute '" + key + "' of <" + e.name + "> has no quoted value");
      }
      const char quote = this->Text[this->Pos++];
      const std::size_t end = this->Text.find(quote, this->Pos);
      if (end == std::string::npos)
      {
        throw VtpError("attribute '" + key + "' of <" + e.name + "> is not closed");
      }
      e.attributes[key] = this->Text.substr(this->Pos, end - this->Pos);
      this->Pos = end + 1;
    }
    if (e.name == "AppendedData")
    {
      // Raw bytes may follow: the XML ends here for the reader too.
      const std::string* encoding = e.Attribute("encoding");
      this->appendedEncoding = encoding ? *encoding : "raw";
      this->SkipSpace();
      this->Expect("_");
      this->appendedStart = this->Pos;
      this->Pos = this->Text.size();
      return true;
    }
    for (;;)
    {
      const std::size_t lt = this->Text.find('<', this->Pos);
      if (lt == std::string::npos)
      {
        throw VtpError("<" + e.name + "> is not closed");
      }
      e.text.append(this->Text, this->Pos, lt - this->Pos);
      this->Pos = lt;
      if (this->Text.compare(this->Pos, 4, "<!--") == 0)
      {
        this->SkipPast("-->");
        continue;
      }
      if (this->Text.compare(this->Pos, 2, "</") == 0)
      {
        this->Pos += 2;
        const std::string name = this->Name();
        this->SkipSpace();
        this->Expect(">");
        if (name != e.name)
        {
          throw VtpError("<" + e.name + "> is closed by </" + name + ">");
        }
        return true;
      }
      e.children.emplace_back();
      this->ParseElement(e.children.back(), depth + 1);
      if (this->appendedStart != std::string::npos)
      {
        return true; // everything after <AppendedData> is data
      }
    }
  }

  const std::string& Text;
  std::size_t Pos = 0;
};

// ---- Numbers and sizes ----

// a * b, saturated at UINT64_MAX.
std::uint64_t Mul(std::uint64_t a, std::uint64_t b)
{
  if (a != 0 && b > UINT64_MAX / a)
  {
    return UINT64_MAX;
  }
  return a * b;
}

std::uint64_t Count(const Element& e, const char* key, std::uint64_t fallback)
{
  const std::string* v = e.Attribute(key);
  if (!v)
  {
    return fallback;
  }
  if (v->empty() || v->size() > 19 ||
    !std::all_of(v->begin(), v->end(), [](unsigned char c) { return std::isdigit(c); }))
  {
    throw VtpError("<" + e.name + "> " + key + "=\"" + *v + "\" is not a count");
  }
  return std::stoull(*v);
}

int WordSize(const std::string& type)
{
  static const std::map<std::string, int> sizes = { { "Int8", 1 }, { "UInt8", 1 }, { "Int16", 2 },
    { "UInt16", 2 }, { "Int32", 4 }, { "UInt32", 4 }, { "Int64", 8 }, { "UInt64", 8 },
    { "Float32", 4 }, { "Float64", 8 }, { "String", 1 }, { "Bit", 1 } };
  const auto it = sizes.find(type);
  return it == sizes.end() ? 0 : it->second;
}

// ---- Base64, as vtkBase64InputStream reads it: independent, padded streams. ----

int Base64Value(unsigned char c)
{
  if (c >= 'A' && c <= 'Z')
  {
    return c - 'A';
  }
  if (c >= 'a' && c <= 'z')
  {
    return c - 'a' + 26;
  }
  if (c >= '0' && c <= '9')
  {
    return c - '0' + 52;
  }
  return c == '+' ? 62 : c == '/' ? 63 : -1;
}

// Decodes `bytes` bytes from the base64 text at `pos` (a stream of whole quadruplets); advances
// `pos` past the quadruplets used. Throws when the text ends or is not base64 first.
std::string DecodeBase64(const std::string& text, std::size_t& pos, std::uint64_t bytes)
{
  std::string out;
  const std::uint64_t quads = (bytes + 2) / 3;
  if (pos > text.size() || Mul(quads, 4) > text.size() - pos)
  {
    throw VtpError("base64 data shorter than its header says");
  }
  out.reserve(static_cast<std::size_t>(quads * 3));
  for (std::uint64_t q = 0; q < quads; ++q, pos += 4)
  {
    int v[4];
    for (int k = 0; k < 4; ++k)
    {
      const unsigned char c = text[pos + k];
      v[k] = c == '=' && k >= 2 ? 0 : Base64Value(c);
      if (v[k] < 0)
      {
        throw VtpError("base64 data holds a character that is not base64");
      }
    }
    out.push_back(static_cast<char>((v[0] << 2) | (v[1] >> 4)));
    out.push_back(static_cast<char>(((v[1] & 15) << 4) | (v[2] >> 2)));
    out.push_back(static_cast<char>(((v[2] & 3) << 6) | v[3]));
  }
  out.resize(static_cast<std::size_t>(bytes));
  return out;
}

// ---- The file ----

struct File
{
  std::string text;
  bool bigEndian = false;
  int headerSize = 4;     // UInt32 or UInt64
  std::string compressor; // "", "zlib", "lz4", "lzma"
  std::size_t appendedStart = std::string::npos;
  bool appendedBase64 = false;
};

std::uint64_t Word(const File& f, const std::string& bytes, std::size_t index, int size)
{
  std::uint64_t v = 0;
  for (int k = 0; k < size; ++k)
  {
    const auto b = static_cast<unsigned char>(bytes[index * size + k]);
    v |= static_cast<std::uint64_t>(b) << (8 * (f.bigEndian ? size - 1 - k : k));
  }
  return v;
}

// `bytes` raw bytes at `pos` of `text`; advances `pos`.
std::string ReadRaw(const std::string& text, std::size_t& pos, std::uint64_t bytes)
{
  if (pos > text.size() || bytes > text.size() - pos)
  {
    throw VtpError("appended data shorter than its header says");
  }
  std::string out = text.substr(pos, static_cast<std::size_t>(bytes));
  pos += static_cast<std::size_t>(bytes);
  return out;
}

// Decompresses one block and checks its size.
void Decompress(const File& f, const std::string& in, std::string& out, std::uint64_t expected)
{
  // zlib expands at most 1032 times, LZ4 at most 255 times: a larger claim is a lie, refused
  // before its buffer is allocated.
  const std::uint64_t ratio = f.compressor == "zlib" ? 1032 : f.compressor == "lz4" ? 256 : 0;
  if (ratio != 0 && expected > Mul(in.size(), ratio) + 64)
  {
    throw VtpError("a compressed block claims more bytes than its compressor can make of it");
  }
  out.resize(static_cast<std::size_t>(expected));
  bool ok = false;
  if (f.compressor == "zlib")
  {
    uLongf size = static_cast<uLongf>(expected);
    ok = uncompress(reinterpret_cast<Bytef*>(&out[0]), &size,
           reinterpret_cast<const Bytef*>(in.data()), static_cast<uLong>(in.size())) == Z_OK &&
      size == expected;
  }
  else if (f.compressor == "lz4")
  {
    ok = expected <= static_cast<std::uint64_t>(INT32_MAX) &&
      in.size() <= static_cast<std::size_t>(INT32_MAX) &&
      LZ4_decompress_safe(in.data(), &out[0], static_cast<int>(in.size()),
        static_cast<int>(expected)) == static_cast<int>(expected);
  }
  else if (f.compressor == "lzma")
  {
    std::uint64_t memlimit = UINT64_MAX;
    std::size_t inPos = 0;
    std::size_t outPos = 0;
    ok = lzma_stream_buffer_decode(&memlimit, 0, nullptr,
           reinterpret_cast<const std::uint8_t*>(in.data()), &inPos, in.size(),
           reinterpret_cast<std::uint8_t*>(&out[0]), &outPos, out.size()) == LZMA_OK &&
      outPos == expected;
  }
  if (!ok)
  {
    throw VtpError("a compressed block does not decompress to the size its table gives");
  }
}

// The largest block and total a compressed array may announce (the reader allocates them).
constexpr std::uint64_t kMaxBlockBytes = std::uint64_t(1) << 30;

// The bytes of a binary array (inline base64 or appended), decompressed, as
// vtkXMLDataParser reads them: uncompressed, one stream of a header word (the byte count) and the
// data; compressed, a header stream (block count, block size, last block size, then each block's
// compressed size) and a data stream of the blocks. In base64 each stream is padded on its own.
// When `keep` is false only the byte count is returned (blocks are still decompressed and checked).
std::uint64_t ReadBinary(const File& f, const Element& array, bool keep, std::string& bytes)
{
  const bool inlineData = *array.Attribute("format") == "binary";
  const std::string& source = inlineData ? array.text : f.text;
  const bool base64 = inlineData || f.appendedBase64;
  std::size_t pos = 0;
  if (inlineData)
  {
    while (pos < source.size() && std::isspace(static_cast<unsigned char>(source[pos])))
    {
      ++pos;
    }
  }
  else
  {
    if (f.appendedStart == std::string::npos)
    {
      throw VtpError("an appended array, but the file has no <AppendedData>");
    }
    const std::uint64_t offset = Count(array, "offset", UINT64_MAX);
    if (offset > f.text.size() - f.appendedStart)
    {
      throw VtpError("offset=\"" + std::to_string(offset) + "\" is past the end of the file");
    }
    pos = f.appendedStart + static_cast<std::size_t>(offset);
  }
  const int hs = f.headerSize;
  // The first `n` bytes of the stream at `pos`, without moving.
  auto peek = [&](std::uint64_t n) {
    std::size_t probe = pos;
    return base64 ? DecodeBase64(source, probe, n) : ReadRaw(source, probe, n);
  };
  auto read = [&](std::uint64_t n) {
    return base64 ? DecodeBase64(source, pos, n) : ReadRaw(source, pos, n);
  };
  if (f.compressor.empty())
  {
    const std::uint64_t n = Word(f, peek(static_cast<std::uint64_t>(hs)), 0, hs);
    if (n > source.size())
    {
      throw VtpError("binary data shorter than its header says");
    }
    if (base64)
    {
      std::string all = read(n + hs);
      if (keep)
      {
        bytes = all.substr(static_cast<std::size_t>(hs));
      }
    }
    else
    {
      read(static_cast<std::uint64_t>(hs));
      std::string data = read(n);
      if (keep)
      {
        bytes.swap(data);
      }
    }
    return n;
  }
  const std::string head = peek(3 * static_cast<std::uint64_t>(hs));
  const std::uint64_t blocks = Word(f, head, 0, hs);
  const std::uint64_t blockSize = Word(f, head, 1, hs);
  const std::uint64_t lastSize = Word(f, head, 2, hs);
  if (blocks == 0)
  {
    return 0;
  }
  if (blockSize == 0 || blockSize > kMaxBlockBytes || lastSize > blockSize)
  {
    throw VtpError("a compressed array's block sizes are not valid (" + std::to_string(blockSize) +
      " bytes a block, " + std::to_string(lastSize) + " in the last)");
  }
  if (Mul(blocks, static_cast<std::uint64_t>(hs)) > source.size())
  {
    throw VtpError("a compressed array announces more blocks than the file can hold");
  }
  const std::string table = read((3 + blocks) * hs).substr(3 * static_cast<std::size_t>(hs));
  std::uint64_t compressedTotal = 0;
  for (std::uint64_t b = 0; b < blocks; ++b)
  {
    compressedTotal += std::min<std::uint64_t>(
      Word(f, table, static_cast<std::size_t>(b), hs), source.size() + std::uint64_t(1));
    if (compressedTotal > source.size())
    {
      throw VtpError("the compressed blocks are larger than the file");
    }
  }
  const std::string packed = read(compressedTotal);
  if (keep)
  {
    bytes.clear();
  }
  std::string block;
  std::size_t at = 0;
  for (std::uint64_t b = 0; b < blocks; ++b)
  {
    const auto c = static_cast<std::size_t>(Word(f, table, static_cast<std::size_t>(b), hs));
    const std::uint64_t size = b + 1 == blocks && lastSize ? lastSize : blockSize;
    Decompress(f, packed.substr(at, c), block, size);
    at += c;
    if (keep)
    {
      bytes += block;
    }
  }
  return (blocks - 1) * blockSize + (lastSize ? lastSize : blockSize);
}

// Counts the numbers of an ASCII array (at most `need`, then stops); keeps them when `values`.
std::uint64_t CountAscii(const Element& array, std::uint64_t need, std::vector<double>* values)
{
  std::uint64_t n = 0;
  const std::string& t = array.text;
  std::size_t i = 0;
  while (i < t.size() && n < need)
  {
    while (i < t.size() && std::isspace(static_cast<unsigned char>(t[i])))
    {
      ++i;
    }
    const std::size_t start = i;
    while (i < t.size() && !std::isspace(static_cast<unsigned char>(t[i])))
    {
      ++i;
    }
    if (i > start)
    {
      ++n;
      if (values)
      {
        try
        {
          values->push_back(std::stod(t.substr(start, i - start)));
        }
        catch (const std::exception&)
        {
          throw VtpError(
            "'" + t.substr(start, std::min<std::size_t>(i - start, 20)) + "' is not a number");
        }
      }
    }
  }
  return n;
}

// A data array (<DataArray>) or another VTK array: strings and variants are written as <Array>.
bool IsArray(const Element& e)
{
  return e.name == "DataArray" || e.name == "Array";
}

std::string ArrayName(const Element& array)
{
  const std::string* name = array.Attribute("Name");
  return name ? "array '" + *name + "'" : std::string("an unnamed array");
}

// Checks that `array` holds at least `tuples` tuples; returns its values when `values`.
void CheckArray(const File& f, const Element& array, std::uint64_t tuples, int components,
  std::vector<double>* values)
{
  const std::string* type = array.Attribute("type");
  const int word = type ? WordSize(*type) : 0;
  if (word == 0)
  {
    throw VtpError(ArrayName(array) + " has an unknown type '" + (type ? *type : "") + "'");
  }
  const std::uint64_t comps =
    components > 0 ? static_cast<std::uint64_t>(components) : Count(array, "NumberOfComponents", 1);
  if (comps == 0 || comps > 1024)
  {
    throw VtpError(ArrayName(array) + ": NumberOfComponents must be in [1, 1024]");
  }
  const std::uint64_t need = Mul(tuples, comps);
  const std::string* format = array.Attribute("format");
  if (!format || (*format != "ascii" && *format != "binary" && *format != "appended"))
  {
    throw VtpError(ArrayName(array) + ": format must be ascii, binary or appended");
  }
  // String arrays are bytes (ASCII: their codes), each string ended by a 0: at least one a string,
  // which the count below checks like any other array's values.
  if (*format == "ascii")
  {
    const std::uint64_t have = CountAscii(array, need, values);
    if (have < need)
    {
      throw VtpError(ArrayName(array) + " has " + std::to_string(have) + " numbers, but " +
        std::to_string(need) + " are announced");
    }
    return;
  }
  std::string bytes;
  // Bits are packed eight a byte.
  const std::uint64_t have =
    ReadBinary(f, array, values != nullptr, bytes) / word * (*type == "Bit" ? 8 : 1);
  if (have < need)
  {
    throw VtpError(ArrayName(array) + " has " + std::to_string(have) + " values, but " +
      std::to_string(need) + " are announced");
  }
  if (values)
  {
    for (std::uint64_t i = 0; i < need; ++i)
    {
      const std::uint64_t raw = Word(f, bytes, static_cast<std::size_t>(i), word);
      if (*type == "Int64" || *type == "Int32" || *type == "Int16" || *type == "Int8")
      {
        const int shift = 64 - 8 * word;
        values->push_back(static_cast<double>(static_cast<std::int64_t>(raw << shift) >> shift));
      }
      else if (*type == "Float32" || *type == "Float64")
      {
        throw VtpError(ArrayName(array) + " must have an integer type");
      }
      else
      {
        values->push_back(static_cast<double>(raw));
      }
    }
  }
}

const Element* Child(const Element& e, const std::string& name)
{
  for (const Element& c : e.children)
  {
    if (c.name == name)
    {
      return &c;
    }
  }
  return nullptr;
}

const Element* ArrayNamed(const Element& e, const std::string& name)
{
  for (const Element& c : e.children)
  {
    const std::string* n = c.Attribute("Name");
    if (c.name == "DataArray" && n && *n == name)
    {
      return &c;
    }
  }
  return nullptr;
}

// Verts, Lines, Strips or Polys of a piece: offsets rise and end in the connectivity.
void CheckCells(const File& f, const Element& piece, const char* section, std::uint64_t cells)
{
  const Element* e = Child(piece, section);
  if (cells == 0)
  {
    return;
  }
  if (!e)
  {
    throw VtpError(std::string("the piece announces ") + std::to_string(cells) + " " + section +
      " but has no <" + section + ">");
  }
  const Element* offsets = ArrayNamed(*e, "offsets");
  const Element* connectivity = ArrayNamed(*e, "connectivity");
  if (!offsets || !connectivity)
  {
    throw VtpError(std::string("<") + section + "> needs 'offsets' and 'connectivity' arrays");
  }
  std::vector<double> ends;
  CheckArray(f, *offsets, cells, 1, &ends);
  double previous = 0;
  for (double end : ends)
  {
    if (!(end >= previous) || end > 9.0e15)
    {
      throw VtpError(std::string("<") + section + "> offsets must rise from 0");
    }
    previous = end;
  }
  CheckArray(f, *connectivity, static_cast<std::uint64_t>(previous), 1, nullptr);
}

// Every DataArray anywhere, whatever the counts say of it (the reader sets up arrays of empty
// pieces too, naming each component: a component count of 2^32 keeps it busy for minutes).
void CheckArrayHeaders(const Element& e)
{
  if (IsArray(e))
  {
    const std::string* type = e.Attribute("type");
    if (!type || WordSize(*type) == 0)
    {
      throw VtpError(ArrayName(e) + " has an unknown type '" + (type ? *type : "") + "'");
    }
    const std::uint64_t comps = Count(e, "NumberOfComponents", 1);
    if (comps == 0 || comps > 1024)
    {
      throw VtpError(ArrayName(e) + ": NumberOfComponents must be in [1, 1024]");
    }
    Count(e, "NumberOfTuples", 0);
    Count(e, "offset", 0);
  }
  for (const Element& child : e.children)
  {
    CheckArrayHeaders(child);
  }
}

// Two arrays of one name in <PointData>, <CellData> or <FieldData>: the data set keeps only the
// second, and the reader, counting two, then reads into an array that is not there.
void CheckUniqueNames(const Element& data)
{
  std::vector<std::string> names;
  for (const Element& array : data.children)
  {
    const std::string* name = array.Attribute("Name");
    if (!IsArray(array) || !name || name->empty())
    {
      continue;
    }
    if (std::find(names.begin(), names.end(), *name) != names.end())
    {
      throw VtpError("<" + data.name + "> has two arrays named '" + *name + "'");
    }
    names.push_back(*name);
  }
}

void CheckPiece(const File& f, const Element& piece)
{
  const std::uint64_t points = Count(piece, "NumberOfPoints", 0);
  const std::uint64_t cells[4] = { Count(piece, "NumberOfVerts", 0),
    Count(piece, "NumberOfLines", 0), Count(piece, "NumberOfStrips", 0),
    Count(piece, "NumberOfPolys", 0) };
  std::uint64_t allCells = 0;
  for (std::uint64_t c : cells)
  {
    allCells += std::min<std::uint64_t>(c, UINT64_MAX / 8);
  }
  if (points > 0)
  {
    const Element* p = Child(piece, "Points");
    const Element* coordinates = p ? Child(*p, "DataArray") : nullptr;
    if (!coordinates)
    {
      throw VtpError(
        "the piece announces " + std::to_string(points) + " points but has no <Points>");
    }
    if (Count(*coordinates, "NumberOfComponents", 1) != 3)
    {
      throw VtpError("the points must have NumberOfComponents=\"3\"");
    }
    CheckArray(f, *coordinates, points, 3, nullptr);
  }
  const char* sections[4] = { "Verts", "Lines", "Strips", "Polys" };
  for (int s = 0; s < 4; ++s)
  {
    CheckCells(f, piece, sections[s], cells[s]);
  }
  for (const auto& [name, tuples] :
    { std::make_pair("PointData", points), std::make_pair("CellData", allCells) })
  {
    if (const Element* data = Child(piece, name))
    {
      CheckUniqueNames(*data);
      for (const Element& array : data->children)
      {
        if (IsArray(array))
        {
          CheckArray(f, array, tuples, 0, nullptr);
        }
      }
    }
  }
}
} // namespace

bool CheckVtpFile(const std::string& path, std::string& error)
{
  try
  {
    File f;
    {
      std::uint64_t size = 0;
      if (!MeshFileSize(path, size, error))
      {
        return false;
      }
      std::ifstream in(path, std::ios::binary);
      f.text.resize(static_cast<std::size_t>(size));
      in.read(&f.text[0], static_cast<std::streamsize>(size));
      if (!in)
      {
        error = path + ": cannot read the mesh file";
        return false;
      }
    }
    XmlReader xml(f.text);
    const Element root = xml.Parse();
    if (root.name != "VTKFile")
    {
      throw VtpError("the root element is <" + root.name + ">, not <VTKFile>");
    }
    const std::string* type = root.Attribute("type");
    if (!type || *type != "PolyData")
    {
      throw VtpError("not a PolyData file (type=\"" + (type ? *type : "") + "\")");
    }
    const std::string* order = root.Attribute("byte_order");
    f.bigEndian = order && *order == "BigEndian";
    const std::string* header = root.Attribute("header_type");
    if (header && *header != "UInt32" && *header != "UInt64")
    {
      throw VtpError("header_type must be UInt32 or UInt64");
    }
    f.headerSize = header && *header == "UInt64" ? 8 : 4;
    if (const std::string* c = root.Attribute("compressor"))
    {
      static const std::map<std::string, std::string> known = { { "vtkZLibDataCompressor", "zlib" },
        { "vtkLZ4DataCompressor", "lz4" }, { "vtkLZMADataCompressor", "lzma" } };
      const auto it = known.find(*c);
      if (it == known.end())
      {
        throw VtpError("unknown compressor '" + *c + "'");
      }
      f.compressor = it->second;
    }
    f.appendedStart = xml.appendedStart;
    if (f.appendedStart != std::string::npos)
    {
      if (xml.appendedEncoding != "raw" && xml.appendedEncoding != "base64")
      {
        throw VtpError("<AppendedData> encoding must be raw or base64");
      }
      f.appendedBase64 = xml.appendedEncoding == "base64";
    }
    CheckArrayHeaders(root);
    const Element* polyData = Child(root, "PolyData");
    if (!polyData)
    {
      throw VtpError("no <PolyData> element");
    }
    for (const Element& child : polyData->children)
    {
      if (child.name == "Piece")
      {
        CheckPiece(f, child);
      }
      else if (child.name == "FieldData")
      {
        CheckUniqueNames(child);
        for (const Element& array : child.children)
        {
          if (IsArray(array))
          {
            CheckArray(f, array, Count(array, "NumberOfTuples", 0), 0, nullptr);
          }
        }
      }
    }
    return true;
  }
  catch (const VtpError& e)
  {
    error = path + ": not a valid VTK PolyData file: " + e.what();
  }
  catch (const std::bad_alloc&)
  {
    error = path + ": not a valid VTK PolyData file: its sizes need more memory than there is";
  }
  catch (const std::exception& e)
  {
    error = path + ": not a valid VTK PolyData file: " + e.what();
  }
  return false;
}
} // namespace catar
