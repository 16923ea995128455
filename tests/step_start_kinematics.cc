// The start-of-step kinematics kept per cell (StepStart, step_start.h): F_n
// and F̄_n = (J₀ₙ/J_n)^α F_n computed by a cell's first update of a step and
// read by the later ones. On one distorted cell with the tube's J2 material
// (plane strain and axisymmetric, standard and F-bar, Q1 and Q2), a sequence
// of steps with several Newton iterates each, a cut-back (the step again from
// the same u_n), and an update that fails part-way (an inverted element)
// before the next valid one. Independent answers:
//  - the update without kept data (F_n and F̄_n from u_n at every update):
//    the strain and rotation increments, F̄, the stress and the tangent must
//    be the same bits;
//  - the F_n kept for step n + 1 must be the F of step n's last iterate (the
//    same u, computed by the other branch of the kernel): the same bits.
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/dofs/dof_handler.h>

#include <anvil/material/material_point.h>
#include <anvil/mechanics/assembly_kernels.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>

using namespace dealii;
using namespace anvil;
using namespace anvil::MechanicsAssembly;

namespace
{
  std::mt19937                           rng(11);
  std::uniform_real_distribution<double> uniform(-1, 1);

  const char *const tube_material =
    "set Model = J2\nsubsection Elasticity\n set Bulk modulus = 70000\n set Poisson's ratio = 0.3\n"
    " set Density = 2.7e-9\n set Heat capacity = 0.9e9\n set Thermal expansion = 23.86e-6\nend\n"
    "subsection Hardening\n set Initial yield stress = 150\n set Hardening modulus = 50\nend\n";

  /// One assembly's stores and kernel; @p keep: with a StepStart.
  struct Run
  {
    Run(const DoFHandler<2> &dofs, const Formulation<2> &formulation, const MaterialModel &model,
        const Mapping<2> &mapping, const Quadrature<2> &quadrature, const bool keep)
      : scratch(mapping, dofs.get_fe(), quadrature, QGauss<1>(2),
                update_values | update_gradients | update_JxW_values | update_quadrature_points)
    {
      const auto        &tria = dofs.get_triangulation();
      const unsigned int n_q  = quadrature.size();
      block = model.create_points(tria.n_active_cells() * n_q);
      points.reinit(tria, n_q);
      points.raw() = block.points;
      for (auto *d : {&heat, &thermoelastic, &work})
        d->reinit(tria, n_q, 0.);
      start.reinit(tria, dofs.get_fe().n_dofs_per_cell(), n_q);
      context.formulation           = &formulation;
      context.with_matrix           = true;
      context.request               = request_stress | request_tangent;
      context.time_step             = 1e-5;
      context.points                = &points;
      context.heat_sources          = &heat;
      context.thermoelastic_sources = &thermoelastic;
      context.plastic_work_rates    = &work;
      context.step_start            = keep ? &start : nullptr;
    }
    PointBlock                 block; // owns the points
    PointData<MaterialPoint *> points;
    PointData<double>          heat, thermoelastic, work;
    StepStart                                 start;
    Context<2>                                context;
    ScratchData<2>                            scratch;
  };

  bool same(const void *a, const void *b, const std::size_t n) { return std::memcmp(a, b, n) == 0; }

  /// The factored tangent field by field (its struct has padding after the flags).
  bool same_factored(const FactoredTangent &a, const FactoredTangent &b)
  {
    return a.active == b.active && a.rank_one == b.rank_one && a.bulk == b.bulk &&
           a.deviatoric == b.deviatoric && a.normal == b.normal &&
           a.sensitivity_deviatoric == b.sensitivity_deviatoric &&
           a.sensitivity_normal == b.sensitivity_normal && same(a.n, b.n, sizeof(a.n)) &&
           same(a.u, b.u, sizeof(a.u)) && same(a.v, b.v, sizeof(a.v)) && same(a.w, b.w, sizeof(a.w));
  }

  /// The bits every point's update produced agree between the two runs (the
  /// tangent in the form the law gave: dense, or factored when it was asked).
  bool same_points(const ScratchData<2> &a, const ScratchData<2> &b)
  {
    for (unsigned int q = 0; q < a.points.size(); ++q)
      {
        const PointValues &p = a.points[q], &r = b.points[q];
        if (!same(&p.F_mat, &r.F_mat, sizeof(p.F_mat)) || p.beta != r.beta ||
            !same(&p.kin.strain_increment, &r.kin.strain_increment, sizeof(p.kin.strain_increment)) ||
            !same(&p.kin.rotation_increment, &r.kin.rotation_increment,
                  sizeof(p.kin.rotation_increment)) ||
            !same(&p.response.stress, &r.response.stress, sizeof(p.response.stress)) ||
            !same_factored(p.response.factored, r.response.factored) ||
            (!p.response.factored.active &&
             !same(&p.response.tangent, &r.response.tangent, sizeof(p.response.tangent))))
          return false;
      }
    return true;
  }

  bool check(const bool axisymmetric, const bool f_bar, const unsigned int degree)
  {
    Triangulation<2> tria;
    GridGenerator::hyper_cube(tria, 1, 2); // off the axis: R > 0
    for (auto &v : tria.get_vertices())
      const_cast<Point<2> &>(v) += Point<2>(0.15 * uniform(rng), 0.15 * uniform(rng));
    const FESystem<2> fe(FE_Q<2>(degree), 2);
    DoFHandler<2>     dofs(tria);
    dofs.distribute_dofs(fe);
    const MappingQ<2>    mapping(1);
    const QGauss<2>      quadrature(degree + 1);
    const Formulation<2> formulation(fe, axisymmetric, f_bar);
    const auto           model = MaterialFactory::create_from_text(tube_material);
    Run                  plain(dofs, formulation, *model, mapping, quadrature, false);
    Run                  kept(dofs, formulation, *model, mapping, quadrature, true);
    const auto           cell = dofs.begin_active();
    const unsigned int   n    = fe.n_dofs_per_cell();
    for (Run *r : {&plain, &kept})
      r->scratch.reinit(cell, nullptr, formulation.component, f_bar, axisymmetric);

    std::vector<double>       u_old(n, 0.), u(n, 0.);
    std::vector<Tensor<2, 3>> F_last(quadrature.size());
    unsigned int updates = 0, differ = 0, kept_wrong = 0, failed_as_expected = 0;
    // Step s: iterates around u_old + s-th increment (plastic after the first steps).
    for (unsigned int step = 0; step < 5; ++step)
      {
        std::vector<double> target(n);
        for (unsigned int i = 0; i < n; ++i)
          target[i] = u_old[i] + 0.02 * uniform(rng);
        // Step 2 is cut back once (its iterates again, from the same u_n); step 3
        // starts with an update that inverts the element (it fails part-way).
        const unsigned int attempts = step == 2 ? 2 : 1;
        for (unsigned int attempt = 0; attempt < attempts; ++attempt)
          for (unsigned int it = 0; it < 3; ++it)
            {
              const bool invert = step == 3 && it == 0;
              for (unsigned int i = 0; i < n; ++i)
                // (Vertex 3, dofs 6 and 7, pushed across the diagonal: the
                // points near it invert, those near vertex 0 do not.)
                u[i] = target[i] + (invert && (i == 6 || i == 7) ? -1.6 : 1e-3 * uniform(rng) / (it + 1));
              bool ok[2];
              for (unsigned int k = 0; k < 2; ++k)
                {
                  Run &r = k == 0 ? plain : kept;
                  r.scratch.local_u     = u;
                  r.scratch.local_u_old = u_old;
                  CopyData copy(n, quadrature.size());
                  ok[k] = MaterialPointUpdate<2>(r.context).update(cell, r.scratch, copy);
                }
              ++updates;
              if (invert)
                {
                  failed_as_expected += !ok[0] && !ok[1];
                  continue;
                }
              if (!ok[0] || !ok[1] || !same_points(plain.scratch, kept.scratch))
                ++differ;
              if (it == 0 && attempt == 0 && step > 0)
                // F_n kept by this step's first update against the last iterate's F.
                for (unsigned int q = 0; q < quadrature.size(); ++q)
                  kept_wrong += !same(&kept.start.points[cell][q].F_old, &F_last[q],
                                      sizeof(Tensor<2, 3>));
            }
        for (unsigned int q = 0; q < quadrature.size(); ++q)
          F_last[q] = kept.scratch.points[q].F;
        for (Run *r : {&plain, &kept})
          for (auto &p : r->points.raw())
            p->commit();
        u_old = u;
      }
    const bool ok = differ == 0 && kept_wrong == 0 && failed_as_expected == 1;
    std::printf("%-13s %-8s Q%u: %u updates, %u differ from the update without kept data "
                "(expected 0), %u kept F_n differ from the last iterate's F (expected 0), "
                "inverted element refused by both: %s: %s\n",
                axisymmetric ? "axisymmetric" : "plane strain", f_bar ? "F-bar" : "standard",
                degree, updates, differ, kept_wrong, failed_as_expected == 1 ? "yes" : "no",
                ok ? "ok" : "FAIL");
    return ok;
  }
} // namespace

int main()
{
  bool ok = true;
  for (const bool axisymmetric : {false, true})
    for (const bool f_bar : {false, true})
      for (const unsigned int degree : {1u, 2u})
        ok = check(axisymmetric, f_bar, degree) && ok;
  std::printf("%s\n", ok ? "PASSED" : "FAILED");
  return ok ? 0 : 1;
}
