// The mechanical assembly (WorkStream over cells, the copier adding them in
// cell order) gives the same tangent and residual on 1 and on 2 threads,
// entry by entry. Independent answer: the 1-thread assembly runs anvil's own
// serial loop on the kept work space, not WorkStream. Cases: plane strain J2 F-bar with a
// follower pressure (tests/plastic_block.prm), axisymmetric, 3D; each
// quasi-static and with implicit dynamics (generalized-α, consistent and
// lumped mass) and gravity. The state is two steps into plastic flow (the
// second step's converged iterate). Expected: exact equality (accepted up to
// 1e-14 relative to the largest entry). Also checks that a 2-thread
// WorkStream really runs on two threads.
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/work_stream.h>

#include "mechanics_fixture.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <mutex>
#include <set>
#include <thread>

using namespace dealii;
using anvil_test::Overrides;

namespace
{
  struct Snapshot
  {
    std::vector<double> matrix, tangent_rhs, residual;
    bool                ok = true;
  };

  template <int dim>
  Snapshot assemble_with(anvil::MechanicalProblem<dim> &problem, const unsigned int threads)
  {
    MultithreadInfo::set_thread_limit(threads);
    Snapshot s;
    s.ok = problem.assemble_system(true);
    const auto &K = problem.get_system_matrix();
    for (auto it = K.begin(); it != K.end(); ++it)
      s.matrix.push_back(it->value());
    for (const auto i : problem.get_system_rhs().locally_owned_elements())
      s.tangent_rhs.push_back(problem.get_system_rhs()(i));
    s.ok = problem.assemble_system(false) && s.ok;
    for (const auto i : problem.get_system_rhs().locally_owned_elements())
      s.residual.push_back(problem.get_system_rhs()(i));
    return s;
  }

  // Largest |a − b| relative to the largest |a|; counts entries that differ at all.
  double compare(const std::vector<double> &a, const std::vector<double> &b, std::size_t &differ)
  {
    differ = 0;
    if (a.size() != b.size())
      {
        differ = std::max(a.size(), b.size());
        return 1;
      }
    double scale = 0, diff = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
      {
        scale = std::max(scale, std::abs(a[i]));
        diff  = std::max(diff, std::abs(a[i] - b[i]));
        differ += a[i] != b[i];
      }
    return diff / std::max(scale, 1e-300);
  }

  template <int dim>
  bool check(const std::string &name, const Overrides &overrides)
  {
    anvil_test::MechanicsFixture<dim> f(std::string(ANVIL_SOURCE_DIR) + "/tests/plastic_block.prm",
                                        overrides);
    if (!f.run_steps(2))
      {
        std::cout << name << ": FAIL, a step did not converge" << std::endl;
        return false;
      }
    const Snapshot one = assemble_with(*f.problem, 1);
    const Snapshot two = assemble_with(*f.problem, 2);
    bool           ok  = one.ok && two.ok;
    std::cout << name << " (" << f.problem->n_dofs() << " DoFs, largest plastic increment "
              << f.problem->largest_plastic_increment() << "):\n";
    for (const auto &[what, a, b] :
         {std::make_tuple("tangent K", &one.matrix, &two.matrix),
          std::make_tuple("-R with K", &one.tangent_rhs, &two.tangent_rhs),
          std::make_tuple("-R alone", &one.residual, &two.residual)})
      {
        std::size_t  differ = 0;
        const double rel    = compare(*a, *b, differ);
        std::cout << "  " << what << ": " << a->size() << " entries, 1 vs 2 threads: " << differ
                  << " differ, max relative difference " << rel << " (expected 0, accepted <= 1e-14)"
                  << std::endl;
        ok = ok && rel <= 1e-14 && !a->empty();
      }
    return ok;
  }

  // The distinct threads a WorkStream with the current limit runs its workers on.
  unsigned int threads_used()
  {
    std::vector<int> items(64);
    std::mutex       m;
    std::set<std::thread::id> ids;
    WorkStream::run(
      items.begin(), items.end(),
      [&](const std::vector<int>::iterator &, int &, int &) {
        std::this_thread::sleep_for(std::chrono::milliseconds(2));
        std::lock_guard<std::mutex> lock(m);
        ids.insert(std::this_thread::get_id());
      },
      [](const int &) {}, 0, 0);
    return ids.size();
  }
} // namespace

int main(int argc, char **argv)
{
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 2);
  bool ok = true;

  MultithreadInfo::set_thread_limit(2);
  const unsigned int used = threads_used();
  std::cout << "WorkStream with a limit of 2 threads ran on " << used << " thread(s) ("
            << MultithreadInfo::n_cores() << " cores)" << std::endl;
  if (MultithreadInfo::n_cores() >= 2 && used < 2)
    {
      std::cout << "FAIL: the 2-thread assembly would run on one thread" << std::endl;
      ok = false;
    }

  const Overrides plane = {{"Geometry/Blocks", "body: 0.1, 0, 1.1, 1, 16, 16"},
                           {"Mechanics/Element", "F-bar"}};
  Overrides axisymmetric = plane;
  axisymmetric.push_back({"Mechanics/Two-dimensional model", "axisymmetric"});
  const Overrides solid = {{"Dimension", "3"},
                           {"Geometry/Blocks", "body: 0.1, 0, 0, 1.1, 1, 1, 6, 6, 6"},
                           {"Mechanics/Element", "F-bar"},
                           {"Boundary conditions/Displacement",
                            "bottom: ux = 0, uy = 0, uz = 0; top: ux = 0.05*t, uy = -0.1*t, uz = 0"}};
  // Dynamics: short steps so that inertia is a real part of the balance.
  auto dynamic = [](Overrides o, const std::string &gravity, const std::string &mass) {
    const bool solid = gravity.find(',') != gravity.rfind(',');
    o.push_back({"Mechanics/Dynamics/Type", "implicit"});
    o.push_back({"Mechanics/Dynamics/Spectral radius", "0.8"});
    o.push_back({"Mechanics/Dynamics/Mass", mass});
    o.push_back({"Mechanics/Gravity", gravity});
    o.push_back({"Time/Time step", "2e-5"});
    o.push_back({"Boundary conditions/Displacement",
                 solid ? "bottom: ux = 0, uy = 0, uz = 0; top: ux = 250*t, uy = -500*t, uz = 0" :
                         "bottom: ux = 0, uy = 0; top: ux = 250*t, uy = -500*t"});
    o.push_back({"Boundary conditions/Pressure", "right: 2.5e6*t"});
    return o;
  };
  ok = check<2>("plane strain, F-bar, J2, pressure", plane) && ok;
  ok = check<2>("axisymmetric, F-bar, J2, pressure", axisymmetric) && ok;
  ok = check<3>("3D, F-bar, J2, pressure", solid) && ok;
  ok = check<2>("plane strain, dynamics (consistent mass), gravity",
                dynamic(plane, "0, -9810", "consistent")) && ok;
  ok = check<2>("axisymmetric, dynamics (lumped mass), gravity",
                dynamic(axisymmetric, "0, -9810", "lumped")) && ok;
  ok = check<3>("3D, dynamics (consistent mass), gravity",
                dynamic(solid, "0, -9810, 0", "consistent")) && ok;
  std::cout << (ok ? "PASS" : "FAIL") << std::endl;
  return ok ? 0 : 1;
}
