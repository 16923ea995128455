// Pass/fail bookkeeping shared by the C++ test programs. ctest reads only the
// exit code, so a program counts its failed checks and returns finish(); the
// lines printed are for the reader of a failed run: which check, with what
// numbers. On several processes only the first prints (each rank still counts
// its own failures, and mpirun fails if any rank does).
#pragma once

#include <iostream>
#include <string>

namespace anvil::testing
{
  class Checks
  {
  public:
    enum class Print
    {
      every_check,
      failures_only // for programs that check thousands of entries in loops
    };

    explicit Checks(const Print print = Print::every_check)
      : print(print)
    {}

    /// Only the process that prints (the first) writes lines; call once from main().
    void print_on_this_process(const bool yes) { printing = yes; }

    void operator()(const bool ok, const std::string &what)
    {
      failures += ok ? 0 : 1;
      if (printing && (!ok || print == Print::every_check))
        std::cout << (ok ? "  PASS " : "  FAIL ") << what << std::endl;
    }

    int n_failures() const { return failures; }

    /// The closing line and the exit code: 0 when every check passed.
    int finish() const
    {
      if (printing)
        std::cout << (failures == 0 ? "\nall checks passed\n" : "\nFAILED checks: " + std::to_string(failures) + "\n")
                  << std::flush;
      return failures == 0 ? 0 : 1;
    }

  private:
    Print print;
    bool  printing = true;
    int   failures = 0;
  };
} // namespace anvil::testing
