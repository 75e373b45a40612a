// The benchmarks' tables: numbers formatted for a row, and a table written as CSV.
#ifndef catarBenchmarkTable_h
#define catarBenchmarkTable_h

#include "Csv.h" // catar::CsvField

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

/// v with a printf format ("%.2f"), or "inf", "-inf", "nan".
inline std::string Number(double v, const char* format)
{
  if (std::isinf(v))
  {
    return v > 0 ? "inf" : "-inf";
  }
  if (std::isnan(v))
  {
    return "nan";
  }
  char buffer[64];
  std::snprintf(buffer, sizeof(buffer), format, v);
  return buffer;
}

/// Writes a header of `columns` and one line per row (fields quoted where CSV needs it); prints
/// "wrote FILE". Throws when the file cannot be written.
inline void WriteCsvTable(const std::string& file, const std::vector<std::string>& columns,
  const std::vector<std::vector<std::string>>& rows)
{
  std::ofstream out(file);
  for (std::size_t k = 0; k < columns.size(); ++k)
  {
    out << (k ? "," : "") << columns[k];
  }
  out << "\n";
  for (const std::vector<std::string>& fields : rows)
  {
    for (std::size_t k = 0; k < fields.size(); ++k)
    {
      out << (k ? "," : "") << catar::CsvField(fields[k]);
    }
    out << "\n";
  }
  out.close();
  if (!out)
  {
    throw std::runtime_error("cannot write " + file);
  }
  std::printf("wrote %s\n", file.c_str());
}

#endif
