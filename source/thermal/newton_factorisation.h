#pragma once

// The heat problem's Newton matrix (M + gamma A for ARKode, A for the steady
// state) made ready to solve with: KLU, or the AMG of a Krylov solver. One
// place for both users (thermal_solvers.cc, steady_state.cc).

#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <cstddef>
#include <memory>

#include <anvil/core/klu_factorization.h>

namespace anvil
{
  namespace thermal
  {
    inline void factorise_newton_matrix(const dealii::TrilinosWrappers::SparseMatrix &matrix,
                                        const bool use_direct, const unsigned int degree,
                                        std::unique_ptr<KluFactorization> &direct,
                                        std::unique_ptr<dealii::TrilinosWrappers::PreconditionAMG> &amg)
    {
      if (use_direct)
        {
          // Numeric only while the matrix keeps its object and pattern
          // (KluFactorization notices a new one and analyses it again).
          if (!direct)
            direct = std::make_unique<KluFactorization>();
          direct->factorize(matrix);
          return;
        }
      dealii::TrilinosWrappers::PreconditionAMG::AdditionalData data;
      data.elliptic              = true;
      data.higher_order_elements = degree > 1;
      data.smoother_sweeps       = 2;
      amg                        = std::make_unique<dealii::TrilinosWrappers::PreconditionAMG>();
      amg->initialize(matrix, data);
    }

    /// Whether ARKode's mass solves use a KLU of M (factorised once per mass
    /// assembly) rather than CG + Jacobi: where M + γA is direct and the
    /// problem is small. Measured: 462 unknowns (two_blocks), one KLU solve
    /// instead of 23 CG iterations; 15 625 (contrib/bench/heat_plate.prm),
    /// 9 CG iterations beat the solve with KLU's fill-in (the run took 20 %
    /// more CPU).
    inline bool mass_by_klu(const bool use_direct, const bool lumped, const std::size_t n_dofs)
    {
      return use_direct && !lumped && n_dofs <= 5000;
    }
  } // namespace thermal
} // namespace anvil
