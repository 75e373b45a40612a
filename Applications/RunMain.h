// The command-line programs' main: the program's body, with no exception left to abort it.
#ifndef catarRunMain_h
#define catarRunMain_h

#include <cstdio>
#include <exception>
#include <new>

namespace catar
{
/// Runs a program's body, run(argc, argv), and returns its exit status; an exception that escapes
/// it is printed once on standard error as "PROGRAM: what" (std::bad_alloc as "out of memory")
/// and ends the program with status 1, instead of std::terminate's abort.
template<typename Run>
int RunMain(const char* program, Run run, int argc, char** argv) noexcept
{
  try
  {
    return run(argc, argv);
  }
  catch (const std::bad_alloc&)
  {
    std::fprintf(stderr, "%s: out of memory\n", program);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "%s: %s\n", program, e.what());
  }
  catch (...)
  {
    std::fprintf(stderr, "%s: an unknown error\n", program);
  }
  return 1;
}
} // namespace catar

#endif
