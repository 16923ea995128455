// Inertia of the generalized-α scheme (Chung & Hulbert 1993), assembly_kernels.h.
#include <anvil/core/instantiate.h>
#include <anvil/mechanics/assembly_kernels.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace anvil
{
  namespace MechanicsAssembly
  {
    using namespace dealii;

    template <int dim>
    void Inertia<dim>::mass(const CellIterator<dim> &cell, ScratchData<dim> &scratch) const
    {
      const Formulation<dim> &formulation = *context.formulation;
      const unsigned int      n_dofs      = formulation.n_dofs;
      for (unsigned int i = 0; i < n_dofs; ++i)
        scratch.local_a[i] =
          newmark_acceleration(scratch.local_u[i], scratch.local_u_old[i], scratch.local_v_old[i],
                               scratch.local_a_old[i], context.time_step, context.newmark_beta);
      // Mass on the reference configuration: ρ₀ dV is conserved, so the
      // cell's mass is integrated at its first assembly and kept (NaN until
      // then; a cell writes only its own entries, on any thread). Shape
      // functions a, b of one component carry the scalar N_i, N_j of their
      // nodes: the node mass m_ij = Σ ρ N_i N_j w, once per node pair.
      const unsigned int n_nodes = formulation.n_nodes;
      double *const      kept    = (*context.node_masses)[cell].data();
      scratch.cell_node_mass     = kept;
      if (!std::isnan(kept[0]))
        return;
      const auto          &node = formulation.node;
      std::vector<double> &m    = scratch.node_mass;
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
      std::copy(m.begin(), m.end(), kept);
    }

    template <int dim>
    void Inertia<dim>::assemble(ScratchData<dim> &scratch, CopyData &copy) const
    {
      // Generalized α: M ã + (1 − α_f) R(u_{n+1}) + α_f R(u_n) = 0 with
      // ã = (1 − α_m) a_{n+1} + α_m a_n; α_f R(u_n) is added globally.
      const Formulation<dim> &formulation = *context.formulation;
      const unsigned int      n_dofs      = formulation.n_dofs;
      const unsigned int      n_nodes     = formulation.n_nodes;
      const auto             &node        = formulation.node;
      const auto             &component   = formulation.component;
      const double            alpha_m     = context.alpha_m;
      const double            alpha_f     = context.alpha_f;
      const double            dt          = context.time_step;
      const double           *m           = scratch.cell_node_mass;
      // ∂a_{n+1}/∂u_{n+1} of Newmark, scaled by (1 − α_m) of the generalized-α balance.
      const double mass_factor = (1 - alpha_m) / (context.newmark_beta * dt * dt);
      // On raw storage: deal.II's Vector and FullMatrix *= cost more in
      // their dispatch than in the 8–18 products of a cell (the same products).
      const double static_factor = 1 - alpha_f;
      for (unsigned int a = 0; a < n_dofs; ++a)
        copy.rhs(a) *= static_factor;
      double *K = context.with_matrix ? &copy.matrix(0, 0) : nullptr;
      if (K)
        for (unsigned int ab = 0; ab < n_dofs * n_dofs; ++ab)
          K[ab] *= static_factor;
      // The dof mass M_ab is m_ij of the nodes of a and b if they share a
      // component, else zero: only those b are visited (the sums of the full
      // rows, whose other terms are exact zeros). Lumped: M_aa = its row's sum.
      // ã_b once per dof, not per pair (the same expression: the same bits).
      double a_tilde[27 * 3];
      AssertThrow(n_dofs <= 27 * 3, ExcInternalError());
      for (unsigned int b = 0; b < n_dofs; ++b)
        a_tilde[b] = (1 - alpha_m) * scratch.local_a[b] + alpha_m * scratch.local_a_old[b];
      const double *acc = scratch.local_a.data();
      // The dofs of a's component: every b, or (interleaved 2D layout) b ≡ a mod 2.
      const unsigned int stride = formulation.planar_dofs ? 2 : 1;
      for (unsigned int a = 0; a < n_dofs; ++a)
        {
          const double      *m_row = m + node[a] * n_nodes;
          const unsigned int ca    = component[a];
          double             ma = 0, ma_tilde = 0;
          if (context.lumped_mass)
            {
              double m_aa = 0;
              for (unsigned int b = 0; b < n_dofs; ++b)
                if (component[b] == ca)
                  m_aa += m_row[node[b]];
              ma       = m_aa * acc[a];
              ma_tilde = m_aa * a_tilde[a];
              if (K)
                K[a * n_dofs + a] += mass_factor * m_aa;
            }
          else
            for (unsigned int b = stride == 2 ? ca : 0; b < n_dofs; b += stride)
              if (component[b] == ca)
                {
                  const double m_ab = m_row[node[b]];
                  ma += m_ab * acc[b];
                  ma_tilde += m_ab * a_tilde[b];
                  if (K)
                    K[a * n_dofs + b] += mass_factor * m_ab;
                }
          copy.inertia(a) = ma;
          copy.rhs(a) -= ma_tilde;
        }
    }

    ANVIL_INSTANTIATE_CLASS(Inertia)
  } // namespace MechanicsAssembly
} // namespace anvil
