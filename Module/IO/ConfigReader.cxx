#include "ConfigReader.h"

#include "EditDistance.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <unordered_set>

namespace catar
{
namespace fs
{
struct Node::Impl
{
  YAML::Node node; // always defined (IsDefined()): absent keys have no Impl at all
};

Node::Node() = default;
Node::~Node() = default;
Node::Node(std::unique_ptr<Impl> impl)
  : impl_(std::move(impl))
{
}
Node::Node(const Node& other)
  : impl_(other.impl_ ? std::make_unique<Impl>(*other.impl_) : nullptr)
{
}
Node& Node::operator=(const Node& other)
{
  if (this != &other)
  {
    impl_ = other.impl_ ? std::make_unique<Impl>(*other.impl_) : nullptr;
  }
  return *this;
}

namespace
{
// A plain scalar's number, as YAML's core schema and JSON write them ("+1", "-2.5e3", ".5",
// "1.", ".inf", ".nan"); false for anything else.
bool ParseNumber(const std::string& s, double& value)
{
  if (s.empty())
  {
    return false;
  }
  std::string t = s;
  for (const char* special : { ".inf", ".Inf", ".INF", "+.inf", "+.Inf", "+.INF" })
  {
    if (s == special)
    {
      value = std::numeric_limits<double>::infinity();
      return true;
    }
  }
  for (const char* special : { "-.inf", "-.Inf", "-.INF" })
  {
    if (s == special)
    {
      value = -std::numeric_limits<double>::infinity();
      return true;
    }
  }
  for (const char* special : { ".nan", ".NaN", ".NAN" })
  {
    if (s == special)
    {
      value = std::numeric_limits<double>::quiet_NaN();
      return true;
    }
  }
  const char* first = t.data();
  const char* last = t.data() + t.size();
  if (*first == '+')
  {
    ++first;
  }
  // from_chars reads "inf" and "nan", which YAML does not call numbers.
  if (first == last ||
    !(std::isdigit(static_cast<unsigned char>(*first)) || *first == '.' || *first == '-'))
  {
    return false;
  }
  const auto [end, ec] = std::from_chars(first, last, value);
  if (ec == std::errc::result_out_of_range)
  {
    value = std::numeric_limits<double>::infinity(); // refused as not finite by Numbers
    return true;
  }
  return ec == std::errc() && end == last;
}

bool Plain(const YAML::Node& n)
{
  return n.IsScalar() && n.Tag() != "!"; // "!" marks a quoted scalar
}
} // namespace

bool Node::empty() const
{
  return !impl_;
}

bool Node::isNone() const
{
  return impl_ && impl_->node.IsNull();
}

bool Node::isMap() const
{
  return impl_ && impl_->node.IsMap();
}

bool Node::isSeq() const
{
  return impl_ && impl_->node.IsSequence();
}

bool Node::isNumber() const
{
  double v;
  return impl_ && Plain(impl_->node) && ParseNumber(impl_->node.Scalar(), v);
}

bool Node::isInt() const
{
  const double v = number();
  return std::isfinite(v) && v == std::floor(v) && std::abs(v) <= std::numeric_limits<int>::max();
}

bool Node::isBool() const
{
  if (!impl_ || !Plain(impl_->node))
  {
    return false;
  }
  std::string s = impl_->node.Scalar();
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s == "true" || s == "false";
}

bool Node::isString() const
{
  return impl_ && impl_->node.IsScalar() && !isNumber();
}

Node Node::operator[](const std::string& key) const
{
  if (!isMap())
  {
    return Node();
  }
  // Looked up by hand: yaml-cpp's operator[] can insert, and compares keys by conversion.
  for (YAML::const_iterator it = impl_->node.begin(); it != impl_->node.end(); ++it)
  {
    if (it->first.IsScalar() && it->first.Scalar() == key)
    {
      return Node(std::make_unique<Impl>(Impl{ it->second }));
    }
  }
  return Node();
}

std::vector<Node> Node::items() const
{
  std::vector<Node> out;
  if (isSeq())
  {
    for (YAML::const_iterator it = impl_->node.begin(); it != impl_->node.end(); ++it)
    {
      out.push_back(Node(std::make_unique<Impl>(Impl{ *it })));
    }
  }
  return out;
}

std::vector<std::string> Node::keys() const
{
  std::vector<std::string> out;
  if (isMap())
  {
    for (YAML::const_iterator it = impl_->node.begin(); it != impl_->node.end(); ++it)
    {
      out.push_back(it->first.IsScalar() ? it->first.Scalar() : std::string("(not a name)"));
    }
  }
  return out;
}

std::size_t Node::size() const
{
  return isMap() || isSeq() ? impl_->node.size() : 0;
}

std::string Node::text() const
{
  return impl_ && impl_->node.IsScalar() ? impl_->node.Scalar() : std::string();
}

double Node::number() const
{
  double v = std::numeric_limits<double>::quiet_NaN();
  if (!impl_ || !Plain(impl_->node) || !ParseNumber(impl_->node.Scalar(), v))
  {
    return std::numeric_limits<double>::quiet_NaN();
  }
  return v;
}

int Node::line() const
{
  return impl_ && impl_->node.Mark().line >= 0 ? impl_->node.Mark().line + 1 : 0;
}

std::vector<double> Numbers(const Node& node, const std::string& key)
{
  std::vector<double> out;
  if (node.empty() || node.isNone())
  {
    throw ParseError("missing key '" + key + "'");
  }
  if (node.isNumber())
  {
    out.push_back(node.number());
  }
  else if (node.isSeq())
  {
    out.reserve(node.size());
    for (const Node& item : node.items())
    {
      if (!item.isNumber())
      {
        throw ParseError("'" + key + "' must contain only numbers");
      }
      out.push_back(item.number());
    }
  }
  else if (node.isMap() && !node["data"].empty())
  {
    // An OpenCV matrix: {rows, cols, dt, data}; rows x cols must be what data holds.
    const Node rows = node["rows"], cols = node["cols"], data = node["data"];
    if (!rows.isInt() || !cols.isInt() || !data.isSeq() || rows.number() < 1 || cols.number() < 1 ||
      rows.number() * cols.number() != static_cast<double>(data.size()))
    {
      throw ParseError("'" + key + "': the matrix's rows x cols must match its data");
    }
    out = Numbers(data, key);
  }
  else
  {
    throw ParseError("'" + key + "' must be a number, a sequence or a matrix");
  }
  for (double v : out)
  {
    if (!std::isfinite(v))
    {
      throw ParseError("'" + key + "' contains NaN or Inf");
    }
  }
  return out;
}

std::vector<double> Numbers(const Node& node, const std::string& key, size_t n)
{
  std::vector<double> v = Numbers(node, key);
  if (v.size() != n)
  {
    std::ostringstream msg;
    msg << "'" << key << "' must have " << n << " numbers, found " << v.size();
    throw ParseError(msg.str());
  }
  return v;
}

double Number(const Node& parent, const std::string& key, double fallback)
{
  const Node n = parent[key];
  if (n.empty() || n.isNone())
  {
    return fallback;
  }
  return Numbers(n, key, 1)[0];
}

double Number(const Node& parent, const std::string& key)
{
  return Numbers(parent[key], key, 1)[0];
}

std::string String(const Node& parent, const std::string& key, const std::string& fallback)
{
  const Node n = parent[key];
  if (n.empty() || n.isNone())
  {
    return fallback;
  }
  if (!n.isString())
  {
    throw ParseError("'" + key + "' must be a string");
  }
  return n.text();
}

bool Flag(const Node& parent, const std::string& key, bool fallback)
{
  const Node n = parent[key];
  if (n.empty() || n.isNone())
  {
    return fallback;
  }
  if (n.isBool())
  {
    std::string s = n.text();
    return s[0] == 't' || s[0] == 'T';
  }
  if (n.isNumber() && std::isfinite(n.number()))
  {
    return n.number() != 0.0;
  }
  throw ParseError("'" + key + "' must be true or false (or 1 or 0)");
}

namespace
{
// The deepest nesting of `text`: flow brackets ([ {) outside quotes and comments, plus the
// levels of block indentation (a stack of increasing indents, "- " items counting as one more).
int Nesting(const std::string& text)
{
  int deepest = 0;
  int brackets = 0;
  std::vector<std::size_t> indents;
  std::size_t pos = 0;
  while (pos < text.size())
  {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos)
    {
      end = text.size();
    }
    // Block indentation of the line (blank and comment lines do not count).
    std::size_t indent = pos;
    while (indent < end && (text[indent] == ' ' || text[indent] == '-'))
    {
      ++indent;
    }
    if (indent < end && text[indent] != '#' && text[indent] != '\r' && brackets == 0)
    {
      const std::size_t column = indent - pos;
      while (!indents.empty() && indents.back() > column)
      {
        indents.pop_back();
      }
      if (indents.empty() || indents.back() < column)
      {
        indents.push_back(column);
      }
    }
    // "- - - x" nests sequences on one line.
    int dashes = 0;
    for (std::size_t k = pos; k < indent; ++k)
    {
      dashes += text[k] == '-';
    }
    char quote = 0;
    for (std::size_t k = pos; k < end; ++k)
    {
      const char c = text[k];
      if (quote)
      {
        quote = c == quote ? 0 : quote;
      }
      else if (c == '"' || c == '\'')
      {
        quote = c;
      }
      else if (c == '#')
      {
        break;
      }
      else if (c == '[' || c == '{')
      {
        deepest = std::max(deepest, static_cast<int>(indents.size()) + dashes + ++brackets);
      }
      else if ((c == ']' || c == '}') && brackets > 0)
      {
        --brackets;
      }
    }
    deepest = std::max(deepest, static_cast<int>(indents.size()) + dashes);
    pos = end + 1;
  }
  return deepest;
}

// Strips what only OpenCV's reader accepts: the `%YAML:1.0` directive (made a comment, so that
// line numbers stay).
void OpenCVCompatible(std::string& text)
{
  if (text.compare(0, 6, "%YAML:") == 0)
  {
    text[0] = '#';
  }
}

// Walks the parsed tree once: a key given twice in a map is an error (yaml-cpp keeps both, and
// which one a reader sees is an accident), and so is a tree that aliases expand past
// kMaxValues values (a few lines of anchors can name billions).
void CheckTree(const YAML::Node& node, std::size_t& values, const std::string& what)
{
  if (++values > kMaxValues)
  {
    throw ParseError(
      what + ": more than " + std::to_string(kMaxValues) + " values once its aliases are expanded");
  }
  if (node.IsSequence())
  {
    for (YAML::const_iterator it = node.begin(); it != node.end(); ++it)
    {
      CheckTree(*it, values, what);
    }
  }
  else if (node.IsMap())
  {
    std::unordered_set<std::string> keys;
    for (YAML::const_iterator it = node.begin(); it != node.end(); ++it)
    {
      if (it->first.IsScalar() && !keys.insert(it->first.Scalar()).second)
      {
        throw ParseError(what + ": line " + std::to_string(it->first.Mark().line + 1) + ": key '" +
          it->first.Scalar() + "' is given twice");
      }
      CheckTree(it->first, values, what);
      CheckTree(it->second, values, what);
    }
  }
}
} // namespace

void CheckKeys(const Node& node, std::initializer_list<const char*> known)
{
  CheckKeys(node, std::vector<std::string>(known.begin(), known.end()));
}

void CheckKeys(const Node& node, const std::vector<std::string>& known)
{
  if (!node.isMap())
  {
    return;
  }
  for (const std::string& key : node.keys())
  {
    if (std::find(known.begin(), known.end(), key) != known.end())
    {
      continue;
    }
    std::string message = "unknown key '" + key + "'";
    // Close: at most a third of the key's letters (two at least) edited.
    const std::size_t limit = std::max<std::size_t>(2, key.size() / 3);
    const std::string* nearest =
      Nearest(key, known, [limit](std::size_t d, const std::string&) { return d <= limit; });
    if (nearest)
    {
      message += " (did you mean '" + *nearest + "'?)";
    }
    else
    {
      message += " (known keys:";
      for (const std::string& k : known)
      {
        message += " " + k;
      }
      message += ")";
    }
    throw ParseError(message);
  }
}

bool Parse(
  const std::string& source, bool isText, const std::string& what, Node& root, std::string& error)
{
  std::string text;
  if (isText)
  {
    text = source;
  }
  else
  {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(source, ec))
    {
      error = what + ": cannot open the file (" +
        (ec ? ec.message() : std::string("not a regular file")) + ")";
      return false;
    }
    std::ifstream in(source, std::ios::binary);
    if (!in)
    {
      error = what + ": cannot open the file";
      return false;
    }
    try
    {
      text.resize(kMaxTextBytes + 1);
      in.read(&text[0], static_cast<std::streamsize>(text.size()));
      text.resize(static_cast<std::size_t>(std::max<std::streamsize>(0, in.gcount())));
    }
    catch (const std::exception& e)
    {
      error = what + ": cannot read the file (" + e.what() + ")";
      return false;
    }
  }
  if (text.size() > kMaxTextBytes)
  {
    error = what + ": larger than the limit of " + std::to_string(kMaxTextBytes) + " bytes";
    return false;
  }
  const int depth = Nesting(text);
  if (depth > kMaxNesting)
  {
    error = what + ": nested " + std::to_string(depth) + " levels deep (at most " +
      std::to_string(kMaxNesting) + ")";
    return false;
  }
  if (text.find('\0') != std::string::npos)
  {
    error = what + ": not a text file (it contains a NUL byte)";
    return false;
  }
  OpenCVCompatible(text);
  try
  {
    const YAML::Node parsed = YAML::Load(text);
    std::size_t values = 0;
    CheckTree(parsed, values, what);
    root = Node(std::make_unique<Node::Impl>(Node::Impl{ parsed }));
  }
  catch (const ParseError& e)
  {
    error = e.what();
    return false;
  }
  catch (const YAML::Exception& e)
  {
    std::ostringstream msg;
    msg << what << ": not valid YAML or JSON";
    if (!e.mark.is_null())
    {
      msg << " (line " << e.mark.line + 1 << ", column " << e.mark.column + 1 << ": " << e.msg
          << ")";
    }
    else
    {
      msg << " (" << e.msg << ")";
    }
    error = msg.str();
    return false;
  }
  catch (const std::exception& e)
  {
    error = what + ": not valid YAML or JSON (" + e.what() + ")";
    return false;
  }
  return true;
}
} // namespace fs
} // namespace catar
