#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_solver.h>

#include <anvil/coupling/block_solve.h>

namespace anvil
{
  using namespace dealii;
  using Vector = TrilinosWrappers::MPI::Vector;

  namespace
  {
    /// Block-diagonal preconditioner: one AMG per field.
    struct BlockAMG
    {
      BlockAMG(const TwoFieldSystem &s, const Vector &u_layout, const Vector &T_layout)
        : s(s)
        , src_u(u_layout)
        , src_T(T_layout)
        , dst_u(u_layout)
        , dst_T(T_layout)
      {}
      const TwoFieldSystem             &s;
      std::unique_ptr<TrilinosWrappers::PreconditionAMG> amg_u;
      TrilinosWrappers::PreconditionAMG                  amg_T;
      mutable Vector                    src_u, src_T, dst_u, dst_T;
      void                              vmult(Vector &dst, const Vector &src) const
      {
        for (const auto i : s.owned_u)
          src_u(i) = src(i);
        for (const auto i : s.owned_T)
          src_T(i) = src(s.n_u + i);
        src_u.compress(VectorOperation::insert);
        src_T.compress(VectorOperation::insert);
        amg_u->vmult(dst_u, src_u);
        amg_T.vmult(dst_T, src_T);
        for (const auto i : s.owned_u)
          dst(i) = dst_u(i);
        for (const auto i : s.owned_T)
          dst(s.n_u + i) = dst_T(i);
        dst.compress(VectorOperation::insert);
      }
    };
  } // namespace

  unsigned int solve_two_field(const TwoFieldSystem &s, const Vector &b_u, const Vector &b_T,
                               Vector &x_u, Vector &x_T, const bool direct)
  {
    const auto comm = b_u.get_mpi_communicator();
    Vector     b(s.owned, comm), x(s.owned, comm);
    for (const auto i : s.owned_u)
      b(i) = b_u(i);
    for (const auto i : s.owned_T)
      b(s.n_u + i) = b_T(i);
    b.compress(VectorOperation::insert);
    unsigned int iterations = 1;
    if (direct)
      {
        SolverControl                  control(1, 0);
        TrilinosWrappers::SolverDirect solver(control, TrilinosWrappers::SolverDirect::AdditionalData(
                                                         false, "Amesos_Klu"));
        solver.solve(s.matrix, x, b);
      }
    else
      {
        BlockAMG p(s, b_u, b_T);
        // The displacement block as the mechanics' own solve preconditions
        // it (doc/linear_solver.md): rigid-body modes, nodes aggregated.
        IterativeSolverSettings settings_u;
        if (s.u_modes && s.u_modes->node_blocks)
          settings_u.components = s.u_modes->components;
        p.amg_u = build_amg(s.K_uu, s.u_modes ? s.u_modes->modes : std::vector<std::vector<double>>(),
                            settings_u);
        TrilinosWrappers::PreconditionAMG::AdditionalData data_T;
        data_T.elliptic        = true;
        data_T.smoother_sweeps = 2;
        p.amg_T.initialize(s.K_TT, data_T);
        SolverControl       control(1000, 1e-10 * b.l2_norm());
        SolverGMRES<Vector> gmres(control, SolverGMRES<Vector>::AdditionalData(50));
        gmres.solve(s.matrix, x, b, p);
        iterations = control.last_step();
      }
    for (const auto i : s.owned_u)
      x_u(i) = x(i);
    for (const auto i : s.owned_T)
      x_T(i) = x(s.n_u + i);
    x_u.compress(VectorOperation::insert);
    x_T.compress(VectorOperation::insert);
    return iterations;
  }
} // namespace anvil
