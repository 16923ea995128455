// ThermalProblem's Dirichlet boundary: the prescribed temperatures, the
// mass couplings M_fD of the free rows to the prescribed dofs and the rates
// ġ_D that move them to the right-hand side (doc/thermal.md).
#include <deal.II/numerics/vector_tools.h>

#include <anvil/core/instantiate.h>
#include <anvil/thermal/assembly_data.h>
#include <anvil/thermal/kernels.h>
#include <anvil/thermal/thermal_problem.h>

#include "current_weights.h"
#include "owned_cells.h"

#include <algorithm>

namespace anvil
{
  using namespace dealii;
  using thermal::for_owned_cells;

  template <int dim>
  void ThermalProblem<dim>::dirichlet_values(const double t,
                                             std::map<types::global_dof_index, double> &values) const
  {
    values.clear();
    for (const auto &[id, b] : boundary_conditions.boundaries)
      if (b.temperature)
        {
          b.temperature->set_time(t);
          VectorTools::interpolate_boundary_values(get_mapping(), dof_handler, id, *b.temperature, values);
        }
  }

  template <int dim>
  void ThermalProblem<dim>::apply_dirichlet(const double t, Vector &y) const
  {
    std::map<types::global_dof_index, double> values;
    if (has_dirichlet)
      dirichlet_values(t, values);
    for (const auto i : dirichlet_dofs)
      y(i) = values.at(i);
    y.compress(VectorOperation::insert);
  }

  template <int dim>
  void ThermalProblem<dim>::assemble_dirichlet_couplings()
  {
    // M_fD on the reference configuration (ρ dv = ρ₀ dV): of each cell's
    // matrix only the columns of Dirichlet dofs and the rows of the others,
    // rows condensed through the hanging nodes as constraints.distribute does.
    // (K_fD needs no matrix of its own: the tangent keeps those columns.)
    TimerOutput::Scope scope(timer, "Heat: Dirichlet couplings");
    dirichlet_mass.reinit(tangent_matrix); // its layout: the pattern keeps constrained entries
    dirichlet_mass = 0;
    auto dirichlet = [&](const types::global_dof_index i) {
      return locally_relevant_dofs.is_element(i) && is_dirichlet[locally_relevant_dofs.index_within_set(i)];
    };
    auto keep_couplings = [&](thermal::CopyData &c) {
      bool any = false;
      for (unsigned int i = 0; i < c.dofs.size(); ++i)
        for (unsigned int j = 0; j < c.dofs.size(); ++j)
          if (dirichlet(c.dofs[i]) || !dirichlet(c.dofs[j]))
            c.matrix(i, j) = 0;
          else
            any = any || c.matrix(i, j) != 0;
      return any;
    };
    const bool axi = parameters.axisymmetric;
    {
      const thermal::ScratchData<dim> scratch(reference_mapping, reference_mapping, fe, quadrature,
                                              face_quadrature,
                                              update_values | update_JxW_values | update_quadrature_points,
                                              update_default, update_default);
      auto worker = [&](const CellIterator &cell, thermal::ScratchData<dim> &s, thermal::CopyData &c) {
        c.n_faces = 0;
        cell->get_dof_indices(c.dofs);
        if (std::none_of(c.dofs.begin(), c.dofs.end(), dirichlet))
          return;
        s.fe_values.reinit(cell);
        thermal::fill_weights<dim>(s.fe_values, axi, s.weight);
        const auto &m = materials.at(cell->material_id());
        thermal::HeatCapacity::cell_matrix(s, m.density * m.heat_capacity, c);
        c.n_faces = keep_couplings(c);
      };
      auto copier = [&](const thermal::CopyData &c) {
        if (c.n_faces)
          hanging.distribute_local_to_global(c.matrix, c.dofs, dirichlet_mass);
      };
      for_owned_cells(dof_handler, worker, copier, scratch);
    }
    dirichlet_mass.compress(VectorOperation::add);
  }

  template <int dim>
  std::map<types::global_dof_index, double> ThermalProblem<dim>::dirichlet_rates(const double t) const
  {
    // ġ at the Dirichlet dofs (central difference in time), for the rows
    // Ṫ_D = ġ_D and for moving M_fD ġ_D to the free rows.
    std::map<types::global_dof_index, double> g_dot;
    if (!has_dirichlet || solving_steady) // a steady state has no dT/dt, at the boundary neither
      return g_dot;
    const double eps = 1e-6 * std::max(step_length, 1e-300);
    std::map<types::global_dof_index, double> plus, minus;
    dirichlet_values(t + eps, plus);
    dirichlet_values(t - eps, minus);
    for (const auto &[i, v] : plus)
      {
        const double d = (v - minus.at(i)) / (2 * eps);
        if (d != 0)
          g_dot[i] = d;
      }
    return g_dot;
  }

  ANVIL_INSTANTIATE_CLASS(ThermalProblem)
} // namespace anvil
