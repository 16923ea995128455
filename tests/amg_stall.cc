// solve_gmres() gives up on a stalled solve (amg_solver.cc, StallControl:
// the residual not halved over one restart cycle) instead of running to the
// iteration cap, and still lets a slow but steady solve converge.
// The preconditioner is ML on the identity (n below ML's coarse size: one
// level, solved by KLU, so P = I exactly), and the closed forms are GMRES's on
// I + rho S, S the cyclic shift (S e_i = e_{i+1 mod n}, unitary):
//   - rho = infinity, i.e. K = S, b = e_0: K x for x in the Krylov space
//     span{e_0 .. e_{m-1}} lies in span{e_1 .. e_m}, orthogonal to b, so
//     GMRES(m) makes no progress at all for m < n: |r| = |b| at every step.
//     Expected: NoConvergence at step m (+1), not at the cap of 1000.
//   - rho = 0.97: the polynomial (1 - z)^k gives |r_k| <= rho^k |b| (S
//     unitary), also across restarts, so one cycle of m = 28 reduces the
//     residual by at least 0.97^28 = 0.43 < 1/2: the stop never fires and
//     GMRES reaches 1e-8 within ln(1e-8)/ln(0.97) = 605 iterations.
//   - K = I ⊕ S (two blocks of n), b = e_0 + 0.3 f_0 (f_0 the first unit
//     vector of the shift block): the I part is solved at once, while every
//     K x of the first cycles is orthogonal to f_0 (the shift block's Krylov
//     vectors reach f_0 only after wrapping round its n = 200 indices), so
//     |r| falls from 1.04 to ~0.3 in the first cycle (halved: GCRO-DR
//     continues) and then stays there. Expected: NoConvergence within two
//     more cycles' worth of stall checks (28 + 2 x 56), not at the cap.
#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/mechanics/linear_solver.h>

#include "check.h"

#include <algorithm>
#include <cmath>
#include <string>

using namespace dealii;

namespace
{
  /// I ⊕ S on 2n rows: the identity on the first n, the cyclic shift on the last n.
  void fill_split(TrilinosWrappers::SparseMatrix &K, const unsigned int n)
  {
    const IndexSet         owned = complete_index_set(2 * n);
    DynamicSparsityPattern dsp(2 * n, 2 * n, owned);
    for (unsigned int i = 0; i < n; ++i)
      {
        dsp.add(i, i);
        dsp.add(n + (i + 1) % n, n + i);
      }
    K.reinit(owned, owned, dsp, MPI_COMM_WORLD);
    for (unsigned int i = 0; i < n; ++i)
      {
        K.set(i, i, 1.);
        K.set(n + (i + 1) % n, n + i, 1.);
      }
    K.compress(VectorOperation::insert);
  }

  /// diagonal I + rho S, or S alone if identity is false.
  void fill(TrilinosWrappers::SparseMatrix &K, const unsigned int n, const bool identity, const double rho)
  {
    const IndexSet         owned = complete_index_set(n);
    DynamicSparsityPattern dsp(n, n, owned);
    for (unsigned int i = 0; i < n; ++i)
      {
        dsp.add(i, i);
        dsp.add((i + 1) % n, i);
      }
    K.reinit(owned, owned, dsp, MPI_COMM_WORLD);
    for (unsigned int i = 0; i < n; ++i)
      {
        K.set(i, i, identity ? 1. : 0.);
        K.set((i + 1) % n, i, rho);
      }
    K.compress(VectorOperation::insert);
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  anvil::testing::Checks           check;
  const unsigned int               n     = 200;
  const IndexSet                   owned = complete_index_set(n);

  TrilinosWrappers::SparseMatrix I, shift, damped;
  fill(I, n, true, 0.);
  fill(shift, n, false, 1.);
  fill(damped, n, true, 0.97);
  anvil::IterativeSolverSettings settings; // cap 1000, 1e-8
  settings.restart = 28; // (the cycles below are counted for 28)
  const auto amg = anvil::build_amg(I, {}, settings);

  TrilinosWrappers::MPI::Vector b(owned, MPI_COMM_WORLD), x(owned, MPI_COMM_WORLD), r(owned, MPI_COMM_WORLD);
  b[0] = 1.;
  b.compress(VectorOperation::insert);

  // The step a solve that must fail gave up at (0: it did not fail).
  const auto failed_at = [&](const TrilinosWrappers::SparseMatrix &K, TrilinosWrappers::MPI::Vector &u,
                             const TrilinosWrappers::MPI::Vector &f, const TrilinosWrappers::PreconditionAMG &P) {
    try
      {
        anvil::solve_gmres(K, u, f, P, settings);
      }
    catch (const SolverControl::NoConvergence &e)
      {
        return std::max(1u, e.last_step);
      }
    return 0u;
  };

  // The cyclic shift: no progress, stopped after one cycle.
  unsigned int stopped = failed_at(shift, x, b, *amg);
  check(stopped > 0, "K = S: GMRES(28) does not converge");
  check(stopped >= settings.restart && stopped <= settings.restart + 1,
        "K = S: stopped at step " + std::to_string(stopped) + " (one cycle: 28), not at the cap");

  // I + 0.97 S: steady, slow; converges.
  x                  = 0;
  unsigned int steps = 0;
  try
    {
      steps = anvil::solve_gmres(damped, x, b, *amg, settings);
    }
  catch (const SolverControl::NoConvergence &e)
    {
      steps = e.last_step + 100000;
    }
  damped.vmult(r, x);
  r -= b;
  check(steps > 2 * settings.restart && steps <= 605,
        "K = I + 0.97 S: " + std::to_string(steps) + " iterations (bound 605, more than two cycles)");
  check(r.l2_norm() <= 1e-8 * b.l2_norm(), "K = I + 0.97 S: |b - K x| / |b| = " + std::to_string(r.l2_norm()));

  // I ⊕ S: halved in the first cycle, then stalled inside GCRO-DR's continuation.
  TrilinosWrappers::SparseMatrix split, I2;
  fill_split(split, n);
  fill(I2, 2 * n, true, 0.);
  const auto                    amg2 = anvil::build_amg(I2, {}, settings);
  const IndexSet                owned2 = complete_index_set(2 * n);
  TrilinosWrappers::MPI::Vector b2(owned2, MPI_COMM_WORLD), x2(owned2, MPI_COMM_WORLD);
  b2[0] = 1.;
  b2[n] = 0.3;
  b2.compress(VectorOperation::insert);
  stopped = failed_at(split, x2, b2, *amg2);
  check(stopped > 0, "K = I + S split: does not converge");
  check(stopped > settings.restart && stopped <= 5 * settings.restart,
        "K = I + S split: the continuation stopped at step " + std::to_string(stopped) +
          " (past the first cycle of 28, within 28 + 2 x 56), not at the cap of 1000");
  return check.finish();
}
