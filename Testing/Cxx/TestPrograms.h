// Tests that run one of the project's command-line programs and read what it printed.
#ifndef catarTestPrograms_h
#define catarTestPrograms_h

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <string>

namespace catar_test
{
struct ProgramRun
{
  int status = -1;    ///< exit status; -1 when it did not exit (a signal) or could not start
  std::string output; ///< standard output and standard error
};

/// Runs `program` (a path, quoted here) with `arguments` (already quoted as the shell needs).
inline ProgramRun RunProgram(const std::string& program, const std::string& arguments)
{
  ProgramRun run;
  const std::string command = "'" + program + "' " + arguments + " 2>&1";
  FILE* pipe = popen(command.c_str(), "r");
  if (!pipe)
  {
    return run;
  }
  std::array<char, 4096> buffer;
  std::size_t n = 0;
  while ((n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0)
  {
    run.output.append(buffer.data(), n);
  }
  const int status = pclose(pipe);
  run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}
} // namespace catar_test

#endif
