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

  // A process started without a launcher (no mpirun/srun variables) is a
  // one-rank run. Open MPI would open every network transport for it, and the
  // Omni-Path one (libpsm2) calibrates a clock with ~800 sleeps of 125 us when
  // it loads: ~0.2 s of a 0.6 s start-up (issue 15, measured with strace
  // and timings). A single rank needs no network: pml ob1 (shared
  // memory and self) only. Not ess_singleton_isolated, which would save the
  // daemon's ~0.09 s too: isolated singletons all get the same session
  // directory (jf.0/1), and one run's clean-up removed it under another's
  // MPI-IO file (p4est's checkpoint: "sharedfp_sm ... unable to open file"),
  // a crash seen with tests running side by side. Never overrides what the
  // user set, never touches launched runs.
  void lean_singleton_mpi()
  {
    for (const char *launched : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"})
      if (std::getenv(launched) != nullptr)
        return;
    setenv("OMPI_MCA_pml", "ob1", 0);
  }
} // namespace

int main(int argc, char **argv)
{
  if (wants_study(argc, argv))
    return run_study(argc, argv);
  lean_singleton_mpi();
  return anvil::run_anvil(argc, argv);
}
