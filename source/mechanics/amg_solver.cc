// The mechanics' iterative solve: GMRES right-preconditioned by smoothed-
// aggregation AMG (Trilinos ML) on the rigid-body modes, and the hierarchy
// kept across solves (ReusedAMG). doc/linear_solver.md.
#include <deal.II/base/utilities.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/lac/vector_memory.h>
#include <deal.II/lac/trilinos_precondition.h>

#include <anvil/mechanics/linear_solver.h>

#include "gmres_run.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include <dlfcn.h>

DEAL_II_DISABLE_EXTRA_DIAGNOSTICS
#include <BelosEpetraAdapter.hpp>
#include <BelosGCRODRSolMgr.hpp>
#include <BelosLinearProblem.hpp>
#include <Epetra_CrsMatrix.h>
#include <Epetra_MultiVector.h>
#include <Epetra_Operator.h>
#include <Teuchos_ParameterList.hpp>
DEAL_II_ENABLE_EXTRA_DIAGNOSTICS

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// The near-null space over K's domain map (one zero vector if empty).
    Epetra_MultiVector as_multivector(const TrilinosWrappers::SparseMatrix   &K,
                                      const std::vector<std::vector<double>> &near_null_space)
    {
      const Epetra_Map  &map = K.trilinos_matrix().OperatorDomainMap();
      Epetra_MultiVector modes(map, std::max<int>(1, near_null_space.size()));
      for (unsigned int k = 0; k < near_null_space.size(); ++k)
        {
          AssertDimension(near_null_space[k].size(), static_cast<std::size_t>(map.NumMyElements()));
          std::copy(near_null_space[k].begin(), near_null_space[k].end(), modes[k]);
        }
      return modes;
    }

    std::string trimmed(const std::string &s)
    {
      const auto a = s.find_first_not_of(" \t"), b = s.find_last_not_of(" \t");
      return a == std::string::npos ? "" : s.substr(a, b - a + 1);
    }
  } // namespace

  void apply_ml_overrides(Teuchos::ParameterList &list, const std::string &overrides)
  {
    std::istringstream entries(overrides);
    for (std::string entry; std::getline(entries, entry, ';');)
      {
        entry = trimmed(entry);
        if (entry.empty())
          continue;
        const auto eq = entry.find('=');
        AssertThrow(eq != std::string::npos,
                    ExcMessage("ML parameter override without '=': " + entry));
        std::string       name  = trimmed(entry.substr(0, eq));
        const std::string value = trimmed(entry.substr(eq + 1));
        // "a/b/name": name in sublist b of sublist a (ML's "smoother: ifpack list").
        Teuchos::ParameterList *target = &list;
        for (auto slash = name.find('/'); slash != std::string::npos; slash = name.find('/'))
          {
            target = &target->sublist(trimmed(name.substr(0, slash)));
            name   = name.substr(slash + 1);
          }
        // ML names contain ':' themselves: the type is a last ":int", ":double", ":bool".
        std::string type  = "string";
        const auto  colon = name.rfind(':');
        if (colon != std::string::npos)
          {
            const std::string t = trimmed(name.substr(colon + 1));
            if (t == "int" || t == "double" || t == "bool")
              {
                type = t;
                name = trimmed(name.substr(0, colon));
              }
          }
        if (type == "int")
          target->set(name, std::stoi(value));
        else if (type == "double")
          target->set(name, std::stod(value));
        else if (type == "bool")
          target->set(name, value == "true" || value == "1");
        else
          target->set(name, value);
      }
  }

  std::unique_ptr<TrilinosWrappers::PreconditionAMG>
  build_amg(const TrilinosWrappers::SparseMatrix   &K,
            const std::vector<std::vector<double>> &near_null_space,
            const IterativeSolverSettings          &settings)
  {
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic              = true; // smoothed aggregation, Chebyshev smoother
    data.higher_order_elements = settings.higher_order;
    // Chebyshev degree: 2 by default; 4 saves 25-30 % of the Krylov
    // iterations on the rigid-body modes alone but costs as much more per
    // V-cycle; with the isochoric modes as well degree 5 halves them
    // (doc/linear_solver.md, session 14).
    data.smoother_sweeps       = settings.smoother_degree;
    data.aggregation_threshold = settings.aggregation_threshold;
    Teuchos::ParameterList              list;
    std::unique_ptr<Epetra_MultiVector> unused; // deal.II's boolean modes: none given
    data.set_parameters(list, unused, K);
    list.set("smoother: Chebyshev alpha", settings.chebyshev_ratio);
    list.set("coarse: max size", static_cast<int>(settings.coarse_size));
    if (settings.plain_aggregation)
      list.set("aggregation: damping factor", 0.);
    if (settings.w_cycle)
      list.set("prec type", "MGW");

    // ML reads the modes (copied into its hierarchy) during initialize().
    const Epetra_MultiVector modes = as_multivector(K, near_null_space);
    if (!near_null_space.empty())
      {
        list.set("null space: type", "pre-computed");
        list.set("null space: dimension", static_cast<int>(near_null_space.size()));
        list.set("null space: vectors", modes.Values());
      }
    // Aggregate nodes, not dofs: a node's components move together in
    // every mode, and splitting them would cut the modes apart.
    list.set("PDE equations", static_cast<int>(settings.components));
    // ML's default ("Uncoupled-MIS", which stays uncoupled here) aggregates
    // each process's rows apart on every level: two bodies in contact on
    // one process each (the contact strip) get aggregates of half the size
    // from level 1 on, one more level and 12 % more operator complexity
    // than on one process. ANVIL_COARSE_AGGREGATION=coupled aggregates the
    // levels from 1 on across the processes (ML's MIS; level 0, where it
    // would cost most, stays per process). Not the default: the strip keeps
    // its Krylov count either way, its set-up gains nothing below ~10^5 DoFs,
    // and the 3D plastic block at 20^3 needs 70.4 instead of 67.8 Krylov
    // iterations per solve (doc/performance.md, session 13).
    const char *coarse = std::getenv("ANVIL_COARSE_AGGREGATION");
    if (coarse && std::string(coarse) == "coupled" && K.trilinos_matrix().Comm().NumProc() > 1)
      {
        list.set("aggregation: type", "MIS");
        list.set("aggregation: type (level 0)", "Uncoupled");
      }
    if (settings.aggregate_blocks)
      {
        // ML's own sweep count does not reach a user smoother: the sweeps
        // are AggregateBlockSmoother::sweeps.
        list.set("smoother: type (level 0)", "user-defined");
        list.set("smoother: user-defined function", &AggregateBlockSmoother::ml_smoother);
        list.set("smoother: user-defined name", "aggregate-block Gauss-Seidel");
        list.set("smoother: sweeps (level 0)", 1);
      }
    // Benchmarks try ML's other settings without rebuilding (doc/linear_solver.md).
    if (const char *overrides = std::getenv("ANVIL_ML_PARAMETERS"))
      apply_ml_overrides(list, overrides);
    auto amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
    amg->initialize(K, list);
    return amg;
  }

  namespace
  {
    /// The module's entry points (muelu_preconditioner.cc).
    using MueLuCreate  = Epetra_Operator *(*)(const Epetra_CrsMatrix *, const Epetra_MultiVector *,
                                              Teuchos::ParameterList *, std::string *);
    using MueLuRefresh = void (*)(Epetra_Operator *);
    struct MueLuModule
    {
      MueLuCreate  create;
      MueLuRefresh refresh;
    };

    /// libanvil-muelu.so, from libanvil's own folder, loaded once.
    const MueLuModule &muelu_module()
    {
#ifdef ANVIL_MUELU_MODULE
      static const MueLuModule entries = [] {
        Dl_info info;
        AssertThrow(dladdr(reinterpret_cast<void *>(&muelu_module), &info) != 0 && info.dli_fname,
                    ExcMessage("MueLu: cannot locate libanvil to find " ANVIL_MUELU_MODULE));
        std::string path = info.dli_fname;
        path             = path.substr(0, path.find_last_of('/') + 1) + ANVIL_MUELU_MODULE;
        void *module     = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        AssertThrow(module, ExcMessage(std::string("MueLu: cannot load ") + path + ": " + dlerror()));
        MueLuModule m{reinterpret_cast<MueLuCreate>(dlsym(module, "anvil_muelu_create")),
                      reinterpret_cast<MueLuRefresh>(dlsym(module, "anvil_muelu_refresh"))};
        AssertThrow(m.create && m.refresh, ExcMessage("MueLu: " + path + " lacks anvil_muelu_create/refresh"));
        return m;
      }();
      return entries;
#else
      AssertThrow(false, ExcMessage("MueLu: anvil was configured with ANVIL_WITH_MUELU=OFF"));
      static const MueLuModule none{};
      return none;
#endif
    }

    /// A preconditioner whose vmult is ApplyInverse of MueLu's operator
    /// (deal.II's PreconditionBase keeps it in a protected member; derived
    /// from PreconditionAMG so that ReusedAMG keeps either kind).
    class PreconditionOperator : public TrilinosWrappers::PreconditionAMG
    {
    public:
      explicit PreconditionOperator(Epetra_Operator *op) { preconditioner = Teuchos::rcp(op); }
      /// K's current values into MueLu's copy of the fine level.
      void refresh() { muelu_module().refresh(preconditioner.get()); }
    };
  } // namespace

  std::unique_ptr<TrilinosWrappers::PreconditionAMG>
  build_muelu(const TrilinosWrappers::SparseMatrix   &K,
              const std::vector<std::vector<double>> &near_null_space,
              const IterativeSolverSettings          &settings)
  {
    AssertThrow(!settings.aggregate_blocks,
                ExcMessage("MueLu: the aggregate-block smoother (ANVIL_FINE_SMOOTHER=blocks) is ML's"));
    // ML's settings in build_amg(), in MueLu's names (its MasterList).
    Teuchos::ParameterList list;
    list.set("verbosity", "none");
    list.set("multigrid algorithm", settings.plain_aggregation ? "unsmoothed" : "sa");
    list.set("number of equations", static_cast<int>(settings.components));
    list.set("coarse: max size", static_cast<int>(settings.coarse_size));
    list.set("coarse: type", "KLU2");
    list.set("cycle type", settings.w_cycle ? "W" : "V");
    list.set("aggregation: type", "uncoupled");
    list.set("aggregation: drop tol", settings.aggregation_threshold);
    list.set("smoother: type", "CHEBYSHEV");
    list.sublist("smoother: params").set("chebyshev: degree", static_cast<int>(settings.smoother_degree));
    list.sublist("smoother: params").set("chebyshev: ratio eigenvalue", settings.chebyshev_ratio);
    // R = Pᵀ applied through P, not stored. R A P as a triple product
    // (`rap: triple product`, A P not kept) saves 4 % of the peak at 1.75
    // times the CPU (Tpetra 13.2's serial kernel): not taken (doc/linear_solver.md).
    list.set("transpose: use implicit", true);
    if (const char *overrides = std::getenv("ANVIL_MUELU_PARAMETERS"))
      apply_ml_overrides(list, overrides);

    Epetra_MultiVector modes = as_multivector(K, near_null_space);
    if (near_null_space.empty())
      modes.PutScalar(1.);
    std::string      error;
    Epetra_Operator *op = muelu_module().create(&K.trilinos_matrix(), &modes, &list, &error);
    AssertThrow(op, ExcMessage("MueLu: " + error));
    return std::make_unique<PreconditionOperator>(op);
  }

  namespace
  {
    std::unique_ptr<TrilinosWrappers::PreconditionAMG>
    build_preconditioner(const TrilinosWrappers::SparseMatrix   &K,
                         const std::vector<std::vector<double>> &near_null_space,
                         const IterativeSolverSettings          &settings)
    {
      if (settings.package == IterativeSolverSettings::Package::muelu)
        return build_muelu(K, near_null_space, settings);
      return build_amg(K, near_null_space, settings);
    }

    /// The deflated restart's sizes: vectors per cycle and harmonic Ritz
    /// vectors kept across a restart (ANVIL_GCRODR="m,k"; "0": off).
    struct DeflatedRestart
    {
      int blocks = 0, kept = 0;
    };

    DeflatedRestart deflated_restart(const IterativeSolverSettings &settings)
    {
      DeflatedRestart d{static_cast<int>(settings.restart), static_cast<int>(settings.restart / 3)};
      if (const char *s = std::getenv("ANVIL_GCRODR"))
        {
          const std::string v = s;
          if (v == "0")
            return {};
          d.blocks = std::stoi(v.substr(0, v.find(',')));
          d.kept   = v.find(',') == std::string::npos ? d.blocks / 3 : std::stoi(v.substr(v.find(',') + 1));
        }
      return d.kept >= 1 && d.kept < d.blocks ? d : DeflatedRestart{};
    }

    /**
     * Continues x towards K⁻¹ b with Belos's GCRO-DR (right preconditioned
     * by @p amg): at every restart the k harmonic Ritz vectors of smallest
     * modulus are kept and deflated, so that the outlying eigenvalues of K M⁻¹
     * are not found again in every cycle as GMRES(m) must. Tested on the true
     * residual |b − K x| ≤ tolerance |b|. Returns the iterations; throws
     * NoConvergence (the step is cut back) after @p cap of them, or when
     * two restart cycles have not halved the residual @p entry_residual
     * started from: GMRES's stall stop (gmres_run.h), which Belos's solver
     * lacks. A stalled continuation otherwise ran to `Maximum iterations`:
     * the 2D 512² block's step 3, 1000 iterations before the cut-back
     * (doc/linear_solver.md, session 25).
     */
    unsigned int gcrodr(const TrilinosWrappers::SparseMatrix &K, TrilinosWrappers::MPI::Vector &x,
                        const TrilinosWrappers::MPI::Vector &b, const TrilinosWrappers::PreconditionAMG &amg,
                        const IterativeSolverSettings &settings, const DeflatedRestart &sizes, const unsigned int cap,
                        const double entry_residual)
    {
      using MV = Epetra_MultiVector;
      using OP = Epetra_Operator;
      Teuchos::RCP<OP> A = Teuchos::rcp(const_cast<Epetra_CrsMatrix *>(&K.trilinos_matrix()), false);
      Teuchos::RCP<MV> X = Teuchos::rcp(&x.trilinos_vector(), false);
      Teuchos::RCP<MV> B = Teuchos::rcp(const_cast<MV *>(static_cast<const MV *>(&b.trilinos_vector())), false);
      // Belos applies a preconditioner's Apply: EpetraPrecOp turns ML's ApplyInverse (the V-cycle) into it.
      auto M = Teuchos::rcp(new Belos::EpetraPrecOp(Teuchos::rcp(&amg.trilinos_operator(), false)));
      auto problem = Teuchos::rcp(new Belos::LinearProblem<double, MV, OP>(A, X, B));
      problem->setRightPrec(M);
      // Two cycles between the stall checks, as GMRES's window. Each further
      // chunk starts from the iterate reached and the space kept (the solver
      // object keeps it: its k vectors cost one product each to re-project,
      // paid only by solves past 2 cycles of continuation).
      const unsigned int chunk = 2 * static_cast<unsigned int>(sizes.blocks);
      auto               list  = Teuchos::rcp(new Teuchos::ParameterList);
      list->set("Num Blocks", sizes.blocks);
      list->set("Num Recycled Blocks", sizes.kept);
      list->set("Maximum Iterations", static_cast<int>(std::min(chunk, cap)));
      list->set("Convergence Tolerance", settings.tolerance);
      // Relative to |b|, as GMRES's test (x is not zero here).
      list->set("Implicit Residual Scaling", "Norm of RHS");
      list->set("Explicit Residual Scaling", "Norm of RHS");
      list->set("Verbosity", static_cast<int>(Belos::Errors));
      Belos::GCRODRSolMgr<double, MV, OP> solver(problem, list);
      TrilinosWrappers::MPI::Vector       r(b);
      const double                        b_norm     = b.l2_norm();
      double                              before     = entry_residual;
      unsigned int                        iterations = 0;
      while (true)
        {
          problem->setProblem(); // the residual of the iterate reached
          const Belos::ReturnType outcome = solver.solve();
          iterations += solver.getNumIters();
          K.vmult(r, x);
          r.sadd(-1., 1., b);
          const double residual = r.l2_norm();
          // The implicit residual may drift from the true one: the test is GMRES's.
          if (outcome == Belos::Converged && residual <= 1.5 * settings.tolerance * b_norm)
            return iterations;
          if (iterations >= cap || !(residual <= 0.5 * before))
            throw SolverControl::NoConvergence(iterations, residual);
          before = residual;
          list->set("Maximum Iterations", static_cast<int>(std::min(chunk, cap - iterations)));
          solver.setParameters(list);
        }
    }
  } // namespace

  unsigned int solve_gmres(const TrilinosWrappers::SparseMatrix    &K,
                           TrilinosWrappers::MPI::Vector           &x,
                           const TrilinosWrappers::MPI::Vector     &b,
                           const TrilinosWrappers::PreconditionAMG &amg,
                           const IterativeSolverSettings           &settings)
  {
    // A solve that converges within one restart cycle is GMRES's, to the bit.
    // One that does not was thrown its Krylov space at every restart: the
    // 2D 512² plastic block's onset solve needs 114 iterations unrestarted,
    // 541 with GMRES(60) and 121 with GCRO-DR(60, 20) (doc/linear_solver.md,
    // session 24). So after the first cycle, unless it stalled (not halved:
    // the failed attempt's solves, which the step's cut-back needs at once),
    // GCRO-DR continues from the iterate reached.
    const DeflatedRestart sizes = deflated_restart(settings);
    if (sizes.blocks == 0 || settings.max_iterations <= settings.restart)
      return run_gmres(K, x, b, amg, settings);
    IterativeSolverSettings first = settings;
    first.max_iterations          = settings.restart;
    try
      {
        return run_gmres(K, x, b, amg, first);
      }
    catch (const SolverControl::NoConvergence &e)
      {
        if (e.last_step < first.max_iterations || !(e.last_residual <= 0.5 * b.l2_norm()))
          throw;
        // As GMRES: up to Maximum iterations, or a stall.
        const unsigned int cap = settings.max_iterations - settings.restart;
        try
          {
            return settings.restart + gcrodr(K, x, b, amg, settings, sizes, cap, e.last_residual);
          }
        catch (const SolverControl::NoConvergence &more)
          {
            throw SolverControl::NoConvergence(settings.restart + more.last_step, more.last_residual);
          }
      }
  }

  unsigned int ReusedAMG::solve(const TrilinosWrappers::SparseMatrix      &K,
                                TrilinosWrappers::MPI::Vector             &x,
                                const TrilinosWrappers::MPI::Vector       &b,
                                const std::function<RigidBodyModes()>     &modes,
                                const IterativeSolverSettings             &settings)
  {
    unsigned int stale = 0;
    if (amg && matrix == &K && settings.rebuild_growth > 0)
      {
        // The kept hierarchy gets rebuild_growth times the iterations its
        // first solve needed; if that is not enough, a fresh hierarchy
        // continues from the iterate reached (nothing is thrown away but
        // the set-up avoided).
        IterativeSolverSettings capped = settings;
        capped.max_iterations =
          std::min<unsigned int>(settings.max_iterations,
                                 std::ceil(settings.rebuild_growth * first_iterations));
        if (auto *muelu = dynamic_cast<PreconditionOperator *>(amg.get()))
          muelu->refresh();
        try
          {
            const AggregateBlockSmoother::ActiveScope active(smoother.get());
            return solve_gmres(K, x, b, *amg, capped);
          }
        catch (const SolverControl::NoConvergence &e)
          {
            stale = e.last_step;
          }
      }
    amg.reset(); // free the old hierarchy before building the new one
    smoother.reset();
    const RigidBodyModes    m     = modes();
    IterativeSolverSettings built = settings;
    if (!m.node_blocks)
      built.components = 1;
    amg    = build_preconditioner(K, m.modes, built);
    matrix = &K;
    ++n_builds;
    // After ML's set-up (the run's memory peak), so that the factors do not
    // add to it; ML calls the smoother only when it is applied.
    if (built.aggregate_blocks)
      {
        smoother = std::make_unique<AggregateBlockSmoother>(K.trilinos_matrix(), built.components);
        // A symmetric sweep before and after the coarse correction: 3D 10^3
        // 33.8 Krylov iterations per solve at Chebyshev 2's CPU; 4 sweeps
        // 27.8 at 1.3 times the CPU (doc/linear_solver.md).
        smoother->sweeps = 2;
        if (const char *n = std::getenv("ANVIL_BLOCK_SWEEPS"))
          smoother->sweeps = std::max(1, std::atoi(n));
      }
    const AggregateBlockSmoother::ActiveScope active(smoother.get());
    first_iterations = std::max(1u, solve_gmres(K, x, b, *amg, settings));
    return stale + first_iterations;
  }
} // namespace anvil
