#pragma once

#include <deal.II/base/parameter_handler.h>

#include <anvil/core/instantiate.h>
#include <anvil/core/registry.h>
#include <anvil/coupling/coupled_problem.h>

#include <memory>
#include <string>

namespace anvil
{
  /**
   * How the physics of a scene advance together over one time step (seed
   * §2.2): the mechanics alone, the heat alone, one after the other, or
   * iterated. One file per scheme under source/coupling/, each ending with
   * ANVIL_REGISTER_COUPLING_SCHEME; `Physics/Coupling` chooses among what is
   * registered, and the Simulator knows none of them by name.
   *
   * A scheme talks to the physics through CoupledProblem: solve a half,
   * revert both halves, commit both, temperatures at the mechanics' points.
   */
  template <int dim>
  class CouplingScheme
  {
  public:
    virtual ~CouplingScheme() = default;

    /// The scheme's own entries, declared inside `subsection Physics`
    /// (a scheme with entries hides this with its own).
    static void declare_parameters(dealii::ParameterHandler & /*prm*/) {}

    /// What the scheme solves: the Simulator builds only these.
    virtual bool needs_mechanics() const     = 0;
    virtual bool needs_heat_equation() const = 0;
    /// Whether the scene has a temperature field (solved or given).
    virtual bool provides_temperature() const { return needs_heat_equation(); }

    /// The scheme's own entries (declared by the registry in `Physics`).
    virtual void parse_parameters(dealii::ParameterHandler & /*prm*/, const Scene & /*scene*/) {}

    /// Before any work (--check and run), on the mesh: what the scheme itself
    /// sets that the mesh can refute (a given temperature that is not an
    /// absolute one at some node); throws InputError.
    virtual void check(const dealii::parallel::DistributedTriangulationBase<dim> & /*triangulation*/,
                       const Scene & /*scene*/, double /*end_time*/) const
    {}

    /// Wire the problems together, once they exist and before the first step
    /// (after a restart, too: the state is then already loaded).
    virtual void initialize(CoupledProblem<dim> &p) { problem = &p; }

    /// Advance from @p t_old to @p t_new. On failure everything is back at
    /// @p t_old and the report says why.
    virtual StepReport<dim> advance(double t_old, double t_new) = 0;

    /// Accept the step just advanced.
    virtual void commit(const double t_old, const double t_new) { problem->commit(t_new - t_old); }

    /// An easy step lets the time step grow (the heat half's failures count).
    virtual bool easy(const StepReport<dim> &r, unsigned int easy_iterations) const
    {
      return r.mechanics().iterations <= easy_iterations &&
             r.thermal.error_test_failures + r.thermal.nonlinear_failures == 0;
    }

  protected:
    CoupledProblem<dim> *problem = nullptr;
  };

  /// Schemes by name: Registry<CouplingScheme<dim>>::instance().
  template <int dim>
  using CouplingSchemeRegistry = Registry<CouplingScheme<dim>>;

  /// Declares `Physics/Coupling` (from what is registered) and each scheme's entries.
  template <int dim>
  void declare_coupling_parameters(dealii::ParameterHandler &prm);
} // namespace anvil

/**
 * Registers scheme class template @p Scheme under @p name for dim 2 and 3 and
 * instantiates it; its static declare_parameters() is called inside
 * `subsection Physics`.
 */
#define ANVIL_REGISTER_COUPLING_SCHEME_DIM_(Scheme, name, documentation, dim)            \
  template class Scheme<dim>;                                                                     \
  static const bool ANVIL_REGISTRY_UNIQUE(anvil_coupling_scheme_##dim##_) =                       \
    ::anvil::CouplingSchemeRegistry<dim>::instance().add(                                         \
      name, documentation,                                                                        \
      []() -> std::unique_ptr<::anvil::CouplingScheme<dim>> {                                    \
        return std::make_unique<Scheme<dim>>();                                                   \
      },                                                                                          \
      &Scheme<dim>::declare_parameters);
#define ANVIL_REGISTER_COUPLING_SCHEME(Scheme, name, documentation)                               \
  ANVIL_REGISTER_COUPLING_SCHEME_DIM_(Scheme, name, documentation, 2)                             \
  ANVIL_REGISTER_COUPLING_SCHEME_DIM_(Scheme, name, documentation, 3)
