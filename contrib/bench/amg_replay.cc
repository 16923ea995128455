// Benchmark (prints, asserts nothing): one mechanics solve written by
// ANVIL_KRYLOV_DUMP (linear_solver.cc), solved again by GMRES + ML with the
// settings given, so that a preconditioner can be tried on the one solve that
// costs (the onset of plastic flow, doc/linear_solver.md, session 19) without
// rerunning the scene.
//
// Usage: amg_replay FILE [modes=N] [degree=D] [ratio=R] [restart=M]
//                   [threshold=T] [coarse=C] [plain=1] [tolerance=E]
// log=1 prints the residual every 10 iterations; the diagonal's signs are printed.
// eig=1 prints the Ritz values of the preconditioned operator K M⁻¹ (the
// Hessenberg matrix's eigenvalues at the end of the solve, or of its last
// restart cycle), the 12 of smallest modulus and the count below 0.1 and with
// a negative real part: outliers GMRES has to resolve one by one.
// gcrodr=M,K solves with Belos's GCRO-DR instead (M vectors per cycle, K of
// them harmonic Ritz vectors carried over each restart), same tolerance.
// modes: the first N of the dumped vectors (2D: 3 rigid-body, + 2 isochoric).
// ANVIL_ML_PARAMETERS reaches ML as in a run (build_amg()).
#include <deal.II/base/index_set.h>
#include <deal.II/base/logstream.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/solver_gmres.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/timer.h>
#include <deal.II/lac/trilinos_solver.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/mechanics/linear_solver.h>

#include <algorithm>
#include <complex>
#include <cstdio>

DEAL_II_DISABLE_EXTRA_DIAGNOSTICS
#include <BelosEpetraAdapter.hpp>
#include <BelosGCRODRSolMgr.hpp>
#include <BelosLinearProblem.hpp>
#include <Epetra_CrsMatrix.h>
DEAL_II_ENABLE_EXTRA_DIAGNOSTICS
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

using namespace dealii;

namespace
{
  template <typename T>
  void read(FILE *f, T *data, const std::size_t n)
  {
    if (std::fread(data, sizeof(T), n, f) != n)
      {
        std::cerr << "amg_replay: short file" << std::endl;
        std::exit(2);
      }
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (argc < 2)
    {
      std::cerr << "usage: amg_replay FILE [modes=N] [degree=D] [ratio=R] [restart=M] [threshold=T] "
                   "[coarse=C] [plain=1] [tolerance=E]"
                << std::endl;
      return 2;
    }
  FILE *f = std::fopen(argv[1], "rb");
  if (!f)
    {
      std::cerr << "amg_replay: cannot read " << argv[1] << std::endl;
      return 2;
    }
  int n = 0, entries = 0;
  read(f, &n, 1);
  read(f, &entries, 1);
  std::vector<int>    offsets(n + 1), columns(entries);
  std::vector<double> values(entries), b(n);
  read(f, offsets.data(), n + 1);
  read(f, columns.data(), entries);
  read(f, values.data(), entries);
  read(f, b.data(), n);
  int m = 0;
  read(f, &m, 1);
  std::vector<std::vector<double>> modes(m, std::vector<double>(n));
  for (auto &mode : modes)
    read(f, mode.data(), n);
  std::fclose(f);

  anvil::IterativeSolverSettings settings;
  settings.components      = 2;
  settings.smoother_degree = 8;
  settings.chebyshev_ratio = 100;
  unsigned int n_modes     = m;
  if (const char *cap = std::getenv("REPLAY_MAX"))
    settings.max_iterations = std::atoi(cap);
  bool         log         = false, direct = false, eig = false;
  int          gcrodr_blocks = 0, gcrodr_kept = 0;
  for (int a = 2; a < argc; ++a)
    {
      const std::string arg = argv[a], key = arg.substr(0, arg.find('=')),
                        value = arg.substr(arg.find('=') + 1);
      if (key == "modes")
        n_modes = std::stoi(value);
      else if (key == "degree")
        settings.smoother_degree = std::stoi(value);
      else if (key == "ratio")
        settings.chebyshev_ratio = std::stod(value);
      else if (key == "restart")
        settings.restart = std::stoi(value);
      else if (key == "threshold")
        settings.aggregation_threshold = std::stod(value);
      else if (key == "coarse")
        settings.coarse_size = std::stoi(value);
      else if (key == "plain")
        settings.plain_aggregation = value == "1";
      else if (key == "tolerance")
        settings.tolerance = std::stod(value);
      else if (key == "direct")
        direct = value == "1";
      else if (key == "log")
        log = value == "1";
      else if (key == "gcrodr")
        {
          gcrodr_blocks = std::stoi(value.substr(0, value.find(',')));
          gcrodr_kept   = std::stoi(value.substr(value.find(',') + 1));
        }
      else if (key == "eig")
        eig = value == "1";
      else if (key == "components")
        settings.components = std::stoi(value);
      else
        {
          std::cerr << "amg_replay: unknown " << arg << std::endl;
          return 2;
        }
    }
  modes.resize(std::min<unsigned int>(n_modes, m));

  const IndexSet all = complete_index_set(n);
  TrilinosWrappers::SparsityPattern pattern(all, MPI_COMM_WORLD);
  for (int i = 0; i < n; ++i)
    {
      std::vector<TrilinosWrappers::SparsityPattern::size_type> row(columns.begin() + offsets[i],
                                                                   columns.begin() + offsets[i + 1]);
      pattern.add_entries(i, row.begin(), row.end());
    }
  pattern.compress();
  TrilinosWrappers::SparseMatrix K(pattern);
  for (int i = 0; i < n; ++i)
    {
      std::vector<TrilinosWrappers::SparseMatrix::size_type> row(columns.begin() + offsets[i],
                                                                 columns.begin() + offsets[i + 1]);
      K.set(i, row.size(), row.data(), values.data() + offsets[i]);
    }
  K.compress(VectorOperation::insert);
  TrilinosWrappers::MPI::Vector rhs(all, MPI_COMM_WORLD), x(all, MPI_COMM_WORLD);
  for (int i = 0; i < n; ++i)
    rhs[i] = b[i];
  rhs.compress(VectorOperation::insert);

  // The diagonal's signs: a negative entry makes K indefinite, which a
  // Chebyshev smoother (built for a positive spectrum of D⁻¹K) amplifies.
  int    negative = 0;
  double smallest = 1e300, largest = 0;
  for (int i = 0; i < n; ++i)
    for (int k = offsets[i]; k < offsets[i + 1]; ++k)
      if (columns[k] == i)
        {
          negative += values[k] < 0;
          smallest = std::min(smallest, values[k]);
          largest  = std::max(largest, values[k]);
        }
  std::cout << "diagonal: " << negative << " negative, min " << smallest << ", max " << largest << std::endl;

  if (direct)
    {
      // KLU's answer: is the system solvable, how large is x.
      SolverControl                  control(1, 0);
      TrilinosWrappers::SolverDirect klu(control);
      klu.solve(K, x, rhs);
      TrilinosWrappers::MPI::Vector r(rhs);
      K.vmult(r, x);
      r -= rhs;
      std::cout << "KLU: |x| " << x.l2_norm() << ", |r|/|b| " << r.l2_norm() / rhs.l2_norm() << std::endl;
      x = 0;
    }

  Timer      timer;
  const auto amg   = anvil::build_amg(K, modes, settings);
  const double set = timer.cpu_time();
  unsigned int iterations = 0;
  try
    {
      if (gcrodr_blocks > 0)
        {
          using MV = Epetra_MultiVector;
          using OP = Epetra_Operator;
          Teuchos::RCP<OP> A = Teuchos::rcp(const_cast<Epetra_CrsMatrix *>(&K.trilinos_matrix()), false);
          Teuchos::RCP<MV> X = Teuchos::rcp(&x.trilinos_vector(), false);
          Teuchos::RCP<MV> B = Teuchos::rcp(const_cast<Epetra_FEVector *>(&rhs.trilinos_vector()), false);
          auto M = Teuchos::rcp(new Belos::EpetraPrecOp(Teuchos::rcp(&amg->trilinos_operator(), false)));
          auto problem = Teuchos::rcp(new Belos::LinearProblem<double, MV, OP>(A, X, B));
          problem->setRightPrec(M);
          problem->setProblem();
          auto params = Teuchos::rcp(new Teuchos::ParameterList);
          params->set("Num Blocks", gcrodr_blocks);
          params->set("Num Recycled Blocks", gcrodr_kept);
          params->set("Maximum Iterations", static_cast<int>(settings.max_iterations));
          params->set("Convergence Tolerance", settings.tolerance);
          params->set("Verbosity", Belos::Errors + Belos::Warnings + (log ? Belos::StatusTestDetails : 0));
          params->set("Output Frequency", 10);
          Belos::GCRODRSolMgr<double, MV, OP> solver(problem, params);
          const Belos::ReturnType converged = solver.solve();
          iterations = solver.getNumIters();
          if (converged != Belos::Converged)
            std::cout << "GCRO-DR: not converged" << std::endl;
        }
      else if (log || eig)
        {
          // The residual's history (the run's solver, with deallog).
          deallog.depth_console(2);
          SolverControl control(settings.max_iterations, settings.tolerance * rhs.l2_norm(), true);
          control.log_frequency(10);
          control.log_history(log);
          SolverGMRES<TrilinosWrappers::MPI::Vector> gmres(
            control, SolverGMRES<TrilinosWrappers::MPI::Vector>::AdditionalData(settings.restart + 2, true));
          std::vector<std::complex<double>> ritz;
          if (eig)
            gmres.connect_eigenvalues_slot([&](const std::vector<std::complex<double>> &v) { ritz = v; });
          try
            {
              gmres.solve(K, x, rhs, *amg);
            }
          catch (...)
            {
              if (!eig)
                throw;
            }
          if (eig)
            {
              std::sort(ritz.begin(), ritz.end(),
                        [](const auto &a, const auto &b) { return std::abs(a) < std::abs(b); });
              int below = 0, negative = 0;
              for (const auto &z : ritz)
                {
                  below += std::abs(z) < 0.1;
                  negative += z.real() < 0;
                }
              std::cout << ritz.size() << " Ritz values of K M^-1, " << below << " of modulus < 0.1, " << negative
                        << " with Re < 0; smallest:";
              for (unsigned int k = 0; k < std::min<std::size_t>(12, ritz.size()); ++k)
                std::cout << " " << ritz[k];
              std::cout << "; largest " << (ritz.empty() ? 0. : std::abs(ritz.back())) << std::endl;
            }
          iterations = control.last_step();
        }
      else
        iterations = anvil::solve_gmres(K, x, rhs, *amg, settings);
    }
  catch (const SolverControl::NoConvergence &e)
    {
      std::cout << "no convergence (stalled or the cap) at " << e.last_step << std::endl;
      iterations = e.last_step;
    }
  TrilinosWrappers::MPI::Vector r(rhs);
  K.vmult(r, x);
  r -= rhs;
  std::cout << argv[1] << ": " << n << " rows, " << modes.size() << " modes, Chebyshev "
            << settings.smoother_degree << " ratio " << settings.chebyshev_ratio << ": " << iterations
            << " Krylov, |r|/|b| " << r.l2_norm() / rhs.l2_norm() << ", CPU s set-up " << set << " solve "
            << timer.cpu_time() - set << std::endl;
  return 0;
}
