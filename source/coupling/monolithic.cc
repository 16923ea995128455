// The monolithic thermo-mechanical Newton: displacement and temperature solved
// together in every step (doc/monolithic.md): the Newton loop, its
// evaluations and line search. The class is in monolithic.h, its Jacobian in
// monolithic_jacobian.cc; the column colouring (dof_colouring.cc) and the
// block solve (block_solve.cc) are generic.
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>

#include <anvil/coupling/block_solve.h>

#include "monolithic.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    using Vector = TrilinosWrappers::MPI::Vector;
  } // namespace


  /// b_u = −R_u and f(T, u) at (u, T): mechanics assembled with the points at T.
  template <int dim>
  bool Monolithic<dim>::evaluate(const double t, const Vector &u, const Vector &T, Vector &b_u,
                                 Vector &f)
  {
    auto &mech = *this->problem->mechanics();
    auto &heat = *this->problem->heat();
    mech.set_displacement(u);
    heat.set_temperature(T);
    this->problem->point_temperatures_from_heat_field();
    if (!mech.assemble_system(false))
      return false;
    b_u = mech.get_system_rhs();
    heat.set_configuration(mech.get_dof_handler(), mech.displacement());
    if (contact_heat) // the exchange at this contact state (eq. 30–34)
      this->problem->contact_problem().prepare_heat(step_length);
    heat.implicit_residual(t, T, f);
    return true;
  }

  /// b_T = −R_T = Δt f − M (T − Tₙ) (eq. 26 by backward Euler), constrained rows 0; returns |M (T − Tₙ)|.
  template <int dim>
  double Monolithic<dim>::heat_residual(const Vector &T, const Vector &f, const double dt,
                                        Vector &b_T) const
  {
    const auto &heat = *this->problem->heat();
    Vector      change(T), M_change(T);
    change -= heat.owned_old_temperature();
    heat.mass_vmult(M_change, change);
    b_T = f;
    b_T *= dt;
    b_T -= M_change;
    for (const auto i : owned_T)
      if (heat.get_constraints().is_constrained(i))
        {
          b_T(i)      = 0;
          M_change(i) = 0;
        }
    b_T.compress(VectorOperation::insert);
    M_change.compress(VectorOperation::insert);
    return M_change.l2_norm();
  }

  template <int dim>
  unsigned int Monolithic<dim>::solve(const Vector &b_u, const Vector &b_T, Vector &du, Vector &dT)
  {
    const bool direct =
      linear_solver == "direct" || (linear_solver == "automatic" && n_u + n_T <= direct_limit);
    const auto          &mech  = *this->problem->mechanics();
    const RigidBodyModes modes = direct ? RigidBodyModes{} :
                                          rigid_body_modes(mech.get_mapping(), mech.get_dof_handler(),
                                                           &mech.displacement());
    const TwoFieldSystem system{jacobian, mech.get_system_matrix(), heat_block, owned_u,
                                owned_T,  owned,                    n_u,        &modes};
    const unsigned int   iterations = solve_two_field(system, b_u, b_T, du, dT, direct);
    this->problem->mechanics()->update_constraints().distribute(du);
    this->problem->heat()->get_constraints().distribute(dT);
    return iterations;
  }

  template <int dim>
  double Monolithic<dim>::line_search(const double t, const double dt, const Vector &u,
                                      const Vector &T, const Vector &du, const Vector &dT,
                                      const double scale_u, const double scale_T,
                                      const double merit_0)
  {
    // Backtracking on the normalised residual max(|R_u|/scale_u, |R_T|/scale_T)
    // (the convergence test's measure): halve until it decreases, at most 6
    // times. Not the mechanics' energy line search: from the first iterate
    // (the mechanics converged at Tₙ) δu · R_u is zero. Past the load maximum
    // the full coupled step can overshoot the neck.
    double alpha = 1;
    Vector ut(u), Tt(T), b(u), f(T), b_T(T);
    for (unsigned int ls = 0; ls < 6; ++ls, alpha *= 0.5)
      {
        ut = u;
        ut.add(alpha, du);
        Tt = T;
        Tt.add(alpha, dT);
        if (!evaluate(t, ut, Tt, b, f))
          continue;
        heat_residual(Tt, f, dt, b_T);
        const double merit = std::max(b.l2_norm() / scale_u, b_T.l2_norm() / scale_T);
        if (std::isfinite(merit) && merit < merit_0)
          break;
      }
    return std::max(alpha, 1. / 64);
  }

  template <int dim>
  StepReport<dim> Monolithic<dim>::advance(const double t_old, const double t_new)
  {
    auto                                       &p    = *this->problem;
    auto                                       &mech = *p.mechanics();
    auto                                       &heat = *p.heat();
    StepReport<dim>                             r;
    typename MechanicalProblem<dim>::StepResult m;
    const double                                dt    = t_new - t_old;
    const double                                start = MPI_Wtime();
    auto                                        fail  = [&](const std::string &why) {
      m.failure = why;
      r.mechanical_solves.push_back(m);
      r.mechanical_wall = MPI_Wtime() - start;
      p.revert();
      return r.fail(why);
    };

    heat.begin_step(t_old, t_new);
    step_length = dt;
    Vector T(heat.owned_old_temperature());
    heat.apply_dirichlet_values(t_new, T);
    // The first iterate: the mechanics converged alone at Tₙ (the isothermal
    // split's mechanical phase, with its line search): past the load maximum
    // the coupled Newton from the bare predictor needs many damped steps.
    // If that fails, the predictor with the boundary values' jump carried
    // into the body (the first iteration of the mechanics' own Newton).
    if (!p.solve_mechanics(t_old, t_new, false, r))
      {
        mech.revert_step();
        const bool has_jump = mech.begin_step(t_old, t_new);
        if (has_jump && !mech.predictor_update(m.linear_iterations))
          return fail(mech.failure_message());
      }
    heat.set_temperature(T);
    p.point_temperatures_from_heat_field();
    Vector              u(mech.owned_displacement()), b_u(u), du(u), f(T), b_T(T), dT(T);
    std::vector<double> error;
    double              r_u0 = 0, r_T0 = 0, heat_floor = 0;
    du = 0;
    dT = 0;
    for (unsigned int it = 0;; ++it)
      {
        if (!evaluate(t_new, u, T, b_u, f))
          return fail(mech.failure_message());
        const double r_u    = b_u.l2_norm();
        const double change = heat_residual(T, f, dt, b_T);
        const double r_T    = b_T.l2_norm();
        if (!std::isfinite(r_u) || !std::isfinite(r_T))
          return fail("the residual is not a number");
        if (it == 0)
          {
            r_u0 = r_u;
            r_T0 = r_T;
          }
        // Scales: the forces of the step; the heat the step stores (or, at
        // the first iterate, the heat that arrives in it).
        // Below 1e-12 of the heat content |M T| the heat residual is round-off
        // (a step that stores almost no heat cannot be measured against itself).
        if (it == 0)
          {
            Vector MT(T);
            heat.mass_vmult(MT, T);
            heat_floor = 1e-12 * MT.l2_norm();
          }
        const double scale_u = std::max(mech.force_scale(), r_u0);
        const double scale_T = std::max(change, r_T0);
        const double e_u     = r_u / std::max(scale_u, 1e-300);
        const double e_T     = r_T / std::max(scale_T, 1e-300);
        error.push_back(std::max(e_u, e_T));
        std::ostringstream line;
        line << "    monolithic " << std::setw(2) << it << ": |R_u| " << std::scientific
             << std::setprecision(2) << r_u << " N (" << e_u << " of " << scale_u << "), |R_T| "
             << r_T << " mJ (" << e_T << " of " << scale_T << ")";
        // Contraction order log(e_k/e_k-1)/log(e_k-1/e_k-2), and e_k/e_k-1²,
        // bounded when the convergence is quadratic.
        const std::size_t k = error.size() - 1;
        if (k >= 1)
          line << ", e/e_prev^2 " << error[k] / (error[k - 1] * error[k - 1]);
        if (k >= 2 && error[k] < error[k - 1] && error[k - 1] < error[k - 2])
          line << ", order " << std::fixed << std::setprecision(2)
               << std::log(error[k] / error[k - 1]) / std::log(error[k - 1] / error[k - 2]);
        m.residuals.push_back(r_u);
        r.thermal_residuals.push_back(r_T);
        // Updates at the round-off of the values: the residuals sit on their floor.
        const bool stagnated = it > 0 && error.back() <= 1e3 * tolerance &&
                               du.linfty_norm() <= 1e-12 * std::max(1.0, u.linfty_norm()) &&
                               dT.linfty_norm() <= 1e-12 * T.linfty_norm();
        const bool converged =
          ((e_u <= tolerance || r_u <= p.mechanics_parameters().absolute_residual_tolerance) &&
           (e_T <= tolerance || r_T <= heat_floor)) ||
          stagnated;
        line << (converged ? "  converged" : "");
        p.log() << line.str() << std::endl;
        if (converged)
          break;
        if (it >= max_iterations)
          return fail("the monolithic Newton did not converge in " + std::to_string(it) +
                      " iterations (|R_u| = " + Utilities::to_string(r_u, 3) +
                      " N, |R_T| = " + Utilities::to_string(r_T, 3) + " mJ)");
        if (!assemble_jacobian(t_new, dt, u, T, b_u, f))
          return fail(mech.failure_message());
        if (check_tangent)
          print_tangent_check(t_new, dt, u, T);
        du = 0;
        dT = 0;
        try
          {
            m.linear_iterations += solve(b_u, b_T, du, dT);
          }
        catch (const std::exception &)
          {
            return fail("the linear solver failed on the monolithic system");
          }
        const double alpha = error.back() > 1e-4 ?
                               line_search(t_new, dt, u, T, du, dT, std::max(scale_u, 1e-300),
                                           std::max(scale_T, 1e-300), error.back()) :
                               1.;
        u.add(alpha, du);
        T.add(alpha, dT);
        m.increments.push_back(alpha * du.l2_norm());
        r.thermal_increments.push_back(alpha * dT.linfty_norm());
        m.line_search_steps.push_back(alpha);
        m.iterations = it + 1;
      }
    m.converged = true;
    // The state of the converged iterate is the last evaluation's: points,
    // heat sources, configuration. T becomes the heat problem's solution.
    heat.accept_temperature(T, t_old, t_new);
    r.thermal.converged            = true;
    r.thermal.internal_steps       = 1;
    r.thermal.nonlinear_iterations = m.iterations;
    r.thermal.linear_solves        = m.iterations;
    r.mechanical_solves.push_back(m);
    r.mechanical_wall = MPI_Wtime() - start;
    const auto &contact = p.contact_problem();
    if (!contact.empty() && contact.last_max_penetration() > contact.maximum_penetration())
      return fail("contact penetration " + Utilities::to_string(contact.last_max_penetration(), 3) +
                  " mm exceeds Contact/Maximum penetration = " +
                  Utilities::to_string(contact.maximum_penetration(), 3) + " mm");
    const double limit = p.mechanics_parameters().maximum_plastic_increment;
    if (limit > 0 && mech.largest_plastic_increment() > limit)
      return fail("the plastic strain grew by " +
                  Utilities::to_string(mech.largest_plastic_increment(), 3) +
                  " at a point (limit " + Utilities::to_string(limit) + ")");
    return r;
  }

  ANVIL_REGISTER_COUPLING_SCHEME(
    Monolithic, "monolithic",
    "displacement and temperature solved together by one Newton loop per step, backward Euler "
    "for the heat equation, the full coupled tangent (the seed's reference system, §2.2; "
    "doc/monolithic.md).")
} // namespace anvil

