// The benchmarks' VTK messages: errors counted, so that a failing stage ends the run with a
// message (Check), and warnings (the bunny's repairs, repeated for every remesh) printed once
// each, or not at all.
#ifndef catarBenchmarkErrors_h
#define catarBenchmarkErrors_h

#include "vtkOutputWindow.h"

#include <cstdio>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

class CountingOutputWindow : public vtkOutputWindow
{
public:
  static CountingOutputWindow* New()
  {
    auto* window = new CountingOutputWindow;
    window->InitializeObjectBase();
    return window;
  }
  vtkTypeMacro(CountingOutputWindow, vtkOutputWindow);
  void DisplayErrorText(const char* text) override
  {
    ++this->Errors;
    this->ErrorTexts.emplace_back(text ? text : "");
    std::fprintf(stderr, "%s", this->ErrorTexts.back().c_str());
  }
  void DisplayWarningText(const char* text) override { this->Warn(text); }
  void DisplayGenericWarningText(const char* text) override { this->Warn(text); }
  void DisplayDebugText(const char*) override {}
  int Errors = 0;
  std::vector<std::string> ErrorTexts;
  bool PrintWarnings = true; ///< each distinct warning once; false: none

private:
  void Warn(const char* text)
  {
    std::string t = text ? text : "";
    const std::size_t message = t.find("): "); // after "vtkClass (0x...)"
    if (message != std::string::npos)
    {
      t = t.substr(message + 3);
    }
    if (this->PrintWarnings && this->Seen.insert(t).second)
    {
      std::fprintf(stderr, "warning: %s", t.c_str());
    }
  }
  std::set<std::string> Seen;
};

/// The window the benchmark installed (vtkOutputWindow::SetInstance).
inline CountingOutputWindow* Output = nullptr;

/// Throws when a VTK error was reported since `errorsBefore`, or when `ok` is false.
inline void Check(const std::string& stage, int errorsBefore, bool ok = true)
{
  if (Output->Errors != errorsBefore)
  {
    throw std::runtime_error(stage + " failed: " + Output->ErrorTexts[errorsBefore]);
  }
  if (!ok)
  {
    throw std::runtime_error(stage + " failed");
  }
}

#endif
