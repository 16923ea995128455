#pragma once

// The one place that knows SUNDIALS exists (see arkode_integrator.cc).

#include <deal.II/lac/trilinos_vector.h>

#include <string>

namespace anvil
{
  namespace thermal
  {
    using Vector = dealii::TrilinosWrappers::MPI::Vector;

    /**
     * A stiff system M ẏ = f(t, y) with a constant mass matrix M, as ARKode's
     * implicit part sees it. Every method returns 0 on success, > 0 for a
     * recoverable failure (ARKode retries with a smaller step), < 0 fatal;
     * exceptions are caught by the integrator (SolverControl::NoConvergence
     * counts as recoverable).
     */
    class ImplicitSystem
    {
    public:
      virtual ~ImplicitSystem() = default;
      virtual void reinit_vector(Vector &v) const = 0;
      virtual int  rhs(double t, const Vector &y, Vector &f) = 0;
      /// Whether rhs(t, y) is the same for every t of the current call (the
      /// linear DIRK loop then evaluates f(·, y) once per step, not per stage).
      virtual bool rhs_independent_of_time() const { return false; }
      /// Assemble J = ∂f/∂y at (t, y).
      virtual int  setup_jacobian(double t, const Vector &y) = 0;
      virtual int  jacobian_vmult(const Vector &v, Vector &Jv) = 0;
      /// Build (and factor) an approximation of M − γJ with the last J.
      virtual int  setup_newton_matrix(double gamma) = 0;
      /// x ≈ (M − γJ)⁻¹ b with the matrix of the last setup_newton_matrix;
      /// returns the number of inner iterations (≥ 1) or a negative error.
      virtual int  solve_newton_matrix(Vector &x, const Vector &b) = 0;
      /// Whether solve_newton_matrix is (M − γJ)⁻¹ itself, to round-off, for
      /// this γ and the J of jacobian_vmult (a factorisation of that very
      /// matrix): then a Newton system is one solve, no Krylov iteration.
      virtual bool newton_matrix_is_exact(double /*gamma*/) const { return false; }
      /// Whether setup_exact_newton_matrix can factorise M − γJ itself, every
      /// coupling of J in it (a direct solver): the linear DIRK loop needs it.
      virtual bool can_solve_exactly() const { return false; }
      /// Build and factor M − γJ for this very γ (setup_newton_matrix may keep
      /// a factorisation of a nearby γ as a preconditioner).
      virtual int  setup_exact_newton_matrix(double gamma) { return setup_newton_matrix(gamma); }
      virtual int  mass_vmult(const Vector &v, Vector &Mv) = 0;
      /// x = M⁻¹ b to the absolute residual tolerance @p tol.
      virtual int  solve_mass(Vector &x, const Vector &b, double tol) = 0;
    };

    struct IntegratorSettings
    {
      unsigned int order                    = 3; // DIRK: 2, 3, 4 or 5; 1: backward Euler
      bool         linear                   = false; // f linear in y: one Newton iteration per stage
      /// With linear: J = ∂f/∂y does not depend on t, so ARKode sets up the
      /// Newton matrix only when γ changes, not at every stage.
      bool         jacobian_constant        = false;
      /// With linear, jacobian_constant and a system that can_solve_exactly():
      /// anvil's own DIRK loop on ARKode's table (dirk_linear.h), one linear
      /// solve per stage and none of ARKode's Newton machinery. False: ARKode.
      bool         linear_stages            = true;
      double       relative_tolerance       = 1e-6;
      double       absolute_tolerance       = 1e-6;
      double       fixed_step_size          = 0; // 0: adaptive
      /// 0: ARKode's estimate; else the step the last call found possible
      /// (IntegratorStatistics::next_step): the call starts with the span cut
      /// into equal steps near it (see integrate).
      double       initial_step_size        = 0;
      unsigned int max_internal_steps       = 5000;
      unsigned int max_nonlinear_iterations = 10;
    };

    struct IntegratorStatistics
    {
      bool          success = false;
      std::string   failure;
      unsigned long steps = 0, attempts = 0, error_test_failures = 0, nonlinear_iterations = 0,
                    nonlinear_failures = 0, linear_setups = 0, linear_solves = 0,
                    linear_iterations = 0, rhs_evaluations = 0, mass_solves = 0;
      double last_step = 0;
      /// The largest accepted internal step: where the next call should start
      /// (last_step is usually cut short by the end time, by any amount).
      double largest_step = 0;
      /// Where the next call should start: ARKode's proposal after the last
      /// step (its error controller's), or the largest step if that is larger
      /// (a last step cut to a sliver by the end time proposes too little).
      double next_step = 0;
    };

    /**
     * Integrate @p system from (t0, y) to t1 with ARKode's implicit DIRK of
     * the given order (SUNDIALS' default table for that order), Newton with
     * our own linear solver (GMRES on ARKode's exact M − γJ, preconditioned
     * by system.solve_newton_matrix), and our own mass solver. A fresh ARKode
     * object per call, i.e. reset at t0: operators may change between calls.
     * @p y holds y(t0) on entry and y(t1) on successful return. Linear
     * problems (settings.linear_stages) go to integrate_linear_dirk instead.
     */
    IntegratorStatistics integrate(ImplicitSystem &system, Vector &y, double t0, double t1,
                                   const IntegratorSettings &settings);
  } // namespace thermal
} // namespace anvil
