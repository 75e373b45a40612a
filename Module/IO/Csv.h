// CSV output shared by the tools and benchmarks that write tables.
#ifndef catarCsv_h
#define catarCsv_h

#include <string>

namespace catar
{
/// A CSV field (RFC 4180): s as it is, or in double quotes with its quotes doubled when it holds
/// a comma, a double quote or a newline.
std::string CsvField(const std::string& s);
} // namespace catar

#endif
