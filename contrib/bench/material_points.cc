// Material point throughput: updates per second on one core for each model,
// in the elastic and in the plastic branch, 3D tensors, with the mechanics'
// request (stress | tangent, factored where the law gives it:
// request_factored_tangent), with the dense tangent, and with stress only. Prints figures and the
// targets beside them; asserts nothing (ctest label "bench", skipped by CI).
//
//   build/tests/bench_material_points            # ~1 s per measurement
//   build/tests/bench_material_points --quick    # ~0.1 s per measurement
//   build/tests/bench_material_points --updates N [--only NAME] [--branch plastic] [--request s|st|dense]
//        # exactly N updates per figure, for instruction counts (callgrind):
//        # instructions per update = (Ir of J2Point::update) / (rows x 2 x N)
//
// Every update starts from the committed (virgin) state, as Newton's repeated
// updates of one step do; the increments cycle through a small table so that
// the inputs vary, and a checksum of the results is printed so that nothing
// is optimised away. Rates are per CPU second of this thread (the wall clock
// of a loaded machine counts the time other processes had the core).
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/core/scene.h>
#include <anvil/material/material_point.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

using namespace dealii;
using namespace anvil;

namespace
{
  std::shared_ptr<const MaterialModel> make_model(const std::string &settings)
  {
    return MaterialFactory::create_from_text(settings);
  }

  struct Model
  {
    std::string name, settings;
    double      target_plastic; // updates/s per core, 0: none
    bool        adiabatic = false; // the Armero–Simo update (the tube's split)
  };

  /// Increments of size ~@p scale (a multiple of the yield strain), general 3D.
  std::vector<MaterialIncrement> increments(const double scale, const bool adiabatic)
  {
    std::vector<MaterialIncrement> list(64);
    for (unsigned int k = 0; k < list.size(); ++k)
      {
        const double           f  = scale * (1 + 0.01 * k);
        SymmetricTensor<2, 3> &de = list[k].strain_increment;
        de[0][0] = 1.0 * f, de[1][1] = -0.4 * f, de[2][2] = -0.3 * f;
        de[0][1] = 0.5 * f, de[1][2] = -0.2 * f, de[0][2] = 0.1 * f;
        list[k].temperature           = 350 + k;
        list[k].temperature_increment = 1;
        list[k].time_step             = 1e-3;
        list[k].adiabatic             = adiabatic;
      }
    return list;
  }

  double checksum = 0;

  /// CPU seconds of this thread.
  double cpu_seconds()
  {
    timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
  }

  /// Updates per second over at least @p seconds (after a short warm-up);
  /// with @p fixed > 0, exactly @p fixed updates (the rate is then not meaningful
  /// under valgrind, the instruction count is).
  double measure(MaterialPoint &point, const std::vector<MaterialIncrement> &list,
                 const MaterialRequest request, const double seconds, unsigned long &count,
                 bool &plastic, const unsigned long fixed)
  {
    MaterialResponse response;
    double           sum = 0;
    auto             run = [&](const unsigned long n) {
      for (unsigned long i = 0; i < n; ++i)
        {
          point.update(list[i & 63], request, response);
          sum += response.stress[0][1] + response.equivalent_plastic_strain;
          if (request & request_tangent)
            sum += response.factored.active ? response.factored.normal : response.tangent[0][1][0][1];
        }
    };
    if (fixed > 0)
      {
        const double t0 = cpu_seconds();
        run(fixed);
        count   = fixed;
        plastic = response.equivalent_plastic_strain > 0;
        checksum += sum;
        return fixed / std::max(cpu_seconds() - t0, 1e-9);
      }
    // Calibrate: double the batch until it takes 5 % of the budget.
    unsigned long batch = 1000;
    for (;;)
      {
        const double t0 = cpu_seconds();
        run(batch);
        const double t  = cpu_seconds() - t0;
        if (t > 0.05 * seconds)
          break;
        batch *= 2;
      }
    plastic              = response.equivalent_plastic_strain > 0;
    count                = 0;
    const double t0      = cpu_seconds();
    double       elapsed = 0;
    while (elapsed < seconds)
      {
        run(batch);
        count += batch;
        elapsed = cpu_seconds() - t0;
      }
    checksum += sum;
    return count / elapsed;
  }
} // namespace

int main(int argc, char **argv)
{
  bool          quick = false;
  unsigned long fixed = 0;
  std::string   only, branch, request_only;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--quick") == 0)
      quick = true;
    else if (std::strcmp(argv[i], "--updates") == 0 && i + 1 < argc)
      fixed = std::stoul(argv[++i]);
    else if (std::strcmp(argv[i], "--only") == 0 && i + 1 < argc)
      only = argv[++i];
    else if (std::strcmp(argv[i], "--branch") == 0 && i + 1 < argc)
      branch = argv[++i];
    else if (std::strcmp(argv[i], "--request") == 0 && i + 1 < argc)
      request_only = argv[++i];
  const double seconds = quick ? 0.1 : 1.0;

  const std::string elastic =
    "subsection Elasticity\n set Young's modulus = 200000\n set Poisson's ratio = 0.3\n"
    " set Thermal expansion = 1.2e-5\nend\n";
  const std::string linear = "subsection Hardening\n set Model = linear\n"
                             " set Initial yield stress = 250\n set Hardening modulus = 1000\nend\n";
  const std::vector<Model> models = {
    {"hypoelastic", "set Model = hypoelastic\n" + elastic, 0},
    {"J2 linear", "set Model = J2\n" + elastic + linear, 2e7},
    {"J2 saturation+softening",
     "set Model = J2\n" + elastic +
       "subsection Hardening\n set Model = saturation\n set Initial yield stress = 250\n"
       " set Hardening modulus = 129\n set Saturation stress = 400\n set Saturation exponent = 16.9\n"
       " subsection Thermal softening\n set Model = linear\n set Softening coefficient = 2e-3\n"
       " end\nend\n",
     0},
    {"Perzyna m=1",
     "set Model = Perzyna\n" + elastic + linear +
       "subsection Viscosity\n subsection Eta\n set Value = 100\n end\n"
       " subsection m\n set Value = 1\n end\nend\n",
     2e6},
    {"Perzyna m=10",
     "set Model = Perzyna\n" + elastic + linear +
       "subsection Viscosity\n subsection Eta\n set Value = 100\n end\n"
       " subsection m\n set Value = 10\n end\nend\n",
     2e6},
    // The tube's material (prm/tube_impact.prm): aluminium, linear hardening with
    // eq. 35's softening of the initial yield stress, in the adiabatic split.
    {"J2 tube adiabatic",
     "set Model = J2\nsubsection Elasticity\n set Bulk modulus = 70000\n set Poisson's ratio = 0.3\n"
     " set Density = 2.7e-9\n set Heat capacity = 0.9e9\n set Thermal expansion = 23.86e-6\nend\n"
     "subsection Hardening\n set Initial yield stress = 150\n set Hardening modulus = 50\n"
     " set Softened parameters = initial yield stress\n subsection Thermal softening\n"
     "  set Model = linear\n  set Softening coefficient = 2e-3\n end\nend\n",
     0, true},
  };
  // Elastic: 0.1 x yield strain; plastic: 10 x (virgin state, one update).
  const auto elastic_list = increments(0.1 * 250 / 200000, false);
  const auto plastic_list = increments(10 * 250 / 200000., false);
  // The tube's yield strain: 150 MPa / E, E = 9K(1 − 2ν)/... ≈ 84 000 MPa.
  const auto elastic_adiabatic = increments(0.1 * 150 / 84000., true);
  const auto plastic_adiabatic = increments(10 * 150 / 84000., true);

  std::printf("Material point updates per CPU second, one core, 3D, %.1f s per figure\n", seconds);
  std::printf("%-26s %-8s %18s %18s %18s  %s\n", "model", "branch", "stress|tangent /s",
              "dense tangent /s", "stress only /s", "target /s");
  const auto start = std::chrono::steady_clock::now();
  for (const auto &m : models)
    {
      if (!only.empty() && m.name != only)
        continue;
      const auto model = make_model(m.settings);
      auto       point = model->create_point({m.adiabatic});
      for (const bool plastic_branch : {false, true})
        {
          if ((plastic_branch && model->name() == "hypoelastic") ||
              (!branch.empty() && branch != (plastic_branch ? "plastic" : "elastic")))
            continue;
          const auto &list = m.adiabatic ? (plastic_branch ? plastic_adiabatic : elastic_adiabatic) :
                                           (plastic_branch ? plastic_list : elastic_list);
          unsigned long n1 = 0, n2 = 0, n3 = 0;
          bool          p1 = false, p2 = false, p3 = false;
          const bool    all = request_only.empty();
          const double  r1 = all || request_only == "st" ?
                               measure(*point, list,
                                       request_stress | request_tangent | request_factored_tangent,
                                       seconds, n1, p1, fixed) :
                               0.;
          const double r3 = all || request_only == "dense" ?
                              measure(*point, list, request_stress | request_tangent, seconds, n3,
                                      p3, fixed) :
                              0.;
          const double r2 = all || request_only == "s" ?
                              measure(*point, list, request_stress, seconds, n2, p2, fixed) :
                              0.;
          const bool p = p1 || p2 || p3; // the branch of the figure measured
          if (!all)
            p1 = p2 = p3 = p;
          char target[96] = "";
          if (plastic_branch && m.target_plastic > 0)
            std::snprintf(target, sizeof target, ">= %.0e: s|t %s, s %s", m.target_plastic,
                          r1 >= m.target_plastic ? "met" : "MISSED",
                          r2 >= m.target_plastic ? "met" : "MISSED");
          std::printf("%-26s %-8s %18.3e %18.3e %18.3e  %s\n", m.name.c_str(),
                      p1 ? "plastic" : "elastic", r1, r3, r2, target);
          if (p1 != plastic_branch || p2 != plastic_branch || p3 != plastic_branch)
            std::printf("  warning: the increments did not give the %s branch\n",
                        plastic_branch ? "plastic" : "elastic");
        }
    }
  std::printf("targets: >= 2e7/s J2 linear (plastic, issue 15), >= 2e6/s Perzyna (plastic), per core\n");
  std::printf("checksum %.17g, %.1f s\n", checksum,
              std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  return 0;
}
