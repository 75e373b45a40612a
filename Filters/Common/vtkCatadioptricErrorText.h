/**
 * @file   vtkCatadioptricErrorText.h
 * @brief  a VTK error or warning message without VTK's decoration
 *
 * vtkErrorMacro's text is "ERROR: In FILE, line N\nCLASS (0x...): what\n\n"; the programs print
 * and the scene renderer collects only "what". C++ only (not wrapped).
 */
#ifndef vtkCatadioptricErrorText_h
#define vtkCatadioptricErrorText_h

#include <string>

namespace vtkCatadioptricErrorText
{
/// The message of a VTK error or warning text: the "ERROR: In FILE, line N" line, the
/// "CLASS (0x...): " prefix and trailing white space removed; other text as it is.
inline std::string Short(std::string text)
{
  if (text.rfind("ERROR: In ", 0) == 0 || text.rfind("Warning: In ", 0) == 0)
  {
    const std::size_t eol = text.find('\n');
    text = eol == std::string::npos ? std::string() : text.substr(eol + 1);
  }
  const std::size_t open = text.find(" (0x");
  const std::size_t close = text.find("): ");
  if (open != std::string::npos && close != std::string::npos && open < close &&
    text.find('\n') > close)
  {
    text = text.substr(close + 3);
  }
  while (!text.empty() &&
    (text.back() == '\n' || text.back() == ' ' || text.back() == '\t' || text.back() == '\r'))
  {
    text.pop_back();
  }
  return text;
}
} // namespace vtkCatadioptricErrorText

#endif
