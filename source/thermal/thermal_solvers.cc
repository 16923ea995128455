// ThermalProblem: the linear solvers behind ARKode (the Newton matrix
// M + γA and its KLU or AMG, the mass solve).
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include <anvil/core/instantiate.h>
#include <anvil/thermal/thermal_problem.h>

#include "newton_factorisation.h"

#include <Epetra_CrsMatrix.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// @p to = @p a + γ @p b value by value where the three have one CRS
    /// layout (rows, columns, column map: built from one pattern), what
    /// copy_from and add(γ, ·) compute entry by entry, without their row
    /// look-ups (two_blocks: 33 M → ~3 M instructions). False if not.
    bool sum_in_one_layout(TrilinosWrappers::SparseMatrix &to, const TrilinosWrappers::SparseMatrix &a,
                           const double gamma, const TrilinosWrappers::SparseMatrix &b)
    {
      int    *to_rows = nullptr, *to_cols = nullptr;
      double *to_values = nullptr;
      auto   &target    = const_cast<Epetra_CrsMatrix &>(to.trilinos_matrix());
      if (target.ExtractCrsDataPointers(to_rows, to_cols, to_values) != 0)
        return false;
      const int n_rows = target.NumMyRows(), n_entries = target.NumMyNonzeros();
      const int n_columns = target.ColMap().NumMyElements();
      std::array<const double *, 2> values{};
      std::array<const TrilinosWrappers::SparseMatrix *, 2> sources{&a, &b};
      for (unsigned int m = 0; m < 2; ++m)
        {
          auto &source = const_cast<Epetra_CrsMatrix &>(sources[m]->trilinos_matrix());
          int    *rows = nullptr, *cols = nullptr;
          double *v    = nullptr;
          if (source.ExtractCrsDataPointers(rows, cols, v) != 0 || source.NumMyRows() != n_rows ||
              source.NumMyNonzeros() != n_entries || source.ColMap().NumMyElements() != n_columns ||
              !std::equal(rows, rows + n_rows + 1, to_rows) || !std::equal(cols, cols + n_entries, to_cols))
            return false;
          for (int c = 0; c < n_columns; ++c)
            if (source.ColMap().GID64(c) != target.ColMap().GID64(c))
              return false;
          values[m] = v;
        }
      for (int k = 0; k < n_entries; ++k)
        to_values[k] = values[0][k] + gamma * values[1][k];
      return true;
    }
  } // namespace

  template <int dim>
  void ThermalProblem<dim>::update_exchange_pattern()
  {
    // Contact (eq. 30) couples slave and master temperatures that share no
    // cell. Their entries join the pattern of the tangent, of the Newton
    // matrix and of a copy of M, so that M + γA − γ∂q/∂T is a sum value by
    // value (row-wise adds across two patterns cost 10× more); rebuilt only
    // when a new pair exchanges heat (the list only grows). The tangent is
    // then assembled again (in the new pattern); M is copied, not assembled.
    if (!exchange.add_matrix || (exchange_pattern_current && !exchange.couplings_changed()))
      return;
    TimerOutput::Scope t(timer, "Heat: exchange pattern");
    const auto         groups = exchange.couplings();
    if (exchange_pattern_current && covers(groups))
      return;
    // Built where covers() reads it (its rows of ghost dofs, which the
    // matrices ignore, too): no copy.
    exchange_sparsity(groups, exchange_pattern);
    newton_matrix.reinit(locally_owned_dofs, locally_owned_dofs, exchange_pattern, mpi_communicator);
    tangent_matrix.reinit(newton_matrix);
    tangent_positions_values = nullptr; // its entries moved (thermal_assembly.cc)
    mass_in_pattern.reinit(newton_matrix);
    newton_direct->clear();
    exchange_pattern_current = true;
    covered_groups.clear();
    covered_groups.insert(groups.begin(), groups.end());
    mass_in_pattern_current  = false;
    tangent_current          = false;
    couplings_current        = false; // dirichlet_mass takes the tangent's layout
    current_gamma            = -1;
  }

  template <int dim>
  void ThermalProblem<dim>::setup_newton(const double gamma, const bool exact)
  {
    // M − γ'J with γ' within 20 % of γ preconditions ARKode's GMRES on M − γJ
    // well (a few iterations): keep the factorisation.
    if (current_gamma > 0 && (exact ? gamma == current_gamma : std::abs(gamma / current_gamma - 1) < 0.2))
      return;
    TimerOutput::Scope t(timer, "Heat: Newton matrix");
    if (exchange.add_matrix)
      {
        // M + γA − γ ∂q/∂T, all three in the pattern of update_exchange_pattern().
        AssertThrow(exchange_pattern_current, ExcMessage("the exchange's pattern is not built"));
        if (!mass_in_pattern_current)
          {
            mass_in_pattern = 0;
            if (parameters.lumped_mass)
              {
                for (const auto i : locally_owned_dofs)
                  mass_in_pattern.set(i, i, lumped_mass(i));
                mass_in_pattern.compress(VectorOperation::insert);
              }
            else
              mass_in_pattern.add(1., mass_matrix);
            mass_in_pattern_current = true;
          }
        if (!sum_in_one_layout(newton_matrix, mass_in_pattern, gamma, tangent_matrix))
          {
            newton_matrix.copy_from(mass_in_pattern);
            newton_matrix.add(gamma, tangent_matrix);
          }
        exchange.add_matrix([&](const types::global_dof_index i, const types::global_dof_index j,
                                const double d) { newton_matrix.add(i, j, -gamma * d); });
        newton_matrix.compress(VectorOperation::add);
      }
    else if (parameters.lumped_mass)
      {
        newton_matrix.copy_from(tangent_matrix);
        newton_matrix *= gamma;
        for (const auto i : locally_owned_dofs)
          newton_matrix.add(i, i, lumped_mass(i));
        newton_matrix.compress(VectorOperation::add);
      }
    else if (!sum_in_one_layout(newton_matrix, mass_matrix, gamma, tangent_matrix))
      {
        newton_matrix.copy_from(mass_matrix);
        newton_matrix.add(gamma, tangent_matrix);
      }
    thermal::factorise_newton_matrix(newton_matrix, use_direct, parameters.polynomial_degree,
                                     newton_direct, newton_amg);
    current_gamma = gamma;
  }

  template <int dim>
  unsigned int ThermalProblem<dim>::solve_newton(Vector &x, const Vector &b, double)
  {
    if (use_direct)
      {
        newton_direct->solve(x, b);
        return 1;
      }
    newton_amg->vmult(x, b); // one V-cycle: the preconditioner of ARKode's GMRES
    return 1;
  }

  template <int dim>
  unsigned int ThermalProblem<dim>::solve_mass(Vector &x, const Vector &b, const double tolerance)
  {
    ++mass_solves;
    if (parameters.lumped_mass)
      {
        x = b;
        for (const auto i : locally_owned_dofs)
          x(i) /= lumped_mass(i);
        x.compress(VectorOperation::insert);
        return 1;
      }
    if (thermal::mass_by_klu(use_direct, parameters.lumped_mass, dof_handler.n_dofs()))
      {
        // M is fixed (reference configuration): factorised once, one solve
        // here instead of ~20 CG iterations.
        mass_direct->solve(x, b);
        ++linear_iterations;
        return 1;
      }
    SolverControl control(1000, std::min(tolerance, 1e-10 * b.l2_norm()));
    SolverCG<Vector> cg(control);
    x = 0;
    cg.solve(mass_matrix, x, b, mass_jacobi);
    linear_iterations += control.last_step();
    return control.last_step();
  }

  ANVIL_INSTANTIATE_CLASS(ThermalProblem)
} // namespace anvil
