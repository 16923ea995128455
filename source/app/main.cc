// anvil: the command-line program. Everything lives in libanvil.
//
// `anvil --study FILE [...]` hands over to the study tool the build writes
// next to this executable (build/anvil-study, from contrib/study; doc/study.md):
// a study runs many anvil processes, so it drives them from outside, and it is
// started before MPI is, so that this process is not an MPI rank.
#include <anvil/simulator/simulator.h>

#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

namespace
{
  std::string executable_directory()
  {
    char          buffer[PATH_MAX];
    const ssize_t n = readlink("/proc/self/exe", buffer, sizeof(buffer) - 1);
    if (n <= 0)
      return ".";
    const std::string path(buffer, n);
    return path.substr(0, path.rfind('/'));
  }

  bool wants_study(int argc, char **argv)
  {
    for (int i = 1; i < argc; ++i)
      if (std::strcmp(argv[i], "--study") == 0 || std::strncmp(argv[i], "--study=", 8) == 0)
        return true;
    return false;
  }

  // Replaces this process by anvil-study with the other arguments; the runs
  // use this very executable.
  int run_study(int argc, char **argv)
  {
    const std::string directory = executable_directory();
    const std::string tool      = directory + "/anvil-study";
    const std::string self      = directory + "/anvil";
    setenv("ANVIL_EXECUTABLE", self.c_str(), 1);
    std::vector<std::string> args{tool};
    for (int i = 1; i < argc; ++i)
      if (std::strncmp(argv[i], "--study=", 8) == 0)
        args.emplace_back(argv[i] + 8);
      else if (std::strcmp(argv[i], "--study") != 0)
        args.emplace_back(argv[i]);
    std::vector<char *> c_args;
    for (auto &a : args)
      c_args.push_back(a.data());
    c_args.push_back(nullptr);
    execv(tool.c_str(), c_args.data());
    std::cerr << "anvil: error: --study: cannot run the study tool " << tool << " ("
              << std::strerror(errno) << "); it is written by cmake into the build directory"
              << std::endl;
    return 2;
  }
} // namespace

int main(int argc, char **argv)
{
  if (wants_study(argc, argv))
    return run_study(argc, argv);
  return anvil::run_anvil(argc, argv);
}
