#pragma once

// What both time integrators of the heat half-step share (arkode_integrator.cc,
// dirk_linear.cc): callbacks' exceptions as return codes, and the first step
// of a call cut from the last call's proposal.

#include <deal.II/lac/solver_control.h>

#include <algorithm>
#include <cmath>
#include <exception>
#include <string>

namespace anvil
{
  namespace thermal
  {
    /// Run @p f, turning exceptions into return codes (0 ok, > 0 recoverable,
    /// < 0 fatal): they must not unwind through SUNDIALS' C frames, and the
    /// own loop treats them alike.
    template <typename F>
    int guarded(std::string &message, F &&f)
    {
      try
        {
          return f();
        }
      catch (const dealii::SolverControl::NoConvergence &e)
        {
          message = "a linear solver did not converge (" + std::to_string(e.last_step) +
                    " iterations, residual " + std::to_string(e.last_residual) + ")";
          return 1;
        }
      catch (const std::exception &e)
        {
          message = e.what();
          return -1;
        }
      catch (...)
        {
          message = "unknown exception in a time integrator's callback";
          return -1;
        }
    }

    /// The proposal carries the controller's safety factor (0.96) and error
    /// bias (1.5): a step of up to 1.25 times it passed the error test on
    /// two_blocks at every step (1.0: 13 of 79 steps in two, 1.15: 3,
    /// 1.25–1.5: 2, the contact's start).
    constexpr double proposal_stretch = 1.25;

    /// @p span cut into the fewest equal steps that are at most
    /// proposal_stretch times @p proposal; 0 without a proposal. ARKode clips
    /// a step at the stop time and never stretches one: started from the
    /// proposal h just below the span (two_blocks: 4.5–5.1e-5 s for 5e-5 s)
    /// it took h and then the remainder, two steps where one passes.
    inline double first_step(const double span, const double proposal)
    {
      if (!(proposal > 0))
        return 0.;
      const double n = std::max(1., std::ceil(span / (proposal_stretch * proposal) - 1e-9));
      return span / n;
    }
  } // namespace thermal
} // namespace anvil
