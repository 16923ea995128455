// The step loop's clock (simulator.cc): summary.json's step_loop_wall_time
// and step_loop_cpu_time, contrib/bench/perf.py's Newton ratio.
#pragma once

#include <mpi.h>

#include <sys/resource.h>

namespace anvil
{
  namespace step_clock_detail
  {
    /// Wall and CPU seconds (user + system, all threads) of a stretch of the
    /// step loop, added to @p wall and @p cpu when it stops. Not a TimerOutput
    /// section: deal.II's synchronises the processes at every start and stop,
    /// and a process that throws alone (ANVIL_RANK_FAULT) would then call a
    /// collective the others do not.
    class StepClock
    {
    public:
      StepClock(double &wall, double &cpu)
        : wall(wall)
        , cpu(cpu)
        , wall_start(MPI_Wtime())
        , cpu_start(cpu_seconds())
      {}
      ~StepClock() { stop(); }
      void stop()
      {
        if (!running)
          return;
        running = false;
        wall += MPI_Wtime() - wall_start;
        cpu += cpu_seconds() - cpu_start;
      }

    private:
      static double cpu_seconds()
      {
        rusage usage;
        getrusage(RUSAGE_SELF, &usage);
        return usage.ru_utime.tv_sec + usage.ru_stime.tv_sec +
               1e-6 * (usage.ru_utime.tv_usec + usage.ru_stime.tv_usec);
      }
      double &wall, &cpu;
      double  wall_start, cpu_start;
      bool    running = true;
    };
  } // namespace step_clock_detail
} // namespace anvil
