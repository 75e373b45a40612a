// What a VTK-based command-line program prints of VTK's errors and warnings: each once, as one
// plain line "PROGRAM: message" (warnings "PROGRAM: warning: message"), without VTK's log
// decoration (time, thread, file and line, colours) and without the executive's "returned failure
// for request" dumps. The program's own report of the same error (its LastError) is not printed a
// second time (PrintError).
#ifndef catarProgramOutput_h
#define catarProgramOutput_h

#include "vtkCatadioptricErrorText.h"
#include "vtkLogger.h"
#include "vtkObjectFactory.h"
#include "vtkOutputWindow.h"

#include <cstdio>
#include <string>

namespace catar
{
class ProgramOutputWindow : public vtkOutputWindow
{
public:
  static ProgramOutputWindow* New();
  vtkTypeMacro(ProgramOutputWindow, vtkOutputWindow);

  /// Installs it for `program`: VTK's errors and warnings go through it; the log's own copy on
  /// standard error is turned off.
  static void Install(const char* program)
  {
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
    ProgramOutputWindow* window = ProgramOutputWindow::New();
    window->Program = program;
    vtkOutputWindow::SetInstance(window);
    window->Delete();
  }

  /// The message of a VTK error or warning text: "ERROR: In FILE, line N\nCLASS (0x..): message"
  /// without its first line and its object prefix, trailing blank lines dropped.
  static std::string Message(const std::string& text)
  {
    return vtkCatadioptricErrorText::Short(text);
  }

  /// The last error line printed (without the program's name).
  static std::string& LastError()
  {
    static std::string last;
    return last;
  }

  void DisplayErrorText(const char* text) override
  {
    const std::string m = Message(text ? text : "");
    if (m.empty() || m.find("returned failure for request") != std::string::npos ||
      m == LastError())
    {
      return;
    }
    LastError() = m;
    std::fprintf(stderr, "%s: %s\n", this->Program.c_str(), m.c_str());
    std::fflush(stderr);
  }
  void DisplayWarningText(const char* text) override
  {
    const std::string m = Message(text ? text : "");
    if (!m.empty())
    {
      std::fprintf(stderr, "%s: warning: %s\n", this->Program.c_str(), m.c_str());
      std::fflush(stderr);
    }
  }
  void DisplayGenericWarningText(const char* text) override { this->DisplayWarningText(text); }
  void DisplayText(const char* text) override
  {
    if (text && *text)
    {
      std::fprintf(stderr, "%s\n", Message(text).c_str());
    }
  }
  void DisplayDebugText(const char*) override {}

private:
  std::string Program = "program";
};

inline ProgramOutputWindow* ProgramOutputWindow::New()
{
  VTK_STANDARD_NEW_BODY(ProgramOutputWindow);
}

/// Prints "PROGRAM: error" on standard error, unless the output window has just printed it (the
/// program's own report of a VTK error that was already shown).
inline void PrintError(const char* program, const std::string& error)
{
  const std::string m = ProgramOutputWindow::Message(error);
  if (m == ProgramOutputWindow::LastError())
  {
    return;
  }
  std::fprintf(stderr, "%s: %s\n", program, m.c_str());
}
} // namespace catar

#endif
