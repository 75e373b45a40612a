// The command-line programs' shared parsing (CLI11): --help, --version, --threads and usage errors
// the same way in each, with a suggestion for a mistyped option.
#ifndef catarCommandLine_h
#define catarCommandLine_h

#include "EditDistance.h"
#include "Threads.h"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

namespace catar
{
namespace command_line
{
/// The option of app closest to `given` ("--tolerence", "--tolerence=3"), or "" when none is
/// close: at most 2 edits, and fewer than a third of the name's letters.
inline std::string ClosestOption(const CLI::App& app, std::string given)
{
  given = given.substr(0, given.find('='));
  std::vector<std::string> names;
  for (const CLI::Option* option : app.get_options())
  {
    for (const std::string& name : option->get_lnames())
    {
      names.push_back("--" + name);
    }
    for (const std::string& name : option->get_snames())
    {
      names.push_back("-" + name);
    }
  }
  const std::string* nearest = Nearest(given, names,
    [](std::size_t d, const std::string& name) { return d < 3 && 3 * d < name.size(); });
  return nearest ? *nearest : std::string();
}
} // namespace command_line

/// Adds --threads N (1 to 1024): the number of threads of the parallel loops (the default: one a
/// core). ParseCommandLine adds it and applies it.
inline CLI::Option* AddThreadsOption(CLI::App& app, int& threads)
{
  return app
    .add_option("--threads", threads, "threads of the parallel loops (default: one a core)")
    ->type_name("N")
    ->check(CLI::Range(1, 1024));
}

/// Parses argv into app, which gets a --version flag ("PROGRAM VERSION"), --threads N (applied
/// here with UseThreads; its value, 0 when not given, also goes to *threadsOut) and a footer
/// line that says where the documentation is installed. Returns -1 to go on;
/// otherwise the exit status to return: 0 after printing the help (-h, --help) or the version,
/// 2 after a usage error, which is printed once on standard error as
/// "PROGRAM: what (run with --help for usage)", with "did you mean --x?" when an unknown option is
/// close to one of app's. Options take their value as --option value or --option=value. Nothing
/// is coloured.
inline int ParseCommandLine(
  CLI::App& app, const char* program, int argc, char** argv, int* threadsOut = nullptr)
{
  app.set_version_flag("--version", std::string(program) + " " + CATAR_VERSION);
  int threads = 0;
  AddThreadsOption(app, threads);
  // Where the documents named in the help are once installed, and the manual page.
  const std::string footer = app.get_footer();
  app.footer(footer + (footer.empty() ? "" : "\n\n") +
    "Documentation: the source tree's Documentation/NAME.md is installed as " CATAR_DOC_DIR
    "/NAME.md; the manual page: man " +
    program + ".");
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
    std::string suggestion;
    for (const std::string& extra : app.remaining())
    {
      if (extra.size() > 1 && extra[0] == '-')
      {
        const std::string close = command_line::ClosestOption(app, extra);
        if (!close.empty())
        {
          suggestion = "; did you mean " + close + "?";
          break;
        }
      }
    }
    std::fprintf(
      stderr, "%s: %s%s (run with --help for usage)\n", program, e.what(), suggestion.c_str());
    return 2;
  }
  UseThreads(threads);
  if (threadsOut)
  {
    *threadsOut = threads;
  }
  return -1;
}
} // namespace catar

#endif
