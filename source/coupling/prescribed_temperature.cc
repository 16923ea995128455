#include <deal.II/base/function_parser.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <anvil/core/expression.h>
#include <anvil/core/first_message.h>
#include <anvil/core/scene.h>
#include <anvil/coupling/interface.h>

#include <sstream>

namespace anvil
{
  using namespace dealii;

  /**
   * The temperature is given, not solved: T(X, t) from an expression of the
   * reference coordinates and time, evaluated at every quadrature point of
   * the mechanics at the end of each step, so thermal strains (eq. 19) and
   * temperature-dependent properties follow it within the step — no lag,
   * no heat equation, no ARKode. For scenes whose temperature history is
   * known (hot forming at a set temperature, a furnace ramp).
   */
  template <int dim>
  class PrescribedTemperature : public CouplingScheme<dim>
  {
  public:
    static void declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Prescribed temperature", "293", Patterns::Anything(),
                        "prescribed temperature: T(x, y[, z], t) in K, a muparser expression of "
                        "the reference coordinates (mm) and time (s), imposed at every "
                        "quadrature point at the end of each step; the mechanics starts from "
                        "T(x, 0) stress-free.");
    }

    bool needs_mechanics() const override { return true; }
    bool needs_heat_equation() const override { return false; }
    bool provides_temperature() const override { return true; }

    void parse_parameters(ParameterHandler &prm, const Scene &scene) override
    {
      text        = prm.get({"Physics"}, "Prescribed temperature");
      temperature = parse_expression<dim>(text, scene, "Physics/Prescribed temperature");
    }

    // The thermal strains and T-dependent laws need absolute temperatures:
    // T(x, t) at every node at t = 0 and at the end time (where a ramp ends).
    void check(const parallel::DistributedTriangulationBase<dim> &tria, const Scene &scene,
               const double end_time) const override
    {
      std::string problem;
      for (const double t : {0., end_time})
        {
          temperature->set_time(t);
          for (const auto &cell : tria.active_cell_iterators())
            if (cell->is_locally_owned())
              for (const unsigned int v : cell->vertex_indices())
                if (const double T = temperature->value(cell->vertex(v)); !(T > 0) && problem.empty())
                  {
                    std::ostringstream m;
                    m << "= '" << text << "' gives " << T << " K at a node (" << cell->vertex(v)
                      << ") at t = " << t << " s: expected an absolute temperature > 0 K";
                    problem = m.str();
                  }
        }
      temperature->set_time(0);
      const MPI_Comm comm = tria.get_communicator();
      throw_recorded_input_error(comm); // NaN or inf: named with where and when
      if (const std::string first = first_message(problem, comm); !first.empty())
        scene.fail("Physics/Prescribed temperature", first);
    }

    void initialize(CoupledProblem<dim> &p) override
    {
      CouplingScheme<dim>::initialize(p);
      p.connect_point_temperatures(false);
      evaluate(0);
      p.mechanics()->set_initial_point_temperatures(p.point_temperatures().raw());
    }

    StepReport<dim> advance(const double t_old, const double t_new) override
    {
      StepReport<dim> r;
      evaluate(t_new);
      if (!this->problem->solve_mechanics(t_old, t_new, false, r))
        {
          this->problem->revert();
          evaluate(t_old);
          return r.fail(r.mechanics().failure);
        }
      return r;
    }

  private:
    void evaluate(const double t)
    {
      temperature->set_time(t);
      auto &T = this->problem->point_temperatures();
      this->problem->for_each_point([&](const auto &cell, const unsigned int q, const Point<dim> &x) {
        T(cell, q) = temperature->value(x);
      });
    }

    std::shared_ptr<FunctionParser<dim>> temperature;
    std::string                          text;
  };

  ANVIL_REGISTER_COUPLING_SCHEME(
    PrescribedTemperature, "prescribed temperature",
    "T(x, t) given by Physics/Prescribed temperature, no heat equation solved; thermal strains "
    "and temperature-dependent properties follow it within the step.")
} // namespace anvil
