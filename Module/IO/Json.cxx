#include "Json.h"

#include <cmath>
#include <cstdio>

namespace catar
{
std::string JsonString(const std::string& text)
{
  std::string out = "\"";
  for (const char c : text)
  {
    if (c == '"' || c == '\\')
    {
      out += '\\';
      out += c;
    }
    else if (static_cast<unsigned char>(c) < 0x20)
    {
      char escaped[8];
      std::snprintf(escaped, sizeof(escaped), "\\u%04x", c);
      out += escaped;
    }
    else
    {
      out += c;
    }
  }
  return out + "\"";
}

std::string JsonNumber(double value, int digits)
{
  if (!std::isfinite(value))
  {
    return "null";
  }
  char text[40];
  std::snprintf(text, sizeof(text), "%.*g", digits, value);
  return text;
}
} // namespace catar
