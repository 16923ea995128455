#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace anvil
{
  /**
   * Times at which a scene's loading changes character (the end of a ramp,
   * the start of an unloading): Time/Breakpoints. The time loop lands a step
   * exactly on each and restarts from a small step after it. Without them a
   * step grown during a smooth phase (a hold: hundreds of seconds) crosses
   * into the next phase, Newton fails there and the step is halved from its
   * large size, one failed attempt of up to Maximum iterations per halving.
   * Kept apart from the time loop: a pure function of t, so a restart needs
   * no state of it.
   */
  class StepBreakpoints
  {
  public:
    StepBreakpoints() = default;
    /// @p times strictly increasing (the caller checks and names the entry).
    explicit StepBreakpoints(std::vector<double> times)
      : times(std::move(times))
    {}

    /// The step to take from @p t: @p dt, shortened so that it ends on the
    /// first breakpoint after t (beyond t + eps) if it would cross it.
    double clip(const double t, const double dt, const double eps) const
    {
      const auto next = std::upper_bound(times.begin(), times.end(), t + eps);
      return next != times.end() && t + dt > *next - eps ? *next - t : dt;
    }

    /// Whether the step just taken ended on a breakpoint (within eps).
    bool lands_on(const double t, const double eps) const
    {
      return std::any_of(times.begin(), times.end(),
                         [&](const double b) { return std::abs(b - t) <= eps; });
    }

    bool empty() const { return times.empty(); }

  private:
    std::vector<double> times;
  };
} // namespace anvil
