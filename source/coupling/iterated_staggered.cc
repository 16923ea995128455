#include <deal.II/base/utilities.h>

#include <anvil/coupling/interface.h>

#include <algorithm>

namespace anvil
{
  using namespace dealii;

  /**
   * The two phases repeated within the step — the mechanics again at the
   * end-of-step temperature T^(k), the heat again with its sources — until
   * the temperature stops changing: the fixed point both splits approximate
   * at first order (doc/thermal.md), the accuracy reference for them.
   */
  template <int dim>
  class IteratedStaggered : public CouplingScheme<dim>
  {
  public:
    static void declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Staggered tolerance", "0", Patterns::Double(0),
                        "iterated staggered: largest change of a nodal temperature between two "
                        "iterations at which the step is converged, K. 0: automatic, ten times "
                        "what the heat integration resolves (Heat/Time integration/Relative "
                        "tolerance x max T + Absolute tolerance); a smaller value is raised to "
                        "that (the iteration cannot converge below the integrator's own error) "
                        "and a note says so.");
      prm.declare_entry("Staggered iterations", "30", Patterns::Integer(1),
                        "iterated staggered: iterations before the step is cut back.");
    }

    bool needs_mechanics() const override { return true; }
    bool needs_heat_equation() const override { return true; }

    void parse_parameters(ParameterHandler &prm, const Scene &) override
    {
      prm.enter_subsection("Physics");
      tolerance_asked = prm.get_double("Staggered tolerance");
      max_iterations  = prm.get_integer("Staggered iterations");
      prm.leave_subsection();
    }

    void initialize(CoupledProblem<dim> &p) override
    {
      CouplingScheme<dim>::initialize(p);
      p.connect_fields(false);
    }

    StepReport<dim> advance(const double t_old, const double t_new) override
    {
      auto           &problem = *this->problem;
      StepReport<dim> r;
      auto            fail = [&](const std::string &why) {
        problem.revert();
        return r.fail(why);
      };
      if (!problem.solve_mechanics(t_old, t_new, false, r))
        return fail(r.mechanics().failure);
      if (!problem.solve_heat(t_old, t_new, r))
        return fail("heat: " + r.thermal.failure);

      auto                         &heat = *problem.heat();
      TrilinosWrappers::MPI::Vector previous(heat.temperature());
      const double                  tolerance = effective_tolerance(previous.linfty_norm());
      double                        last_change = 0;
      unsigned int                  growing     = 0;
      for (unsigned int k = 1;; ++k)
        {
          if (k > max_iterations)
            return fail("the staggered iteration did not reach " + Utilities::to_string(tolerance) +
                        " K in " + Utilities::to_string(max_iterations) +
                        " iterations (last change " + Utilities::to_string(last_change) +
                        " K, contraction " + Utilities::to_string(r.contraction) + ")");
          problem.point_temperatures_from_heat_field(); // T^(k) at the points
          heat.revert();
          if (!problem.solve_mechanics(t_old, t_new, /*again*/ true, r))
            return fail(r.mechanics().failure);
          if (!problem.solve_heat(t_old, t_new, r))
            return fail("heat: " + r.thermal.failure);
          TrilinosWrappers::MPI::Vector change(heat.temperature());
          change -= previous;
          const double dT = change.linfty_norm();
          previous        = heat.temperature();
          if (k > 1 && last_change > 0)
            r.contraction = dT / last_change;
          last_change            = dT;
          r.staggered_iterations = k;
          r.staggered_change     = dT;
          if (dT <= tolerance)
            return r;
          // Two growing changes in a row, well above the tolerance (below it the
          // changes are the thermal integrator's noise): the iteration diverges.
          growing = k > 1 && r.contraction >= 1 && dT > 10 * tolerance ? growing + 1 : 0;
          if (growing >= 2)
            return fail("the staggered iteration diverges (contraction " +
                        Utilities::to_string(r.contraction, 3) +
                        "): the coupling is too strong for it at this time step; the splits, "
                        "or a smaller step, may still work");
        }
    }

  private:
    // Below what the heat integration resolves the changes are its noise.
    double effective_tolerance(const double max_temperature)
    {
      const auto  &hp         = this->problem->heat_parameters();
      const double resolution = hp.relative_tolerance * max_temperature + hp.absolute_tolerance;
      const double tolerance  = std::max(tolerance_asked, 10 * resolution);
      if (tolerance_asked > 0 && tolerance > tolerance_asked && !noted)
        {
          noted = true;
          this->problem->log() << "  note: Physics/Staggered tolerance = " << tolerance_asked
                  << " K is below what the heat integration resolves; using " << tolerance
                  << " K (tighten Heat/Time integration tolerances to go lower)" << std::endl;
        }
      return tolerance;
    }

    double       tolerance_asked = 0;
    unsigned int max_iterations  = 30;
    bool         noted           = false;
  };

  ANVIL_REGISTER_COUPLING_SCHEME(
    IteratedStaggered, "iterated staggered",
    "the two phases repeated within the step, the mechanics at the end-of-step temperature, "
    "until the temperature changes by less than Staggered tolerance (the accuracy reference "
    "for the splits).")
} // namespace anvil
