// The planar stress-divergence kernel (stress_divergence.cc, assemble_planar:
// F⁻¹ and σF⁻ᵀ by their 2x2 blocks, A = ∂P/∂F over the 4 or 5 planar
// directions from the in-plane components of δσ, ∂F/∂u_a sparse at compile
// time) against the general kernel (3x3 tensors, A on dense 9x9 storage,
// G_a dense), on one distorted cell with random states at every point:
// plane strain and axisymmetric, standard and F-bar, Q1 and Q2, with and
// without the adiabatic split's ∂σ/∂ln J, identity or general sensitivity
// ∂σ/∂σ̃_n, prestress with and without the out-of-plane shears 02, 12, and
// a Cauchy stress with them (they must not enter). Independent answer: the
// general kernel. Expected: the same bits (the planar kernel leaves out only
// exact zeros); fails above 1e-13 of the largest entry.
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <anvil/mechanics/assembly_kernels.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>

using namespace dealii;
using namespace anvil;
using namespace anvil::MechanicsAssembly;

namespace
{
  std::mt19937                           rng(7);
  std::uniform_real_distribution<double> uniform(-1, 1);

  /// A material point that only holds a committed stress (what the kernel reads).
  class StressOnlyPoint : public MaterialPoint
  {
  public:
    void update(const MaterialIncrement &, MaterialRequest, MaterialResponse &) override
    {
      throw std::logic_error("not used");
    }
    void                         commit() override {}
    void                         revert() override {}
    const SymmetricTensor<2, 3> &stress() const override { return sigma; }
    const SymmetricTensor<2, 3> &committed_stress() const override { return sigma; }
    void                set_stress(const SymmetricTensor<2, 3> &s) override { sigma = s; }
    std::vector<double> save_state() const override { return {}; }
    void                load_state(const std::vector<double> &) override {}

  private:
    SymmetricTensor<2, 3> sigma;
  };

  SymmetricTensor<2, 3> random_stress(const double scale, const bool out_of_plane)
  {
    SymmetricTensor<2, 3> s;
    for (unsigned int i = 0; i < 6; ++i)
      s.access_raw_entry(i) = scale * uniform(rng);
    if (!out_of_plane)
      s[0][2] = s[1][2] = 0;
    return s;
  }

  SymmetricTensor<4, 3> random_tangent(const double scale)
  {
    SymmetricTensor<4, 3> t;
    for (unsigned int i = 0; i < 36; ++i)
      t.access_raw_entry(i) = scale * uniform(rng);
    return t;
  }

  /// [F_2x2, 0; 0, F₃₃] near the identity (F₃₃ = 1 in plane strain).
  Tensor<2, 3> random_planar_gradient(const bool hoop)
  {
    Tensor<2, 3> F;
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        F[i][j] = (i == j ? 1. : 0.) + 0.2 * uniform(rng);
    F[2][2] = hoop ? 1 + 0.1 * uniform(rng) : 1.;
    return F;
  }

  struct Case
  {
    bool axisymmetric, f_bar, adiabatic, identity, out_of_plane;
    unsigned int degree;
  };

  /// Largest |a − b| over the largest |b|, and how many entries differ at all.
  double compare(const std::vector<double> &a, const std::vector<double> &b, unsigned int &differ)
  {
    double scale = 0, diff = 0;
    differ       = 0;
    for (std::size_t i = 0; i < a.size(); ++i)
      {
        scale = std::max(scale, std::abs(b[i]));
        diff  = std::max(diff, std::abs(a[i] - b[i]));
        differ += a[i] != b[i];
      }
    return diff / std::max(scale, 1e-300);
  }

  bool check(const Case &c, const unsigned int n_states)
  {
    Triangulation<2> tria;
    GridGenerator::hyper_cube(tria, 1, 2); // off the axis: R > 0
    for (auto &v : tria.get_vertices())
      const_cast<Point<2> &>(v) += Point<2>(0.15 * uniform(rng), 0.15 * uniform(rng));
    const FESystem<2>  fe(FE_Q<2>(c.degree), 2);
    const MappingQ<2>  mapping(1);
    const QGauss<2>    quadrature(c.degree + 1);
    const QGauss<1>    face_quadrature(c.degree + 1);
    const Formulation<2> formulation(fe, c.axisymmetric, c.f_bar);
    Context<2>           context;
    context.formulation = &formulation;
    context.with_matrix = true;
    ScratchData<2> scratch(mapping, fe, quadrature, face_quadrature,
                           update_values | update_gradients | update_JxW_values |
                             update_quadrature_points);
    scratch.reinit(tria.begin_active(), nullptr, formulation.component, c.f_bar, c.axisymmetric);
    const StressDivergence<2> planar(context), general(context, false);
    const unsigned int        n_dofs = fe.n_dofs_per_cell(), n_q = quadrature.size();
    std::vector<StressOnlyPoint> material(n_q);

    double       worst  = 0;
    unsigned int differ = 0;
    for (unsigned int state = 0; state < n_states; ++state)
      {
        for (unsigned int b = 0; b < n_dofs; ++b)
          scratch.center_trace[b] = uniform(rng);
        for (unsigned int q = 0; q < n_q; ++q)
          {
            PointValues &p = scratch.points[q];
            p.R            = formulation.radius(scratch.cell, q);
            p.w            = formulation.weight(scratch.cell, q, p.R);
            p.F            = random_planar_gradient(c.axisymmetric);
            p.J            = determinant(p.F);
            p.beta         = c.f_bar ? 1 + 0.1 * uniform(rng) : 1.;
            p.F_mat        = formulation.bar(p.F, p.beta);
            Tensor<2, 3> F_mat_old = random_planar_gradient(c.axisymmetric);
            p.kin.reinit(p.F_mat, F_mat_old, ObjectiveRate::jaumann, kinematics_all);
            material[q].set_stress(random_stress(100, c.out_of_plane));
            p.point                             = &material[q];
            p.adiabatic                         = c.adiabatic;
            p.response.stress                   = random_stress(200, true);
            p.response.tangent                  = random_tangent(1e5);
            p.response.sensitivity_is_identity  = c.identity;
            p.response.rotated_stress_sensitivity = random_tangent(1);
            p.response.volume_ratio_sensitivity = random_stress(50, true);
          }
        std::vector<double> results[2];
        for (unsigned int k = 0; k < 2; ++k)
          {
            CopyData copy(n_dofs, n_q);
            copy.matrix   = 0;
            copy.internal = 0;
            (k == 0 ? planar : general).assemble(scratch, copy);
            results[k].assign(copy.matrix.begin(), copy.matrix.end());
            results[k].insert(results[k].end(), copy.internal.begin(), copy.internal.end());
          }
        unsigned int d = 0;
        worst          = std::max(worst, compare(results[0], results[1], d));
        differ += d;
      }
    const bool ok = worst <= 1e-13;
    std::printf("%-13s %-8s Q%u adiabatic %d identity S %d prestress 02/12 %d: "
                "max |planar - general| / max |general| = %.2e (%u entries differ), "
                "expected <= 1e-13: %s\n",
                c.axisymmetric ? "axisymmetric" : "plane strain", c.f_bar ? "F-bar" : "standard",
                c.degree, c.adiabatic, c.identity, c.out_of_plane, worst, differ,
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
        for (const bool adiabatic : {false, true})
          for (const bool identity : {false, true})
            for (const bool out_of_plane : {false, true})
              ok = check({axisymmetric, f_bar, adiabatic, identity, out_of_plane, degree}, 5) && ok;
  std::printf("%s\n", ok ? "PASSED" : "FAILED");
  return ok ? 0 : 1;
}
