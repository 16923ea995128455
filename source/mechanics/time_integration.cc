// Time integration of MechanicalProblem: the generalized-α dynamics
// (Chung & Hulbert 1993), accepting a step (Newmark update, energy audit) and
// the energies of the state.
#include <deal.II/base/function_parser.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>

#include <anvil/core/expression.h>
#include <anvil/core/scene.h>
#include <anvil/contact/contact_problem.h>
#include <anvil/mechanics/assembly_kernels.h>
#include <anvil/mechanics/cell_scatter.h>
#include <anvil/core/instantiate.h>
#include <anvil/mechanics/mechanical_problem.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// ANVIL_AUDIT_CHECK: the sums an evaluation kept against the pass's at
    /// the committed state (the same operations in the same order: expected
    /// equal to the bit); stops beyond 1e-12 of the largest.
    void check_kept_audit(const std::array<double, 6> &kept, const double kept_energy,
                          const std::array<double, 6> &pass, const double pass_energy,
                          const MPI_Comm comm)
    {
      double scale = std::abs(pass_energy), difference = std::abs(kept_energy - pass_energy);
      for (unsigned int k = 0; k < kept.size(); ++k)
        {
          scale      = std::max(scale, std::abs(pass[k]));
          difference = std::max(difference, std::abs(kept[k] - pass[k]));
        }
      AssertThrow(difference <= 1e-12 * scale,
                  ExcMessage("ANVIL_AUDIT_CHECK: the kept audit differs from the pass by " +
                             std::to_string(difference) + " N mm of " + std::to_string(scale)));
      if (Utilities::MPI::this_mpi_process(comm) == 0)
        std::printf("ANVIL_AUDIT_CHECK step audit: kept, difference %.3g of %.17g N mm\n",
                    difference, scale);
    }
  } // namespace

  template <int dim>
  void MechanicalProblem<dim>::setup_dynamics()
  {
    // Generalized-α (Chung & Hulbert 1993) from the spectral radius ρ∞.
    const double rho = parameters.spectral_radius;
    alpha_m          = (2 * rho - 1) / (rho + 1);
    alpha_f          = rho / (rho + 1);
    newmark_gamma    = 0.5 - alpha_m + alpha_f;
    newmark_beta     = 0.25 * (1 - alpha_m + alpha_f) * (1 - alpha_m + alpha_f);

    // Initial velocity at the dofs' support points.
    if (!parameters.initial_velocity.empty())
      {
        std::vector<std::shared_ptr<FunctionParser<dim>>> v(dim);
        for (const auto &assignment : split_outside_parentheses(parameters.initial_velocity, ','))
          {
            const auto eq = assignment.find('=');
            const auto c  = trim(assignment.substr(0, eq));
            for (unsigned int d = 0; d < dim; ++d)
              if (c == std::string("u") + "xyz"[d])
                v[d] = parse_expression<dim>(trim(assignment.substr(eq + 1)), Scene(),
                                             "Mechanics/Dynamics/Initial velocity");
          }
        std::map<types::global_dof_index, Point<dim>> support;
        DoFTools::map_dofs_to_support_points(mapping, dof_handler, support);
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
              cell->get_dof_indices(dofs);
              for (unsigned int i = 0; i < dofs.size(); ++i)
                {
                  const unsigned int c = fe.system_to_component_index(i).first;
                  if (v[c] && locally_owned_dofs.is_element(dofs[i]))
                    velocity_old(dofs[i]) = v[c]->value(support[dofs[i]]);
                }
            }
        velocity_old.compress(VectorOperation::insert);
      }
    velocity_old_ghosted = velocity_old;
    velocity_ghosted     = velocity_old;

    // Initial acceleration from M a₀ = f_ext(0) − f_int(u₀) with the lumped
    // mass (exact for a uniform body force on a free body; zero at rest).
    current_time_step = 1;
    assemble(false, 0);
    TrilinosWrappers::MPI::Vector lumped;
    lumped.reinit(system_rhs);
    lumped_mass(lumped);
    for (const auto i : locally_owned_dofs)
      if (!constraints.is_constrained(i) && lumped(i) > 0)
        acceleration_old(i) = (external_force(i) - internal_force(i)) / lumped(i);
    acceleration_old.compress(VectorOperation::insert);
    acceleration_old_ghosted = acceleration_old;
    static_residual_old      = internal_force;
    static_residual_old -= external_force;
    energy_audit.kinetic = energy_audit.initial_kinetic = kinetic_energy(velocity_ghosted);
  }

  template <int dim>
  double MechanicalProblem<dim>::elastic_strain_energy() const
  {
    // ∫ W dv with W = p²/2K(T) + s:s/4G(T) at the points' last stresses and
    // temperatures, J from the displacement: the state route of the energy
    // audit (doc/energy_audit.md), independent of the step's work sums.
    FEValues<dim> fe_values(mapping, fe, quadrature,
                            update_gradients | update_values | update_JxW_values |
                              update_quadrature_points);
    const unsigned int                   n_q = quadrature.size();
    std::vector<Tensor<2, dim>>          grad_u(n_q);
    std::vector<Tensor<1, dim>>          u_values(n_q);
    const FEValuesExtractors::Vector     displacements(0);
    const bool                           heat = static_cast<bool>(temperature_field);
    double                               energy = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[displacements].get_function_gradients(solution, grad_u);
          fe_values[displacements].get_function_values(solution, u_values);
          const auto &m  = *materials.at(cell->material_id());
          for (unsigned int q = 0; q < n_q; ++q)
            {
              const double R = axisymmetric ? fe_values.quadrature_point(q)[0] : 1.;
              const double J = determinant(
                deformation_gradient(grad_u[q], axisymmetric ? u_values[q][0] : 0., R));
              const double T     = heat ? material_temperature(cell, q) : parameters.temperature;
              const double K     = m.bulk_modulus_at(T);
              const double G     = m.shear_modulus_at(T);
              const auto  &sigma = points(cell, q)->stress();
              const double p     = trace(sigma) / 3;
              const auto   s     = deviator(sigma);
              energy += 0.5 * (p * p / K + (s * s) / (2 * G)) * J * fe_values.JxW(q) *
                        (axisymmetric ? 2 * numbers::PI * R : 1.);
            }
        }
    return Utilities::MPI::sum(energy, mpi_communicator);
  }

  template <int dim>
  double MechanicalProblem<dim>::newmark_acceleration(const double u, const double u_old,
                                                      const double v_old, const double a_old) const
  {
    return MechanicsAssembly::Inertia<dim>::newmark_acceleration(u, u_old, v_old, a_old,
                                                                 current_time_step, newmark_beta);
  }

  template <int dim>
  double MechanicalProblem<dim>::Energy::balance_error() const
  {
    // Work balance: the nodes' side (loads, supports, contact forces) against
    // the points' side (stress work) and the kinetic energy (eq. in doc/energy_audit.md).
    const double residual =
      external_work + initial_kinetic - kinetic - stress_work - contact_work - algorithmic_dissipation;
    const double scale = std::max({std::abs(external_work), std::abs(stress_work),
                                   std::abs(contact_work), std::abs(kinetic),
                                   std::abs(initial_kinetic), std::abs(algorithmic_dissipation),
                                   1e-300});
    return std::abs(residual) / scale;
  }

  template <int dim>
  double MechanicalProblem<dim>::Energy::stress_balance_error() const
  {
    // Stress work against its parts, each by its own route.
    const double initial  = initial_elastic_energy;
    const double residual = stress_work - (elastic_energy - initial) - flow_plastic_work -
                            thermal_work + hypoelastic_volume_work - f_bar_work;
    // Relative to the largest energy of the audit, not only of this balance:
    // a scene of nearly rigid bodies (two blocks sliding) has a stress work
    // at round-off beside the work of its loads.
    const double scale = std::max({std::abs(stress_work), std::abs(elastic_energy - initial),
                                   std::abs(flow_plastic_work), std::abs(thermal_work),
                                   std::abs(external_work), std::abs(contact_work),
                                   std::abs(kinetic), std::abs(initial_kinetic), 1e-300});
    return std::abs(residual) / scale;
  }

  template <int dim>
  void MechanicalProblem<dim>::commit_step()
  {
    TrilinosWrappers::MPI::Vector &du = owned_work(work_increment);
    du                                = owned_solution;
    du -= owned_old_solution;
    // The owned vectors share locally_owned_dofs' layout: the k-th local
    // entry of each is one dof's, so element-wise updates run on the arrays.
    const unsigned int n_owned = owned_solution.locally_owned_size();

    if (parameters.dynamic)
      {
        // Newmark update of a and v from the converged u.
        TrilinosWrappers::MPI::Vector a(acceleration_old), v(velocity_old);
        const double                  dt    = current_time_step;
        const double *const           u     = owned_solution.begin();
        const double *const           u_old = owned_old_solution.begin();
        const double *const           v_old = velocity_old.begin();
        const double *const           a_old = acceleration_old.begin();
        double *const                 a_new = a.begin();
        double *const                 v_new = v.begin();
        for (unsigned int k = 0; k < n_owned; ++k)
          {
            a_new[k] = newmark_acceleration(u[k], u_old[k], v_old[k], a_old[k]);
            v_new[k] = v_old[k] + dt * ((1 - newmark_gamma) * a_old[k] + newmark_gamma * a_new[k]);
          }
        energy_audit.algorithmic_dissipation += step_algorithmic_dissipation(du, a, v);
        acceleration_old_ghosted = a;
        velocity_old_ghosted = v;
        velocity_ghosted = velocity_old_ghosted;
        acceleration_old.swap(a);
        velocity_old.swap(v);
        static_residual_old = internal_force;
        static_residual_old -= external_force;
        energy_audit.kinetic = kinetic_energy(velocity_ghosted);
      }

    // Work of loads and supports (trapezoidal): the supports' reactions are
    // r = f_int + M a − f_ext at the constrained dofs (reactions.csv); the
    // audit takes them there only, so that an unbalanced free dof shows up
    // as an error instead of being counted as work.
    reaction_force = internal_force;
    reaction_force += inertia_force;
    reaction_force -= external_force;
    TrilinosWrappers::MPI::Vector &mean = owned_work(work_sum);
    mean                                = external_force;
    mean += external_force_old;
    {
      double *const       m      = mean.begin();
      const double *const r      = reaction_force.begin();
      const double *const r_old  = reaction_force_old.begin();
      unsigned int        k      = 0;
      for (const auto i : locally_owned_dofs)
        {
          // A support: a constrained dof with no master dofs (not a hanging node).
          const auto *masters = constraints.get_constraint_entries(i);
          if (masters && masters->empty())
            m[k] += r[k] + r_old[k];
          ++k;
        }
    }
    energy_audit.external_work += 0.5 * (mean * du);
    mean = internal_force;
    mean += internal_force_old;
    energy_audit.internal_work += 0.5 * (mean * du);
    if (contact) // (without, f_c is zero: the work's sum stays +0)
      {
        mean = contact_force;
        mean += contact_force_old;
        energy_audit.contact_work += 0.5 * (mean * du);
      }
    // The points' terms as the step's last evaluation summed them where it
    // was asked to and nothing moved since (audit_from_kept()), else by a
    // pass of their own: the same numbers. ANVIL_AUDIT_CHECK (tests) runs
    // the pass beside the kept sums and stops if they differ.
    static const bool check = std::getenv("ANVIL_AUDIT_CHECK") != nullptr;
    const bool        kept  = audit_from_kept();
    kept_audit.evaluation   = 0; // the points commit below: forgotten
    if (kept && check)
      {
        const std::array<double, 6> kept_terms  = step_audit;
        const double                kept_energy = energy_audit.elastic_energy;
        compute_step_audit();
        check_kept_audit(kept_terms, kept_energy, step_audit, energy_audit.elastic_energy,
                         mpi_communicator);
      }
    else if (!kept)
      {
        compute_step_audit();
        if (check && Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
          std::printf("ANVIL_AUDIT_CHECK step audit: pass\n");
      }
    if (audit_omission)
      step_audit[audit_omission - 1] = 0; // a test-only injected error (ANVIL_AUDIT_OMIT)
    using namespace MechanicsAssembly;
    energy_audit.stress_work += step_audit[audit_stress_work];
    energy_audit.plastic_work += step_audit[audit_heat_plastic_work];
    energy_audit.flow_plastic_work += step_audit[audit_plastic_work];
    energy_audit.thermal_work += step_audit[audit_thermal_work];
    energy_audit.hypoelastic_volume_work += step_audit[audit_volume_work];
    energy_audit.f_bar_work += step_audit[audit_stress_work] - step_audit[audit_material_work];
    // compute_step_audit() summed the state's elastic energy at the points;
    // ANVIL_AUDIT_CHECK (tests) compares it with the FEValues route.
    if (check)
      {
        const double by_fe_values = elastic_strain_energy();
        const double difference   = std::abs(by_fe_values - energy_audit.elastic_energy);
        // Every point's W J dV ≥ 0: the sums differ by the round-off of J and dV.
        AssertThrow(difference <= 1e-12 * std::abs(by_fe_values),
                    ExcMessage("ANVIL_AUDIT_CHECK: elastic energy at the points " +
                               std::to_string(energy_audit.elastic_energy) + " N mm, by FEValues " +
                               std::to_string(by_fe_values) + " N mm"));
        if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
          std::printf("ANVIL_AUDIT_CHECK elastic energy: points %.17g FEValues %.17g N mm\n",
                      energy_audit.elastic_energy, by_fe_values);
      }

    previous_increment = du;
    if (contact)
      contact->commit();
    material_temperature_old = material_temperature;
    previous_time_step = current_time_step;
    for (auto &p : points.raw())
      if (p)
        p->commit();
    owned_old_solution = owned_solution;
    old_solution = owned_solution;
    internal_force_old = internal_force;
    external_force_old = external_force;
    reaction_force_old = reaction_force;
    if (contact)
      contact_force_old = contact_force;
  }

  template <int dim>
  void MechanicalProblem<dim>::lumped_mass(TrilinosWrappers::MPI::Vector &m) const
  {
    FEValues<dim> fe_values(mapping, fe, quadrature, update_values | update_JxW_values |
                                                       update_quadrature_points);
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    Vector<double>                       local(fe.n_dofs_per_cell());
    m = 0;
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell->get_dof_indices(dofs);
          const double rho = materials.at(cell->material_id())->density();
          local            = 0;
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const double w = fe_values.JxW(q) *
                               (axisymmetric ? 2 * numbers::PI * fe_values.quadrature_point(q)[0] : 1.);
              for (unsigned int a = 0; a < dofs.size(); ++a)
                local(a) += rho *
                            fe_values.shape_value_component(a, q, fe.system_to_component_index(a).first) * w;
            }
          m.add(dofs, local);
        }
    m.compress(VectorOperation::add);
  }

  template <int dim>
  double MechanicalProblem<dim>::kinetic_energy(const TrilinosWrappers::MPI::Vector &v) const
  {
    // ½ vᵀ M v with the mass the audit's other terms use (mass_product).
    TrilinosWrappers::MPI::Vector mv;
    mv.reinit(system_rhs); // its layout object: v and mv share it on one process
    mass_product(v, mv);
    double energy = 0;
    // By the local arrays where v has mv's layout (one process): the same
    // values in the same order as v(i) and mv(i), without a look-up each.
    if (MechanicsAssembly::same_local_map(v.trilinos_vector().Map(), mv.trilinos_vector().Map()))
      {
        const double *const v_values = v.trilinos_vector()[0], *const mv_values = mv.begin();
        for (unsigned int k = 0; k < mv.locally_owned_size(); ++k)
          energy += 0.5 * v_values[k] * mv_values[k];
      }
    else
      for (const auto i : locally_owned_dofs)
        energy += 0.5 * v(i) * mv(i);
    return Utilities::MPI::sum(energy, mpi_communicator);
  }

  ANVIL_INSTANTIATE_CLASS(MechanicalProblem)
} // namespace anvil
