#pragma once

// GMRES as every preconditioner of the displacement system runs it (private
// to amg_solver.cc and geometric_coarse_space.cc): right preconditioning,
// the stall stop, the Krylov basis given back after the solve.

#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector_memory.h>

#include <anvil/mechanics/linear_solver.h>

#include <algorithm>
#include <vector>

namespace anvil
{
  namespace gmres_run_detail
  {
    using namespace dealii;

    /**
     * SolverControl that also gives up on a stalled solve: when the
     * residual has not fallen below half of the best it had reached
     * `window` iterations earlier. A stalled solve does not recover: the
     * 2D 256² plastic F-bar block's second Newton iteration of step 1's full
     * step (whose tangent KLU solves to 2e-14) sat at |r| ≈ |b| for all
     * 1000 iterations (its true residual at the end 18 |b|) before the step
     * was cut back anyway; with the stop it fails after one cycle (60
     * iterations). A converging solve gains far more per cycle: the onset
     * solve of the same step (63 iterations to 1e-8) ~50×, the slowest
     * converging solve seen (460, the rigid-body modes only, GMRES(28))
     * ~3× per 28 iterations. doc/linear_solver.md, sessions 19 and 20.
     */
    class StallControl : public SolverControl
    {
    public:
      StallControl(const unsigned int max_steps, const double tolerance, const unsigned int window)
        : SolverControl(max_steps, tolerance)
        , window(window)
      {}

      State check(const unsigned int step, const double value) override
      {
        const State state = SolverControl::check(step, value);
        if (state != iterate)
          return state;
        // GMRES reports a restart's step twice (its estimate, then the true
        // residual): the best of the two.
        if (step < best.size())
          best[step] = std::min(best[step], value);
        else
          {
            const double before = best.empty() ? value : best.back();
            best.resize(step, before);
            best.push_back(std::min(before, value));
          }
        if (step >= window && value > 0.5 * best[step - window])
          {
            lcheck = failure;
            return failure;
          }
        return state;
      }

    private:
      const unsigned int  window;
      /// best[s]: the smallest residual up to step s.
      std::vector<double> best;
    };
  } // namespace gmres_run_detail

  /// GMRES on K x = b to the settings' tolerance relative to |b|, right
  /// preconditioned by @p preconditioner (anything with vmult); the
  /// iterations it took. Throws SolverControl::NoConvergence on failure.
  template <class Preconditioner>
  unsigned int run_gmres(const dealii::TrilinosWrappers::SparseMatrix &K,
                         dealii::TrilinosWrappers::MPI::Vector        &x,
                         const dealii::TrilinosWrappers::MPI::Vector  &b,
                         const Preconditioner                         &preconditioner,
                         const IterativeSolverSettings                &settings)
  {
    using Vector = dealii::TrilinosWrappers::MPI::Vector;
    // One restart cycle without halving the residual: stalled.
    gmres_run_detail::StallControl control(settings.max_iterations, settings.tolerance * b.l2_norm(),
                                           settings.restart);
    // Right preconditioning: the test is on the true residual |b − K x|
    // (left preconditioning would test |P⁻¹(b − K x)|, in mm, against a
    // tolerance in N). deal.II keeps restart + 2 vectors, 8 B per DoF each.
    dealii::SolverGMRES<Vector> gmres(control,
                                      typename dealii::SolverGMRES<Vector>::AdditionalData(settings.restart + 2, true));
    // deal.II's vector pool keeps the Krylov basis after the solve, and the
    // next preconditioner set-up, the run's memory peak, would sit on top of
    // it: give it back (a few page faults per solve).
    const auto release = [] { dealii::GrowingVectorMemory<Vector>::release_unused_memory(); };
    try
      {
        gmres.solve(K, x, b, preconditioner);
      }
    catch (...)
      {
        release();
        throw;
      }
    release();
    return control.last_step();
  }
} // namespace anvil
