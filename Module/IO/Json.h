// CatadioptricAR Core: the pieces of JSON text the programs and logs write.
#ifndef catarJson_h
#define catarJson_h

#include <string>

namespace catar
{
/// A JSON string: `text` in double quotes, its quotes and backslashes escaped and its control
/// characters as \u00XX.
std::string JsonString(const std::string& text);

/// A JSON number with `digits` significant digits; null when not finite (JSON has no NaN).
std::string JsonNumber(double value, int digits = 17);
} // namespace catar

#endif
