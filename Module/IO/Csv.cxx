#include "Csv.h"

namespace catar
{
std::string CsvField(const std::string& s)
{
  if (s.find_first_of(",\"\n") == std::string::npos)
  {
    return s;
  }
  std::string quoted = "\"";
  for (char c : s)
  {
    quoted += c;
    if (c == '"')
    {
      quoted += '"';
    }
  }
  return quoted + "\"";
}
} // namespace catar
