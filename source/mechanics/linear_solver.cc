// The linear solve of a Newton iteration of MechanicalProblem: sparse LU, or
// GMRES with smoothed-aggregation AMG on the rigid-body modes (amg_solver.cc)
// or with the two-level cycle on the geometric coarse space
// (geometric_coarse_space.h), chosen by Preconditioner = automatic.
#include <deal.II/base/utilities.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/vector_memory.h>
#include <deal.II/lac/trilinos_precondition.h>

#include <anvil/core/band_factorization.h>
#include <anvil/core/input_error.h>
#include <anvil/core/instantiate.h>
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <sstream>
#include <anvil/mechanics/linear_solver.h>
#include <anvil/mechanics/mechanical_problem.h>

#include "geometric_coarse_space.h"

DEAL_II_DISABLE_EXTRA_DIAGNOSTICS
#include <Epetra_CrsMatrix.h>
#include <Epetra_MultiVector.h>
#include <Teuchos_ParameterList.hpp>
DEAL_II_ENABLE_EXTRA_DIAGNOSTICS

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// Diagnostics (one process): ANVIL_KRYLOV_DUMP=folder writes every
    /// iterative solve's system to folder/system_<k>.bin: int n, int entries,
    /// int offsets[n + 1], int columns (global), double values, double b[n],
    /// int modes, the modes (rigid-body then isochoric, n doubles each), so
    /// that contrib/bench/amg_replay.cc can try preconditioners on one solve.
    void dump_system(const std::string &folder, const Epetra_CrsMatrix &K, const TrilinosWrappers::MPI::Vector &b,
                     const std::vector<std::vector<double>> &modes)
    {
      static int count = 0;
      int       *offsets = nullptr, *columns = nullptr;
      double    *values  = nullptr;
      AssertThrow(K.Comm().NumProc() == 1 && K.ExtractCrsDataPointers(offsets, columns, values) == 0,
                  ExcMessage("ANVIL_KRYLOV_DUMP: one process only"));
      const int        n = K.NumMyRows(), entries = offsets[n];
      std::vector<int> global(entries);
      for (int k = 0; k < entries; ++k)
        global[k] = K.ColMap().GID(columns[k]);
      FILE *const f = std::fopen((folder + "/system_" + std::to_string(count++) + ".bin").c_str(), "wb");
      AssertThrow(f, ExcMessage("ANVIL_KRYLOV_DUMP: cannot write to " + folder));
      const int m = modes.size();
      std::fwrite(&n, sizeof(int), 1, f);
      std::fwrite(&entries, sizeof(int), 1, f);
      std::fwrite(offsets, sizeof(int), n + 1, f);
      std::fwrite(global.data(), sizeof(int), entries, f);
      std::fwrite(values, sizeof(double), entries, f);
      std::fwrite(b.trilinos_vector()[0], sizeof(double), n, f);
      std::fwrite(&m, sizeof(int), 1, f);
      for (const auto &mode : modes)
        std::fwrite(mode.data(), sizeof(double), n, f);
      std::fclose(f);
    }

    /**
     * What the preconditioner choice knows of the current mesh: whether the
     * geometric coarse space can be built on it (check_geometric_coarse_space(),
     * collective: a loop over the cells and a few reductions), and whether
     * the choice has been written to the log. Kept per dimension until the
     * triangulation changes or goes (its signals, as geometric_coarse_space.cc's
     * KeptSpace) or another DoFHandler solves.
     */
    struct MeshRecord
    {
      const void                        *dof_handler = nullptr;
      int                                geometric   = -1; // -1: not tested; 0: refused; 1: accepted
      bool                               reported    = false;
      boost::signals2::scoped_connection change, clear;
    };

    template <int dim>
    MeshRecord &mesh_record(const DoFHandler<dim> &dof_handler)
    {
      static MeshRecord record;
      // Collective: every process forgets together (one reduction per solve).
      const int stale = Utilities::MPI::max(int(record.dof_handler != &dof_handler), dof_handler.get_communicator());
      if (stale)
        {
          record.dof_handler = &dof_handler;
          record.geometric   = -1;
          record.reported    = false;
          auto &signals      = dof_handler.get_triangulation().signals;
          record.change      = signals.any_change.connect([] { record.dof_handler = nullptr; });
          record.clear       = signals.clear.connect([] { record.dof_handler = nullptr; });
        }
      return record;
    }

    struct PreconditionerChoice
    {
      bool        geometric = false;
      std::string why; // the automatic rule's reason (empty: asked for)
    };

    /**
     * Preconditioner = automatic: the geometric two-level cycle in 3D on a
     * Q1 mesh with a coarser level (Global refinements >= 1, or one block of
     * equal cells with even subdivisions), else AMG. Measured (doc/linear_solver.md,
     * "Session 22: the default"): in 3D geometric costs less CPU on every
     * shipped and tested scene above the direct solver's limit and
     * 30-50 % less peak memory; in 2D (iterative only above 50 000 DoFs)
     * its Krylov count grows with the mesh (2D plastic 256²: 50.2 against
     * ML's 29.5, +38 % CPU). AMG's own options (MueLu, a kept hierarchy,
     * the aggregate-block smoother) ask for AMG.
     */
    template <int dim>
    PreconditionerChoice choose_preconditioner(const std::string &entry, const std::string &package,
                                               const double rebuild_growth, const bool aggregate_blocks,
                                               const DoFHandler<dim> &dof_handler, MeshRecord &record)
    {
      // ANVIL_PRECONDITIONER=geometric|AMG: benchmarks on builds before the entry.
      const char       *forced = std::getenv("ANVIL_PRECONDITIONER");
      const std::string asked  = forced ? std::string(forced) : entry;
      if (asked != "automatic")
        return {asked == "geometric", ""};
      if (dim == 2)
        return {false, "2D"};
      if (package == "MueLu")
        return {false, "AMG package = MueLu"};
      if (rebuild_growth > 0)
        return {false, "AMG rebuild growth > 0"};
      if (aggregate_blocks)
        return {false, "ANVIL_FINE_SMOOTHER=blocks"};
      if (record.geometric < 0)
        try
          {
            check_geometric_coarse_space(dof_handler);
            record.geometric = 1;
          }
        catch (const InputError &)
          {
            record.geometric = 0;
          }
      if (record.geometric == 0)
        return {false, "3D, no coarser mesh level or not Q1"};
      return {true, "3D, Q1, a coarser mesh level"};
    }
  } // namespace

  template <int dim>
  unsigned int MechanicalProblem<dim>::solve_linear_system(TrilinosWrappers::MPI::Vector &du)
  {
    TimerOutput::Scope t(timer, "Mechanics: linear solve");
    const bool direct = parameters.linear_solver == "direct" ||
                        (parameters.linear_solver == "automatic" &&
                         dof_handler.n_dofs() <= parameters.direct_solver_limit);
    if (direct)
      {
        // The ordering depends on the pattern only: kept across iterations
        // and steps until setup_matrix() makes a new one.
        // In 3D RCM's band holds a whole cross-section's plane (n^(7/3)
        // flops against nested dissection's n^2): KLU unless asked.
        direct_solver.method = KluFactorization::parse_method(parameters.direct_solver);
        if (dim == 3 && direct_solver.method == KluFactorization::Method::automatic)
          direct_solver.method = KluFactorization::Method::klu;
        const auto *kept_band = direct_solver.band_solver();
        const auto  orderings = kept_band ? kept_band->orderings : 0;
        direct_solver.factorize(system_matrix);
        // The choice once in the log (and at every new ordering on request).
        const auto *band  = direct_solver.band_solver();
        const bool  first = direct_solver.numeric_factorizations + direct_solver.band_factorizations == 1;
        if ((first || (band && band->orderings != orderings && std::getenv("ANVIL_BAND_LOG"))) &&
            Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
          {
            std::cout << "Mechanics: direct solver " << direct_solver.last_method();
            if (band)
              std::cout << " (band LU: " << band->size() << " unknowns, bandwidths "
                        << band->lower_bandwidth() << " + " << band->upper_bandwidth() << ", "
                        << band->estimated_flops() << " flops on the envelope, ordering "
                        << band->orderings << "; KLU's estimate " << direct_solver.klu_estimated_flops
                        << " flops)";
            std::cout << std::endl;
          }
        direct_solver.solve(du, system_rhs);
        return 1;
      }
    // The modes of the current configuration x = X + u (near-null for the
    // tangent at u; exact for the unloaded body).
    IterativeSolverSettings settings;
    settings.tolerance      = parameters.linear_tolerance;
    settings.max_iterations = parameters.linear_max_iterations;
    settings.restart        = parameters.gmres_restart;
    settings.higher_order   = parameters.polynomial_degree > 1;
    settings.rebuild_growth = parameters.amg_rebuild_growth;
    settings.components     = dim; // when the nodes' rows are consecutive
    if (parameters.amg_package == "MueLu")
      settings.package = IterativeSolverSettings::Package::muelu;
    if (const char *s = std::getenv("ANVIL_FINE_SMOOTHER"))
      settings.aggregate_blocks = std::string(s) == "blocks";
    // Plastic flow makes the tangent nearly incompressible (shear stiffness
    // ~H/3 against the bulk modulus): the isochoric modes, and a Chebyshev
    // smoother of degree 6 over [λ_max/100, λ_max], bring the plastic F-bar
    // block from 66-85 (2D) and 45-61 (3D) Krylov iterations per solve to
    // <= 30 (doc/linear_solver.md, session 17). Elastic solves (8-10
    // iterations) keep the cheaper rigid-body modes and Chebyshev 2. In 2D
    // degree 8: 256² 35.5 -> 30.0 Krylov per solve at the same CPU per Newton
    // (9.91 vs 9.70 s, session 18); in 3D 6 (30³ 20.7; degree 4 25.3 at −4 % CPU, within the scatter).
    const bool isochoric = parameters.amg_isochoric_modes == "automatic" ? has_flowed_plastically()
                                                                          : parameters.amg_isochoric_modes == "true";
    settings.smoother_degree =
      parameters.amg_smoother_degree > 0 ? parameters.amg_smoother_degree : (isochoric ? (dim == 2 ? 8 : 6) : 2);
    settings.chebyshev_ratio =
      parameters.amg_chebyshev_ratio > 0 ? parameters.amg_chebyshev_ratio : (isochoric ? 100 : 10);
    settings.aggregation_threshold = parameters.amg_aggregation_threshold;
    settings.coarse_size           = parameters.amg_coarse_size;
    settings.plain_aggregation     = parameters.amg_plain_aggregation;
    // The plastic tangent's low-energy isochoric fields reach the coarse levels
    // only partly through each level's smoother: in 2D a V-cycle's count grows
    // with the hierarchy's depth (plastic block 128² 23.6, 256² 28.6, 512² 37.4
    // per solve), a W-cycle's much less (19.8, 20.9, 27.7). Its second visits
    // of level 1 pay from ~10^5 DoFs (256²: the same CPU, 512²: -14 %), not
    // below (two_blocks refined 3 times, 52 164 DoFs: +12 % solve time, the
    // same count). In 3D the coarse levels carry 11 modes per aggregate and a
    // second visit costs more than it saves (20³: 21.5 -> 17.9 Krylov per
    // Newton, +8 % solve time). doc/linear_solver.md, session 25.
    constexpr types::global_dof_index w_cycle_min_dofs = 100000;
    settings.w_cycle = parameters.amg_cycle == "automatic"
                         ? (isochoric && dim == 2 && dof_handler.n_dofs() >= w_cycle_min_dofs)
                         : parameters.amg_cycle == "W";
    const auto modes     = [&]() { return rigid_body_modes(mapping, dof_handler, &solution, isochoric); };
    if (const char *folder = std::getenv("ANVIL_KRYLOV_DUMP"))
      dump_system(folder, system_matrix.trilinos_matrix(), system_rhs,
                  rigid_body_modes(mapping, dof_handler, &solution, true).modes);
    // Benchmarks: each solve's count (the averages hide the restarts), a
    // failed one's too: session 18's 2D 256² figure missed a 1000-iteration
    // failure that the cut-back hid (doc/linear_solver.md, session 19).
    const auto log = [&](const unsigned int n, const char *outcome) {
      if (std::getenv("ANVIL_KRYLOV_LOG") && Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
        std::cout << "Krylov: " << n << outcome << (isochoric ? " isochoric" : " rigid") << ", Chebyshev "
                  << settings.smoother_degree << " ratio " << settings.chebyshev_ratio
                  << (settings.w_cycle ? ", W" : ", V") << std::endl;
    };
    MeshRecord                &record = mesh_record(dof_handler);
    const PreconditionerChoice choice =
      choose_preconditioner(parameters.preconditioner, parameters.amg_package, parameters.amg_rebuild_growth,
                            settings.aggregate_blocks, dof_handler, record);
    // The choice once per mesh in the log, as the direct solver's.
    if (!record.reported && Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      std::cout << "Mechanics: iterative solver, preconditioner " << (choice.geometric ? "geometric" : "AMG")
                << (choice.why.empty() ? "" : " (automatic: " + choice.why + ")") << std::endl;
    record.reported = true;
    try
      {
        // The two-level preconditioner on the geometric coarse space
        // (geometric_coarse_space.h).
        if (choice.geometric)
          {
            bool coarse_isochoric = isochoric;
            if (const char *m = std::getenv("ANVIL_GMG_COARSE_MODES"))
              coarse_isochoric = std::string(m) == "isochoric";
            const unsigned int iterations = solve_two_level<dim>(
              system_matrix, du, system_rhs, dof_handler, *active_constraints,
              [&] { return rigid_body_modes(mapping, dof_handler, &solution, coarse_isochoric).modes; },
              coarse_isochoric ? 1 : 0, settings);
            log(iterations, " geometric");
            return iterations;
          }
        const unsigned int iterations = amg.solve(system_matrix, du, system_rhs, modes, settings);
        log(iterations, "");
        return iterations;
      }
    catch (const SolverControl::NoConvergence &e)
      {
        log(e.last_step, " failed");
        throw;
      }
  }

  template <int dim>
  bool MechanicalProblem<dim>::has_flowed_plastically() const
  {
    // The current (trial) state: a point yielding in this Newton iteration counts.
    int plastic = 0;
    for (const auto &point : points.raw())
      if (point && point->equivalent_plastic_strain() > 0)
        {
          plastic = 1;
          break;
        }
    return Utilities::MPI::max(plastic, mpi_communicator) > 0;
  }

#define INSTANTIATE(dim)                                                                      \
  template bool         MechanicalProblem<dim>::has_flowed_plastically() const;             \
  template unsigned int MechanicalProblem<dim>::solve_linear_system(                          \
    TrilinosWrappers::MPI::Vector &);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
