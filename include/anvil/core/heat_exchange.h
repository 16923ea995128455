#pragma once

#include <deal.II/base/types.h>
#include <deal.II/lac/trilinos_vector.h>

#include <functional>
#include <vector>

namespace anvil
{
  /**
   * Heat exchanged at nodes outside the cells' coupling (contact conduction
   * and frictional heat, seed eq. 30–33), linear in T over a step:
   * f += q(T), ∂q/∂T applied matrix-free (add_jacobian) and as entries of
   * the heat problem's Newton matrix (add_matrix, in the pattern that
   * couplings() extends). Each function writes only locally owned entries
   * of its output. It lives in core/ because it is the whole interface
   * between its maker (contact) and its user (the heat problem): neither
   * includes the other.
   */
  struct HeatExchange
  {
    using Vector = dealii::TrilinosWrappers::MPI::Vector;
    using Index  = dealii::types::global_dof_index;
    /// (row, column, ∂q_row/∂T_column), rows owned here and unconstrained.
    using Adder = std::function<void(Index row, Index column, double value)>;

    std::function<void(double t, const Vector &T, Vector &f)> add_rhs;      // f += q(T)
    /// Whether add_rhs depends on t (a tool's temperature T_tool(t)).
    bool rhs_depends_on_time = true;
    std::function<void(const Vector &v, Vector &Jv)>          add_jacobian; // Jv += ∂q/∂T v
    std::function<void(const Adder &add)>                     add_matrix;   // ∂q/∂T, entry by entry
    /// Groups of temperature dofs that may couple (each group all-to-all),
    /// the same list on every process; it only grows, so a pattern built
    /// from it stays valid while couplings_changed() is false.
    std::function<std::vector<std::vector<Index>>()> couplings;
    /// Whether couplings() grew since it was last called (the same answer on every process).
    std::function<bool()> couplings_changed;
  };
} // namespace anvil
