// The round-off floor of the mechanical residual (doc/mechanics.md, "Newton,
// line search, predictor, cut-back"): the smallest |R| Newton can reach.
#include <anvil/core/instantiate.h>
#include <anvil/mechanics/mechanical_problem.h>

#include <Epetra_CrsMatrix.h>

#include <cmath>
#include <limits>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  double MechanicalProblem<dim>::residual_floor() const
  {
    // The displacement of a dof is known to ε|u_i|, and the strain to ε
    // absolute (F = I + ∇u), i.e. the displacement to ε h on cells of size h
    // as well: the residual is only known to |K δu| with |δu_i| ≤ ε(|u_i| + h).
    // The stiffness's rows sum to about zero (a translation is free of
    // force), so Σ_j |K_ij| ≈ 2 K_ii. Newton's corrections stall there and
    // |R| wanders at that level whatever the step: two_blocks after its
    // unloading (|u| = 3.75 mm, |R| 2.5–3e-10 N against a force scale of
    // 0.17 N) or a small vibration (strain 1e-8: 1.5e-11 N against 1e-3 N).
    // Constrained rows carry no residual; h is the largest cell's diameter
    // (kept since setup(): the mesh does not move).
    const double h = largest_cell_diameter;
    // K_ii from its row's view and u_i by local index (diag_element() and
    // operator() searched the row and the map per dof: 23 of two_blocks' 38 M;
    // Epetra's ExtractDiagonalCopy scans every entry).
    const Epetra_CrsMatrix &K     = system_matrix.trilinos_matrix();
    const Epetra_BlockMap  &u_map = owned_solution.trilinos_vector().Map();
    const double           *u     = owned_solution.trilinos_vector()[0];
    double                  sum   = 0;
    for (const auto i : locally_owned_dofs)
      if (!active_constraints->is_constrained(i))
        {
          const int row = K.RowMap().LID(static_cast<int>(i)),
                    col = K.ColMap().LID(static_cast<int>(i));
          int     n_entries = 0, *columns = nullptr;
          double *values    = nullptr;
          double  diagonal  = 0; // absent: 0, as diag_element()
          if (row >= 0 && col >= 0 && K.ExtractMyRowView(row, n_entries, values, columns) == 0)
            for (int k = 0; k < n_entries; ++k)
              if (columns[k] == col)
                {
                  diagonal = values[k];
                  break;
                }
          const double k = 2 * std::abs(diagonal) * (std::abs(u[u_map.LID(static_cast<int>(i))]) + h);
          sum += k * k;
        }
    return std::numeric_limits<double>::epsilon() *
           std::sqrt(Utilities::MPI::sum(sum, mpi_communicator));
  }

#define INSTANTIATE(dim) template double MechanicalProblem<dim>::residual_floor() const;
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
