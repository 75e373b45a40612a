// The command-line programs' shared parsing (CLI11): --help and usage errors the same way in each.
#ifndef catarCommandLine_h
#define catarCommandLine_h

#include <CLI/CLI.hpp>

#include <cstdio>
#include <string>

namespace catar
{
/// Parses argv into app, which gets a --version flag ("PROGRAM VERSION"). Returns -1 to go on;
/// otherwise the exit status to return: 0 after printing the help (-h, --help) or the version,
/// 2 after a usage error, which is printed once on standard error as
/// "PROGRAM: what (run with --help for usage)". Options take their value as --option value or
/// --option=value. Nothing is coloured.
inline int ParseCommandLine(CLI::App& app, const char* program, int argc, char** argv)
{
  app.set_version_flag("--version", std::string(program) + " " + CATAR_VERSION);
  try
  {
    app.parse(argc, argv);
  }
  catch (const CLI::CallForHelp&)
  {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  }
  catch (const CLI::CallForVersion& e)
  {
    std::printf("%s\n", e.what());
    return 0;
  }
  catch (const CLI::ParseError& e)
  {
    std::fprintf(stderr, "%s: %s (run with --help for usage)\n", program, e.what());
    return 2;
  }
  return -1;
}
} // namespace catar

#endif
