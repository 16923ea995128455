// The energy generalized-α removes in one step (doc/energy_audit.md, eq. A3):
// the energy audit's algorithmic-dissipation term, from the step's
// velocities, accelerations and static residuals by its own formula.
#include <deal.II/fe/fe_values.h>

#include <anvil/core/instantiate.h>
#include <anvil/mechanics/assembly_mapping.h>
#include <anvil/mechanics/mechanical_problem.h>

#include <algorithm>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  void MechanicalProblem<dim>::mass_product(const TrilinosWrappers::MPI::Vector &x,
                                            TrilinosWrappers::MPI::Vector       &mx) const
  {
    // M x with the scene's mass (consistent, or its row sums if lumped), the
    // same cell mass as the inertia kernel (inertia.cc); kinetic_energy is
    // ½ v·(M v) with it. The cell masses are integrated on the reference
    // mesh, so they are computed once and kept (cell_masses).
    const unsigned int                   n = fe.n_dofs_per_cell();
    std::vector<types::global_dof_index> dofs(n);
    Vector<double>                       local(n);
    std::vector<double>                  xa(n);
    if (cell_masses.empty())
      {
        FEValues<dim> fe_values(mapping, fe, quadrature, update_values | update_JxW_values |
                                                           update_quadrature_points);
        for (const auto &cell : dof_handler.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              fe_values.reinit(cell);
              const std::size_t start = cell_masses.size();
              cell_masses.resize(start + n * n, 0.);
              double *const m   = &cell_masses[start];
              const double  rho = materials.at(cell->material_id())->density();
              for (unsigned int q = 0; q < quadrature.size(); ++q)
                {
                  const double w = rho * fe_values.JxW(q) *
                                   (axisymmetric ? 2 * numbers::PI * fe_values.quadrature_point(q)[0] : 1.);
                  for (unsigned int a = 0; a < n; ++a)
                    {
                      const unsigned int c  = fe.system_to_component_index(a).first;
                      const double       Na = fe_values.shape_value_component(a, q, c);
                      if (parameters.lumped_mass)
                        m[a * n + a] += Na * w;
                      else
                        for (unsigned int b = 0; b < n; ++b)
                          if (fe.system_to_component_index(b).first == c)
                            m[a * n + b] += Na * fe_values.shape_value_component(b, q, c) * w;
                    }
                }
            }
      }
    mx = 0;
    // The dof values and sums by the assembly's kept local indices (one
    // look-up per dof and mesh), when x has the ghosted vectors' layout; a
    // cell with a dof owned elsewhere adds through mx.add (compress below).
    const Epetra_BlockMap &x_map     = x.trilinos_vector().Map();
    const Epetra_BlockMap &ghost_map = solution.trilinos_vector().Map();
    const Epetra_BlockMap &mx_map    = mx.trilinos_vector().Map();
    const auto             same      = [](const Epetra_BlockMap &a, const Epetra_BlockMap &b) {
      return a.DataPtr() == b.DataPtr() ||
             (a.NumMyElements() == b.NumMyElements() &&
              std::equal(a.MyGlobalElements(), a.MyGlobalElements() + a.NumMyElements(),
                         b.MyGlobalElements()));
    };
    const bool by_index =
      same(x_map, ghost_map) && same(mx_map, system_rhs.trilinos_vector().Map());
    const double *const x_values  = x.trilinos_vector()[0];
    double *const       mx_values = mx.begin();
    if (by_index)
      assembly_mapping->reserve_vector_indices(n);
    const double *mass = cell_masses.data();
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          int *lids = nullptr, *owned = nullptr;
          if (by_index)
            {
              lids  = assembly_mapping->vector_indices(cell->active_cell_index(), n);
              owned = assembly_mapping->owned_vector_indices(cell->active_cell_index(), n);
              if (lids[0] == -2 || owned[0] == -2)
                {
                  cell->get_dof_indices(dofs);
                  for (unsigned int b = 0; b < n; ++b)
                    {
                      const auto gid = static_cast<TrilinosWrappers::types::int_type>(dofs[b]);
                      lids[b]        = ghost_map.LID(gid);
                      owned[b]       = mx_map.LID(gid);
                    }
                }
              for (unsigned int b = 0; b < n; ++b)
                xa[b] = x_values[lids[b]];
            }
          else
            {
              cell->get_dof_indices(dofs);
              for (unsigned int b = 0; b < n; ++b)
                xa[b] = x(dofs[b]);
            }
          for (unsigned int a = 0; a < n; ++a, mass += n)
            {
              double sum = 0;
              for (unsigned int b = 0; b < n; ++b)
                sum += mass[b] * xa[b];
              local(a) = sum;
            }
          const bool all_owned =
            by_index && std::all_of(owned, owned + n, [](const int i) { return i >= 0; });
          if (all_owned)
            for (unsigned int a = 0; a < n; ++a)
              mx_values[owned[a]] += local(a); // what mx.add does with an owned entry
          else
            {
              if (by_index)
                cell->get_dof_indices(dofs);
              mx.add(dofs, local);
            }
        }
    mx.compress(VectorOperation::add);
  }

  template <int dim>
  double MechanicalProblem<dim>::step_algorithmic_dissipation(
    const TrilinosWrappers::MPI::Vector &du, const TrilinosWrappers::MPI::Vector &a_new,
    const TrilinosWrappers::MPI::Vector &v_new) const
  {
    // Eq. A3 (doc/energy_audit.md): with ⟨x⟩ = ½(xₙ + xₙ₊₁), [x] = xₙ₊₁ − xₙ,
    // r = f_int (with contact) − f_ext, the step's Newmark update and the
    // α-shifted balance of the free dofs (Chung & Hulbert 1993),
    //   D = (½ − α_f) (Δt ⟨v⟩ᵀM[a] + [r]·Δu|free)
    //     + (β − γ/2) Δt² (⟨a⟩ᵀM[a] + (½ − α_m)[a]ᵀM[a])
    //     − (½ − α_m) (M[a])·Δu|supports,
    // the last term because the supports' reactions carry M aₙ₊₁, not the
    // balance's M ã. Zero for ρ∞ = 1 (α_m = α_f = ½, γ = ½, β = ¼).
    const double dt = current_time_step;
    TrilinosWrappers::MPI::Vector jump_a(a_new), mean_a(a_new), mean_v(v_new);
    jump_a -= acceleration_old;
    mean_a += acceleration_old;
    mean_a *= 0.5;
    mean_v += velocity_old;
    mean_v *= 0.5;

    TrilinosWrappers::MPI::Vector ghosted(locally_owned_dofs, locally_relevant_dofs,
                                          mpi_communicator);
    ghosted = jump_a;
    TrilinosWrappers::MPI::Vector m_jump_a(locally_owned_dofs, mpi_communicator);
    mass_product(ghosted, m_jump_a);

    // [r]·Δu on the free dofs (hanging nodes included: their residual is
    // condensed onto the masters, which Δu of both carries), M[a]·Δu on the supports.
    // (The owned vectors' k-th local entries are the k-th owned dof's.)
    double              residual_work = 0, support_work = 0;
    const double *const m_a = m_jump_a.begin(), *const u = du.begin();
    const double *const f_int = internal_force.begin(), *const f_ext = external_force.begin();
    const double *const r_old = static_residual_old.begin();
    unsigned int        k     = 0;
    for (const auto i : locally_owned_dofs)
      {
        const auto *masters = constraints.get_constraint_entries(i);
        if (masters && masters->empty())
          support_work += m_a[k] * u[k];
        else
          residual_work += (f_int[k] - f_ext[k] - r_old[k]) * u[k];
        ++k;
      }
    residual_work = Utilities::MPI::sum(residual_work, mpi_communicator);
    support_work  = Utilities::MPI::sum(support_work, mpi_communicator);

    const double beta = newmark_beta, gamma = newmark_gamma;
    return (0.5 - alpha_f) * (dt * (mean_v * m_jump_a) + residual_work) +
           (beta - 0.5 * gamma) * dt * dt *
             ((mean_a * m_jump_a) + (0.5 - alpha_m) * (jump_a * m_jump_a)) -
           (0.5 - alpha_m) * support_work;
  }

  ANVIL_INSTANTIATE_CLASS(MechanicalProblem)
} // namespace anvil
