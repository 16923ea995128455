// Inertia of the generalized-α scheme (Chung & Hulbert 1993), assembly_kernels.h.
#include <anvil/core/instantiate.h>
#include <anvil/mechanics/assembly_kernels.h>

#include <array>

namespace anvil
{
  namespace MechanicsAssembly
  {
    using namespace dealii;

    template <int dim>
    void Inertia<dim>::mass(ScratchData<dim> &scratch) const
    {
      const Formulation<dim> &formulation = *context.formulation;
      const unsigned int      n_dofs      = formulation.n_dofs;
      const auto             &component   = formulation.component;
      for (unsigned int i = 0; i < n_dofs; ++i)
        scratch.local_a[i] =
          newmark_acceleration(scratch.local_u[i], scratch.local_u_old[i], scratch.local_v_old[i],
                               scratch.local_a_old[i], context.time_step, context.newmark_beta);
      // Mass on the reference configuration: ρ₀ dV is conserved. Shape
      // functions a, b of one component carry the scalar N_i, N_j of their
      // nodes: the node mass m_ij = Σ ρ N_i N_j w, the same products and sums
      // per entry, once per node pair instead of once per dof pair.
      const unsigned int n_nodes = formulation.n_nodes;
      const auto        &node    = formulation.node;
      std::vector<double> &m     = scratch.node_mass;
      m.assign(n_nodes * n_nodes, 0.);
      std::array<double, 27> N; // N_i at q, up to 27-node hexahedra
      AssertThrow(n_nodes <= N.size(), ExcInternalError());
      for (unsigned int q = 0; q < scratch.points.size(); ++q)
        {
          const double  w     = scratch.points[q].w;
          const double *value = scratch.cell.value + q * n_dofs;
          for (unsigned int a = 0; a < n_dofs; ++a)
            N[node[a]] = value[a];
          for (unsigned int i = 0; i < n_nodes; ++i)
            for (unsigned int j = 0; j < n_nodes; ++j)
              m[i * n_nodes + j] += scratch.rho * N[i] * N[j] * w;
        }
      FullMatrix<double> &cell_mass = scratch.cell_mass;
      for (unsigned int a = 0; a < n_dofs; ++a)
        for (unsigned int b = 0; b < n_dofs; ++b)
          cell_mass(a, b) = component[a] == component[b] ? m[node[a] * n_nodes + node[b]] : 0.;
    }

    template <int dim>
    void Inertia<dim>::assemble(ScratchData<dim> &scratch, CopyData &copy) const
    {
      // Generalized α: M ã + (1 − α_f) R(u_{n+1}) + α_f R(u_n) = 0 with
      // ã = (1 − α_m) a_{n+1} + α_m a_n; α_f R(u_n) is added globally.
      const unsigned int  n_dofs    = context.formulation->n_dofs;
      const double        alpha_m   = context.alpha_m;
      const double        alpha_f   = context.alpha_f;
      const double        dt        = context.time_step;
      FullMatrix<double> &cell_mass = scratch.cell_mass;
      // ∂a_{n+1}/∂u_{n+1} of Newmark, scaled by (1 − α_m) of the generalized-α balance.
      const double mass_factor = (1 - alpha_m) / (context.newmark_beta * dt * dt);
      if (context.lumped_mass)
        for (unsigned int a = 0; a < n_dofs; ++a)
          {
            double m = 0;
            for (unsigned int b = 0; b < n_dofs; ++b)
              m += cell_mass(a, b);
            for (unsigned int b = 0; b < n_dofs; ++b)
              cell_mass(a, b) = (a == b) ? m : 0.;
          }
      copy.rhs *= (1 - alpha_f);
      if (context.with_matrix)
        copy.matrix *= (1 - alpha_f);
      for (unsigned int a = 0; a < n_dofs; ++a)
        {
          double ma = 0, ma_tilde = 0;
          for (unsigned int b = 0; b < n_dofs; ++b)
            {
              ma += cell_mass(a, b) * scratch.local_a[b];
              ma_tilde += cell_mass(a, b) *
                          ((1 - alpha_m) * scratch.local_a[b] + alpha_m * scratch.local_a_old[b]);
              if (context.with_matrix)
                copy.matrix(a, b) += mass_factor * cell_mass(a, b);
            }
          copy.inertia(a) = ma;
          copy.rhs(a) -= ma_tilde;
        }
    }

    ANVIL_INSTANTIATE_CLASS(Inertia)
  } // namespace MechanicsAssembly
} // namespace anvil
