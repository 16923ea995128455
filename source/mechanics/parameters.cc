// The parameters of MechanicalProblem: declared and parsed from the Mechanics subsection.
#include <deal.II/base/parameter_handler.h>

#include <anvil/core/dof_limit.h>
#include <anvil/core/input_error.h>
#include <anvil/core/expression.h>
#include <anvil/core/instantiate.h>
#include <anvil/core/scene.h>
#include <anvil/mechanics/linear_solver.h>
#include <anvil/mechanics/mechanical_problem.h>

#include <stdexcept>
#include <string>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  void MechanicalProblem<dim>::Parameters::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Mechanics");
    prm.declare_entry("Polynomial degree", "1", Patterns::Integer(1, 2),
                      "Degree of the displacement elements: 1 (Q1) or 2 (Q2).");
    prm.declare_entry("Element", "F-bar", Patterns::Selection("F-bar|standard"),
                      "F-bar: the dilatation of each Q1 cell is its centre's (de Souza Neto et al. "
                      "1996), so isochoric plastic flow does not lock (seed sec. 3.1: constant "
                      "pressure elements); standard: plain displacement elements (Q1 locks in "
                      "plastic flow; Q2 with Polynomial degree = 2).");
    prm.declare_entry("Two-dimensional model", "plane strain",
                      Patterns::Selection("plane strain|axisymmetric"),
                      "For Dimension = 2: plane strain, or axisymmetric about the y axis with x the "
                      "radius (x >= 0; hoop strain u_r/r; forces are per full ring, 2 pi r).");
    prm.declare_entry("Objective rate", "Jaumann", Patterns::Selection(objective_rate_selection()),
                      "Objective stress rate of the incremental update (all materials): Jaumann "
                      "(the seed's eq. 9; shear stress oscillates past a shear of pi/2), "
                      "Green-Naghdi (polar rotation, Dienes 1979) or logarithmic (log spin, Xiao, "
                      "Bruhns & Meyers 1997: hypoelasticity integrates to Hencky's model; the "
                      "choice for large shear). doc/mechanics.md, Objective rates.");
    prm.declare_entry("Temperature", "293", Patterns::Double(0),
                      "Uniform temperature in K of a scene without a temperature field: the "
                      "material laws are evaluated at it.");
    prm.declare_entry("Gravity", "", Patterns::Anything(),
                      "Body force per unit mass as a vector 'gx, gy[, gz]' in mm/s^2 (e.g. 0, -9810); "
                      "empty: none.");
    prm.declare_entry("Maximum plastic strain increment", "0", Patterns::Double(0),
                      "Cut the step back if any point's equivalent plastic strain grows by more than "
                      "this in one step (dimensionless; 0: no limit).");
    prm.enter_subsection("Dynamics");
    prm.declare_entry("Type", "quasi-static", Patterns::Selection("quasi-static|implicit"),
                      "quasi-static: no inertia; implicit: generalized-alpha time integration of "
                      "M a + f_int = f_ext (Chung & Hulbert 1993) with force averaging.");
    prm.declare_entry("Spectral radius", "1", Patterns::Double(0, 1),
                      "rho_inf in [0, 1]: 1 conserves energy (trapezoidal rule, the seed's mid-point "
                      "member); smaller values damp the highest frequencies (0.8 is common).");
    prm.declare_entry("Mass", "consistent", Patterns::Selection("consistent|lumped"),
                      "Consistent or row-sum lumped mass matrix.");
    prm.declare_entry("Initial velocity", "", Patterns::Anything(),
                      "'ux = expr, uy = expr[, uz = expr]' in mm/s, expressions in x, y, z (mm); "
                      "empty: at rest. An impact is an initial velocity.");
    prm.leave_subsection();
    prm.enter_subsection("Newton");
    prm.declare_entry("Maximum iterations", "15", Patterns::Integer(1),
                      "Newton iterations per time step before the step is cut back.");
    prm.declare_entry("Residual tolerance", "1e-8", Patterns::Double(0),
                      "Relative residual tolerance: |R| <= tol * max(|f_int|, |f_ext|, |M a|, |R_0|), R_0 the first residual of the step (dimensionless).");
    prm.declare_entry("Absolute residual tolerance", "1e-12", Patterns::Double(0),
                      "Residual norm in N below which a step is converged whatever the scale.");
    prm.declare_entry("Displacement tolerance", "1e-8", Patterns::Double(0),
                      "Relative increment tolerance: the next correction, estimated as the last one "
                      "times the residual's contraction, <= tol * |Δu of the step| (dimensionless).");
    prm.declare_entry("Extrapolate", "true", Patterns::Bool(),
                      "Start each step from the last step's increment scaled to the new step "
                      "(linear extrapolation in time) instead of the committed configuration.");
    prm.declare_entry("Check tangent", "false", Patterns::Bool(),
                      "Compare the assembled tangent with central finite differences of the "
                      "residual at every Newton iteration and print the relative error (slow; "
                      "for debugging new material laws).");
    prm.declare_entry("Absolute displacement tolerance", "0", Patterns::Double(0),
                      "Correction norm in mm below which the increment test passes whatever the "
                      "step (0: only the relative test and the round-off floor).");
    prm.declare_entry("Line search", "true", Patterns::Bool(),
                      "Shorten the Newton update when the energy norm s(α) = δu · R(u + α δu) "
                      "(Crisfield) is not reduced enough: α from the secant root of s, within "
                      "[0.1, 1], at most 5 trials; also when an element inverts (α halved).");
    prm.declare_entry("Line search bound far from convergence", "0.8", Patterns::Double(0, 1),
                      "b while |R| > 0.1 |R_0| of the step: the line search keeps a step length α "
                      "when |s(α)| <= b |s(0)|, s(α) = δu · R(u + α δu) (Crisfield's energy norm); "
                      "nearer convergence b = 0.8. 0.1 cuts the overshooting updates of plastic "
                      "hinges (tube_impact.prm); it costs iterations on elastic large rotations, "
                      "whose first residuals grow although the full step is good (dimensionless, "
                      "(0, 1]).");
    prm.leave_subsection();
    prm.enter_subsection("Linear solver");
    prm.declare_entry("Type", "automatic", Patterns::Selection("automatic|direct|iterative"),
                      "direct: sparse LU (Amesos KLU); iterative: GMRES with algebraic multigrid "
                      "(Trilinos ML); automatic: direct below 'Direct solver limit' DoFs.");
    prm.declare_entry("Tolerance", "1e-10", Patterns::Double(0),
                      "Relative tolerance of the iterative solver (dimensionless).");
    prm.declare_entry("Maximum iterations", "1000", Patterns::Integer(1),
                      "Iterations of the iterative solver before the step is cut back.");
    prm.declare_entry("GMRES restart", std::to_string(default_gmres_restart), Patterns::Integer(1, 1000),
                      "GMRES iterations before a restart (it keeps up to that many Krylov vectors + 2, "
                      "8 bytes per DoF each, allocated as the solve needs them; 60: the 2D 256² plastic "
                      "F-bar block's onset solve 131 -> 63 iterations, solves below 28 unchanged; "
                      "doc/linear_solver.md, session 19).");
    // The automatic rule is choose_preconditioner() in linear_solver.cc;
    // the figures: doc/linear_solver.md, "Session 22: the default" and "Session 23".
    prm.declare_entry("Preconditioner", "automatic", Patterns::Selection("automatic|AMG|geometric"),
                      "The iterative solver's preconditioner. AMG: smoothed-aggregation algebraic "
                      "multigrid (the AMG entries below). geometric: Chebyshev on the mesh (its products and "
                      "the cycle's residuals on single-precision copies of the levels by nodal blocks, "
                      "GMRES's own products in double) and a coarse "
                      "correction on the Q1 space of the mesh one refinement coarser (Galerkin product, "
                      "itself smoothed and corrected the same way, one ML V-cycle with the AMG entries "
                      "below on the coarsest level); Q1 only, "
                      "on a mesh with a coarser level: Geometry/Global refinements >= 1 (any bodies, "
                      "gmsh meshes, curved or distorted cells), or one unrefined block of equal cells "
                      "with even subdivisions; another mesh is refused. "
                      "The number of levels is automatic: each coarse level of at least 14 000 rows is "
                      "coarsened once more while the mesh allows it (another generation of parents, or "
                      "even subdivisions of one unrefined block): 1 M DoFs get three levels, up to 30^3 "
                      "cells two. The coarsest level takes one ML V-cycle, or two or three (ML applied "
                      "again to its residual) when it has at least 14 000 rows and the mesh cannot "
                      "coarsen it further (1 M DoFs: three; 30.6 -> 28.0 Krylov iterations per solve). "
                      "automatic: geometric in 3D where it applies, else AMG (2D, Q2, a mesh without a "
                      "coarser level, AMG package = MueLu, AMG rebuild growth > 0); the log names the "
                      "choice. On every 3D scene shipped or tested, above the direct solver's limit, "
                      "geometric took 1-51 % less CPU and 5-53 % less peak memory than AMG (plastic "
                      "F-bar block 30^3: 128 -> 96 CPU s, 9393 -> 4636 B/DoF, 20.8 -> 26.6 Krylov "
                      "iterations per solve); in 2D its Krylov count grows with the mesh (plastic "
                      "block 256^2: 50.2 against 29.5, +38 % CPU). doc/linear_solver.md, session 22.");
    prm.declare_entry("AMG rebuild growth", "0", Patterns::Double(0),
                      "0: build the AMG hierarchy for every solve. g > 0: keep it across Newton "
                      "iterations and steps, giving the kept one g times the Krylov iterations of "
                      "its first solve before a fresh one continues (pays on elastic and contact "
                      "scenes, not on spreading plasticity: doc/linear_solver.md).");
    prm.declare_entry("AMG smoother degree", "automatic", Patterns::Anything(),
                      "Degree of the Chebyshev smoother on every level of the AMG hierarchy "
                      "(pre and post), 1 to 10, or automatic: with the isochoric modes 8 in 2D and 6 in 3D, else 2. "
                      "Higher degrees buy Krylov iterations at more work per V-cycle "
                      "(doc/linear_solver.md).");
    prm.declare_entry("AMG Chebyshev ratio", "automatic", Patterns::Anything(),
                      "The Chebyshev smoother damps the eigenvalues of diag(K)^-1 K between "
                      "lambda_max / ratio and lambda_max: a number > 1, or automatic: 100 with the "
                      "isochoric modes (it then reaches the low-energy isochoric fields of plastic "
                      "flow), else 10 (deal.II's). Dimensionless.");
    prm.declare_entry("AMG isochoric modes", "automatic", Patterns::Selection("automatic|true|false"),
                      "Add the linear isochoric fields u = G (x - c), G symmetric and traceless "
                      "(2D: 2, 3D: 5), to the rigid-body modes AMG's coarse spaces are built on. "
                      "They are the low-energy fields of nearly incompressible (plastic) tangents; "
                      "they make the coarse levels denser (3D: 11 instead of 6 columns per "
                      "aggregate). automatic: for a solve where some material point has flowed "
                      "plastically (plastic F-bar blocks: 2D and 3D <= 30 Krylov iterations per "
                      "solve, doc/linear_solver.md, session 17).");
    prm.declare_entry("AMG aggregation threshold", "0.02", Patterns::Double(0, 1),
                      "Strength of connection below which AMG's aggregation drops a coupling "
                      "(ML's 'aggregation: threshold', MueLu's drop tolerance; dimensionless).");
    prm.declare_entry("AMG coarse size", "2000", Patterns::Integer(1),
                      "Rows below which the AMG hierarchy stops coarsening and solves by KLU.");
    prm.declare_entry("AMG cycle", "automatic", Patterns::Selection("automatic|V|W"),
                      "How a preconditioner application visits the AMG hierarchy's levels: V (each "
                      "coarse level once), W (twice per visit of the finer level), or automatic: W "
                      "in 2D with the isochoric modes (plastic flow) from 100000 DoFs, else V. 2D "
                      "plastic F-bar block, Krylov iterations per solve V against W: 256^2 28.6 / 20.9 "
                      "at the same CPU, 512^2 37.4 / 27.7 at 14 % less; below 10^5 DoFs and in 3D W "
                      "costs more than it saves (doc/linear_solver.md, session 25).");
    prm.declare_entry("AMG prolongator", "smoothed", Patterns::Selection("smoothed|plain"),
                      "smoothed: smoothed aggregation (fewest Krylov iterations). plain: the "
                      "tentative prolongator alone, for large 3D problems short of memory: 3D "
                      "plastic F-bar 30^3 with the automatic settings 9835 -> 6627 B/DoF at 20.7 -> "
                      "36.9 Krylov iterations per solve (doc/memory.md, session 18).");
    prm.declare_entry("AMG package", "ML", Patterns::Selection("ML|MueLu"),
                      "The algebraic multigrid library of the iterative solver: Trilinos ML "
                      "(through deal.II) or MueLu (Tpetra; libanvil-muelu.so, loaded only when "
                      "chosen), both smoothed aggregation on the same near-null space and smoother. "
                      "On plastic F-bar blocks MueLu needs 5-14 % fewer Krylov iterations at about the "
                      "same CPU and 8-12 % more peak memory (K is copied into Tpetra). "
                      "doc/linear_solver.md, session 16.");
    prm.declare_entry("Direct solver limit", "measured", Patterns::Anything(),
                      "Number of DoFs up to which 'automatic' chooses the direct solver; measured: "
                      "where KLU and GMRES + AMG cost the same per Newton iteration on the plastic "
                      "F-bar benchmark, " + std::to_string(measured_direct_solver_limit(2)) +
                        " in 2D, " + std::to_string(measured_direct_solver_limit(3)) +
                        " in 3D (contrib/bench/solver_scaling.py, doc/linear_solver.md).");
    prm.declare_entry("Direct solver", "auto", Patterns::Selection("auto|klu|band"),
                      "The direct solver's factorisation on one process (several processes: KLU). "
                      "klu: sparse LU (KLU); band: LU with partial pivoting in the band of a "
                      "reverse Cuthill-McKee numbering; auto: the band where its estimated work "
                      "is below KLU's (small 2D meshes; doc/linear_solver.md, 'Band LU').");
    prm.leave_subsection();
    prm.leave_subsection();
  }

  template <int dim>
  void MechanicalProblem<dim>::Parameters::parse_parameters(ParameterHandler &prm, const Scene &scene)
  {
    prm.enter_subsection("Mechanics");
    polynomial_degree = prm.get_integer("Polynomial degree");
    f_bar             = prm.get("Element") == "F-bar";
    axisymmetric      = dim == 2 && prm.get("Two-dimensional model") == "axisymmetric";
    temperature       = prm.get_double("Temperature");
    objective_rate    = objective_rate_from_string(prm.get("Objective rate"));
    if (!(temperature > 0))
      scene.fail("Mechanics/Temperature", "= " + std::to_string(temperature) +
                                            " K: expected an absolute temperature > 0 K");
    gravity           = prm.get("Gravity");
    maximum_plastic_increment = prm.get_double("Maximum plastic strain increment");
    prm.enter_subsection("Dynamics");
    dynamic          = prm.get("Type") == "implicit";
    spectral_radius  = prm.get_double("Spectral radius");
    lumped_mass      = prm.get("Mass") == "lumped";
    initial_velocity = prm.get("Initial velocity");
    prm.leave_subsection();
    for (const auto &assignment : split_outside_parentheses(initial_velocity, ','))
      {
        if (assignment.empty())
          continue;
        const std::string path = "Mechanics/Dynamics/Initial velocity";
        const auto        eq   = assignment.find('=');
        const std::string c    = eq == std::string::npos ? "" : trim(assignment.substr(0, eq));
        bool              ok   = false;
        for (unsigned int d = 0; d < dim; ++d)
          ok = ok || c == std::string("u") + "xyz"[d];
        if (!ok)
          scene.fail(path, "'" + assignment + "' should be " +
                             (dim == 2 ? "ux = expr or uy = expr" : "ux, uy or uz = expr") + " (mm/s)");
        parse_expression<dim>(trim(assignment.substr(eq + 1)), scene, path);
      }
    // Check the vectors now (one-line errors before any work).
    if (!gravity.empty())
      {
        const auto parts = split_outside_parentheses(gravity, ',');
        bool       ok    = parts.size() == dim;
        for (const auto &x : parts)
          try
            {
              std::size_t used = 0;
              std::stod(x, &used);
              ok = ok && used == x.size();
            }
          catch (...)
            {
              ok = false;
            }
        if (!ok)
          scene.fail("Mechanics/Gravity", "= '" + gravity + "': expected " + std::to_string(dim) +
                                            " numbers 'gx, gy" + (dim == 3 ? ", gz'" : "'") + " in mm/s^2");
      }
    prm.enter_subsection("Newton");
    max_iterations              = prm.get_integer("Maximum iterations");
    residual_tolerance          = prm.get_double("Residual tolerance");
    absolute_residual_tolerance = prm.get_double("Absolute residual tolerance");
    displacement_tolerance      = prm.get_double("Displacement tolerance");
    absolute_displacement_tolerance = prm.get_double("Absolute displacement tolerance");
    line_search                 = prm.get_bool("Line search");
    line_search_far_bound       = prm.get_double("Line search bound far from convergence");
    AssertThrow(line_search_far_bound > 0,
                ExcMessage("Mechanics/Newton/Line search bound far from convergence must be > 0"));
    check_tangent               = prm.get_bool("Check tangent");
    extrapolate                 = prm.get_bool("Extrapolate");
    prm.leave_subsection();
    prm.enter_subsection("Linear solver");
    linear_solver         = prm.get("Type");
    linear_tolerance      = prm.get_double("Tolerance");
    linear_max_iterations = prm.get_integer("Maximum iterations");
    gmres_restart         = prm.get_integer("GMRES restart");
    preconditioner        = prm.get("Preconditioner");
    amg_rebuild_growth    = prm.get_double("AMG rebuild growth");
    // "automatic" (0 here) or a number in [low, high]; else a one-line error.
    const auto automatic_or = [&](const char *entry, const double low, const double high) {
      const std::string value = prm.get(entry);
      if (value == "automatic")
        return 0.;
      try
        {
          std::size_t  used = 0;
          const double x    = std::stod(value, &used);
          if (used == value.size() && x >= low && x <= high)
            return x;
        }
      catch (const std::exception &)
        {
        }
      scene.fail(std::string("Mechanics/Linear solver/") + entry,
                 "= '" + value + "': expected 'automatic' or a number in [" + dealii::Utilities::to_string(low) +
                   ", " + dealii::Utilities::to_string(high) + "]");
    };
    amg_smoother_degree = static_cast<unsigned int>(automatic_or("AMG smoother degree", 1, 10));
    if (amg_smoother_degree != 0 && prm.get("AMG smoother degree") != std::to_string(amg_smoother_degree))
      scene.fail("Mechanics/Linear solver/AMG smoother degree",
                 "= '" + prm.get("AMG smoother degree") + "': expected 'automatic' or an integer in [1, 10]");
    amg_chebyshev_ratio       = automatic_or("AMG Chebyshev ratio", 1.0001, 1e6);
    amg_isochoric_modes       = prm.get("AMG isochoric modes");
    amg_aggregation_threshold = prm.get_double("AMG aggregation threshold");
    amg_coarse_size           = prm.get_integer("AMG coarse size");
    amg_cycle                 = prm.get("AMG cycle");
    amg_plain_aggregation     = prm.get("AMG prolongator") == "plain";
    amg_package           = prm.get("AMG package");
    direct_solver         = prm.get("Direct solver");
    direct_solver_limit   = parse_dof_limit(prm.get("Direct solver limit"), measured_direct_solver_limit(dim), scene,
                                          "Mechanics/Linear solver/Direct solver limit");
    prm.leave_subsection();
    prm.leave_subsection();
    if (f_bar && polynomial_degree != 1)
      scene.fail("Mechanics/Element", "is F-bar, which is a Q1 element: use Element = standard "
                                      "with Polynomial degree = 2");
    if (dim == 3 && prm.get("Dimension") == "3")
      axisymmetric = false;
  }

#define INSTANTIATE(dim) template struct MechanicalProblem<dim>::Parameters;
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
