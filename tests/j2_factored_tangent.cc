// The J2 tangent in factored form (FactoredTangent, request_factored_tangent:
// C = K δ⊗δ + c_d I_dev + c_n n⊗n [+ u⊗v], S likewise) against the dense
// tangent the same point writes without the request, on random states:
//  1. the expanded factored C and S against the dense entries;
//  2. δσ of cauchy_tangent (the general 3x3 path, 3D; the planar path with
//     the hoop direction) from either form;
//  3. the stress divergence's matrix and residual (planar and general
//     kernels, plane strain and axisymmetric, 3D, standard and F-bar) with
//     every point's response dense or factored;
//  4. δσ of the factored form against central differences of σ(F).
// Models: J2 linear and saturation with softening, Perzyna m = 10, the
// tube's adiabatic J2 (which declines the request: the dense form, checked
// the same way); elastic and plastic branches.
// Independent answers: the dense tangent (1-3, fails above 1e-12 relative
// to the largest entry) and finite differences (4, fails above 1e-6).
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <anvil/material/kinematics.h>
#include <anvil/mechanics/assembly_kernels.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

using namespace dealii;
using namespace anvil;
using namespace anvil::MechanicsAssembly;

namespace
{
  std::mt19937                           rng(11);
  std::uniform_real_distribution<double> uniform(-1, 1);

  struct Model
  {
    const char *name;
    std::string settings;
    bool        adiabatic;
  };

  const std::string elastic = "subsection Elasticity\n set Young's modulus = 200000\n"
                              " set Poisson's ratio = 0.3\n set Thermal expansion = 1.2e-5\nend\n";
  const std::string linear  = "subsection Hardening\n set Model = linear\n"
                              " set Initial yield stress = 250\n set Hardening modulus = 1000\nend\n";

  std::vector<Model> models()
  {
    return {
      {"J2 linear", "set Model = J2\n" + elastic + linear, false},
      {"J2 saturation+softening",
       "set Model = J2\n" + elastic +
         "subsection Hardening\n set Model = saturation\n set Initial yield stress = 250\n"
         " set Hardening modulus = 129\n set Saturation stress = 400\n set Saturation exponent = 16.9\n"
         " subsection Thermal softening\n set Model = linear\n set Softening coefficient = 2e-3\n"
         " end\nend\n",
       false},
      {"Perzyna m=10",
       "set Model = Perzyna\n" + elastic + linear +
         "subsection Viscosity\n subsection Eta\n set Value = 100\n end\n"
         " subsection m\n set Value = 10\n end\nend\n",
       false},
      {"J2 tube adiabatic",
       "set Model = J2\nsubsection Elasticity\n set Bulk modulus = 70000\n set Poisson's ratio = 0.3\n"
       " set Density = 2.7e-9\n set Heat capacity = 0.9e9\n set Thermal expansion = 23.86e-6\nend\n"
       "subsection Hardening\n set Initial yield stress = 150\n set Hardening modulus = 50\n"
       " set Softened parameters = initial yield stress\n subsection Thermal softening\n"
       "  set Model = linear\n  set Softening coefficient = 2e-3\n end\nend\n",
       true},
    };
  }

  /// Near the identity by @p size; [F_2x2, 0; 0, F₃₃] if @p planar (F₃₃ = 1 unless @p hoop).
  Tensor<2, 3> random_gradient(const double size, const bool planar, const bool hoop)
  {
    Tensor<2, 3> F;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        if (!planar || (i < 2 && j < 2))
          F[i][j] = (i == j ? 1. : 0.) + size * uniform(rng);
    if (planar)
      F[2][2] = hoop ? 1 + size * uniform(rng) : 1.;
    return F;
  }

  SymmetricTensor<2, 3> random_stress(const double scale, const bool planar)
  {
    SymmetricTensor<2, 3> s;
    for (unsigned int i = 0; i < 6; ++i)
      s.access_raw_entry(i) = scale * uniform(rng);
    if (planar)
      s[0][2] = s[1][2] = 0;
    return s;
  }

  /// One update of a point at σₙ from the kinematics @p kin, with or without the factored request.
  MaterialResponse update(MaterialPoint &point, const IncrementalKinematics &kin,
                          const bool adiabatic, const bool factored)
  {
    MaterialIncrement inc;
    inc.strain_increment      = kin.strain_increment;
    inc.rotation_increment    = kin.rotation_increment;
    inc.temperature           = 400;
    inc.temperature_increment = 5;
    inc.time_step             = 1e-4;
    inc.adiabatic             = adiabatic;
    MaterialResponse r;
    point.update(inc,
                 factored ? request_stress | request_tangent | request_factored_tangent :
                            request_stress | request_tangent,
                 r);
    return r;
  }

  double largest(const double *a, const std::size_t n)
  {
    double m = 0;
    for (std::size_t i = 0; i < n; ++i)
      m = std::max(m, std::abs(a[i]));
    return m;
  }
  double difference(const double *a, const double *b, const std::size_t n)
  {
    double m = 0;
    for (std::size_t i = 0; i < n; ++i)
      m = std::max(m, std::abs(a[i] - b[i]));
    return m;
  }

  struct Worst
  {
    double moduli = 0, dsigma = 0, fd = 0;
    unsigned int plastic = 0, elastic = 0;
  };

  /// 1, 2 and 4 for one model: 3D (general path) and planar (hoop directions).
  void check_point(const Model &m, const MaterialModel &model, const bool planar,
                   const bool plastic, Worst &worst)
  {
    auto point = model.create_point({m.adiabatic});
    point->set_stress(random_stress(plastic ? 120 : 20, planar));
    const Tensor<2, 3> F_old = random_gradient(0.1, planar, true);
    const double       size  = plastic ? 1e-2 : 1e-5;
    // F = (I + small) F_n: the increment's size decides the branch.
    const Tensor<2, 3> F = random_gradient(size, planar, true) * F_old;
    IncrementalKinematics kin;
    kin.reinit(F, F_old, ObjectiveRate::jaumann, planar ? kinematics_all : 3u);
    const MaterialResponse dense = update(*point, kin, m.adiabatic, false),
                           fact  = update(*point, kin, m.adiabatic, true);
    // The adiabatic update declines the request (its rank-one terms would
    // change the tangent's round-off): the dense form, the same bits.
    if (fact.factored.active == m.adiabatic || dense.factored.active ||
        fact.sensitivity_is_identity != dense.sensitivity_is_identity)
      throw std::runtime_error("the factored form was not (only) given on request");
    (dense.equivalent_plastic_strain > point->committed_equivalent_plastic_strain() ?
       worst.plastic : worst.elastic)++;
    // 1. The moduli.
    SymmetricTensor<4, 3> C = fact.tangent, S = fact.rotated_stress_sensitivity;
    if (fact.factored.active)
      fact.factored.expand(C, &S);
    double err = difference(C.begin_raw(), dense.tangent.begin_raw(), 36) /
                 largest(dense.tangent.begin_raw(), 36);
    if (!dense.sensitivity_is_identity)
      err = std::max(err, difference(S.begin_raw(), dense.rotated_stress_sensitivity.begin_raw(), 36) /
                            largest(dense.rotated_stress_sensitivity.begin_raw(), 36));
    worst.moduli = std::max(worst.moduli, err);
    // 2. δσ per direction.
    const TangentDirections directions = TangentDirections::in_plane(planar ? 2 : 3, planar);
    std::array<SymmetricTensor<2, 3>, 9> ds_dense, ds_fact;
    cauchy_tangent(kin, point->committed_stress(), dense, directions, ds_dense.data());
    cauchy_tangent(kin, point->committed_stress(), fact, directions, ds_fact.data());
    const double scale = largest(ds_dense[0].begin_raw(), 6 * directions.n);
    for (unsigned int d = 0; d < directions.n; ++d)
      worst.dsigma = std::max(worst.dsigma, difference(ds_fact[d].begin_raw(), ds_dense[d].begin_raw(), 6) /
                                              scale);
    // 4. Central differences of σ(F) at fixed F_n.
    const double h = 1e-7;
    for (unsigned int d = 0; d < directions.n; ++d)
      {
        const unsigned int k = directions.kl[d].first, L = directions.kl[d].second;
        Tensor<2, 3>       Fp = F, Fm = F;
        Fp[k][L] += h, Fm[k][L] -= h;
        IncrementalKinematics kp, km;
        kp.reinit(Fp, F_old, ObjectiveRate::jaumann, planar ? kinematics_all : 3u);
        km.reinit(Fm, F_old, ObjectiveRate::jaumann, planar ? kinematics_all : 3u);
        const SymmetricTensor<2, 3> fd =
          (update(*point, kp, m.adiabatic, false).stress - update(*point, km, m.adiabatic, false).stress) /
          (2 * h);
        worst.fd = std::max(worst.fd, difference(ds_fact[d].begin_raw(), fd.begin_raw(), 6) / scale);
      }
  }

  /// 3: the stress divergence on one distorted cell, every point a J2 point
  /// with a random state, responses dense or factored.
  template <int dim>
  double check_assembly(const MaterialModel &model, const bool adiabatic, const bool axisymmetric,
                        const bool f_bar, const bool plastic)
  {
    Triangulation<dim> tria;
    GridGenerator::hyper_cube(tria, 1, 2);
    for (auto &v : tria.get_vertices())
      for (unsigned int i = 0; i < dim; ++i)
        const_cast<Point<dim> &>(v)[i] += 0.15 * uniform(rng);
    const FESystem<dim>    fe(FE_Q<dim>(1), dim);
    const MappingQ<dim>    mapping(1);
    const QGauss<dim>      quadrature(2);
    const QGauss<dim - 1>  face_quadrature(2);
    const Formulation<dim> formulation(fe, axisymmetric, f_bar);
    Context<dim>           context;
    context.formulation = &formulation;
    context.with_matrix = true;
    ScratchData<dim> scratch(mapping, fe, quadrature, face_quadrature,
                             update_values | update_gradients | update_JxW_values |
                               update_quadrature_points);
    scratch.reinit(tria.begin_active(), nullptr, formulation.component, f_bar, axisymmetric);
    const StressDivergence<dim> planar(context), general(context, false);
    const unsigned int          n_dofs = fe.n_dofs_per_cell(), n_q = quadrature.size();
    const PointBlock             block  = model.create_points(n_q, {adiabatic});
    const auto                  &points = block.points;
    std::vector<MaterialResponse>               responses[2];
    for (unsigned int b = 0; b < n_dofs; ++b)
      scratch.center_trace[b] = uniform(rng);
    for (unsigned int q = 0; q < n_q; ++q)
      {
        PointValues &p = scratch.points[q];
        p.R            = formulation.radius(scratch.cell, q);
        p.w            = formulation.weight(scratch.cell, q, p.R);
        const Tensor<2, 3> F_old = random_gradient(0.1, dim == 2, axisymmetric);
        p.F            = random_gradient(plastic ? 1e-2 : 1e-5, dim == 2, axisymmetric) * F_old;
        p.J            = determinant(p.F);
        p.beta         = f_bar ? 1 + 0.01 * uniform(rng) : 1.;
        p.F_mat        = formulation.bar(p.F, p.beta);
        p.kin.reinit(p.F_mat, F_old, ObjectiveRate::jaumann, dim == 2 ? kinematics_all : 3u);
        points[q]->set_stress(random_stress(plastic ? 120 : 20, dim == 2));
        p.point     = points[q];
        p.adiabatic = adiabatic;
        for (unsigned int k = 0; k < 2; ++k)
          responses[k].push_back(update(*points[q], p.kin, adiabatic, k == 1));
      }
    double worst = 0;
    for (const StressDivergence<dim> *kernel : {&planar, &general})
      {
        std::vector<double> results[2];
        for (unsigned int k = 0; k < 2; ++k)
          {
            for (unsigned int q = 0; q < n_q; ++q)
              scratch.points[q].response = responses[k][q];
            CopyData copy(n_dofs, n_q);
            copy.matrix   = 0;
            copy.internal = 0;
            kernel->assemble(scratch, copy);
            results[k].assign(copy.matrix.begin(), copy.matrix.end());
          }
        worst = std::max(worst, difference(results[1].data(), results[0].data(), results[0].size()) /
                                  largest(results[0].data(), results[0].size()));
      }
    return worst;
  }
} // namespace

int main()
{
  bool ok = true;
  for (const Model &m : models())
    {
      const auto model = MaterialFactory::create_from_text(m.settings);
      for (const bool planar : {false, true})
        {
          Worst worst;
          for (unsigned int state = 0; state < 20; ++state)
            check_point(m, *model, planar, state % 2 == 1, worst);
          const bool pass = worst.moduli <= 1e-12 && worst.dsigma <= 1e-12 && worst.fd <= 1e-6;
          std::printf("%-24s %-6s (%u plastic, %u elastic): |C, S factored - dense| %.1e, "
                      "|dsigma factored - dense| %.1e (<= 1e-12), |dsigma - FD| %.1e (<= 1e-6): %s\n",
                      m.name, planar ? "planar" : "3D", worst.plastic, worst.elastic, worst.moduli,
                      worst.dsigma, worst.fd, pass ? "ok" : "FAIL");
          ok = ok && pass && worst.plastic > 0 && worst.elastic > 0;
        }
      for (const bool plastic : {false, true})
        for (const bool f_bar : {false, true})
          {
            const double e[3] = {check_assembly<2>(*model, m.adiabatic, false, f_bar, plastic),
                                 check_assembly<2>(*model, m.adiabatic, true, f_bar, plastic),
                                 check_assembly<3>(*model, m.adiabatic, false, f_bar, plastic)};
            const bool pass = std::max({e[0], e[1], e[2]}) <= 1e-12;
            std::printf("%-24s assembly %-7s %-8s: |K factored - dense| / |K|: plane strain %.1e, "
                        "axisymmetric %.1e, 3D %.1e (<= 1e-12): %s\n",
                        m.name, plastic ? "plastic" : "elastic", f_bar ? "F-bar" : "standard", e[0],
                        e[1], e[2], pass ? "ok" : "FAIL");
            ok = ok && pass;
          }
    }
  std::printf("%s\n", ok ? "PASSED" : "FAILED");
  return ok ? 0 : 1;
}
