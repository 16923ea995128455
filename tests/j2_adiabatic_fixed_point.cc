// The adiabatic J2 update's fixed point x = ΔT_ad(Δε, σ̃ₙ, T + x) (Armero–Simo;
// j2_plasticity.cc) checked from outside the iteration that finds it, and the
// planar kinematics' kept zeros:
//  1. an isothermal update at T + x, T_n-increment + x (the same increment)
//     has heat sources that give ΔT_ad = x, and the same stress: the point's x is the fixed point
//     whatever its iteration (Newton first step from the last tangent's
//     ∂f/∂x, then secant) did, to the iteration's tolerance (1e-12);
//  2. the same increment again on the same point, now starting from its last
//     x and ∂f/∂x (Newton's repeated updates within a step), and with the
//     next increment of a sequence: equal to a fresh point's answer to 1e-11;
//     elastic adiabatic points keep ∂σ/∂σ̃ₙ = identity (flagged);
//  3. IncrementalKinematics: the planar path after a general 3x3 one on the
//     same object equals the planar path on a fresh object bit for bit (the
//     planar path writes only the block and keeps the zeros around it).
// Prints the largest relative differences; fails above the tolerances.
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <anvil/material/kinematics.h>
#include <anvil/material/material_point.h>

#include "adiabatic_materials.h"

#include <cmath>
#include <iostream>

using namespace dealii;
using namespace anvil;

namespace
{
  double relative(const SymmetricTensor<2, 3> &a, const SymmetricTensor<2, 3> &b)
  {
    return (a - b).norm() / std::max(b.norm(), 1e-300);
  }

  MaterialIncrement increment(const SymmetricTensor<2, 3> &de, const bool adiabatic)
  {
    return testing::adiabatic_test_increment(de, adiabatic);
  }

  struct Errors
  {
    double fixed_point = 0, stress = 0, repeat = 0;
    bool   identity_ok = true;
  };

  Errors check(const MaterialModel &model, const SymmetricTensor<2, 3> &sigma_n,
               const SymmetricTensor<2, 3> &de, const bool print)
  {
    Errors                 e;
    const MaterialRequest  request = request_stress | request_tangent;
    auto                   point   = model.create_point({true});
    point->set_stress(sigma_n);
    MaterialResponse adiabatic;
    point->update(increment(de, true), request, adiabatic);
    const double x = adiabatic.adiabatic_temperature_increment;
    if (adiabatic.equivalent_plastic_strain == 0 && !adiabatic.sensitivity_is_identity)
      e.identity_ok = false;

    // 1. Isothermal at T + x: ΔT_ad(T + x) = x.
    {
      auto iso = model.create_point();
      iso->set_stress(sigma_n);
      MaterialIncrement inc = increment(de, false);
      inc.temperature += x;
      inc.temperature_increment += x;
      MaterialResponse r;
      iso->update(inc, request, r);
      // ΔT_ad(T + x) from the isothermal update's heat sources (it does not
      // form ΔT_ad itself): ρ₀c ΔT_ad / J = Δt (χ Ẇirr + Ẇthel), eq. 20–22.
      const double dT_ad = inc.time_step * inc.volume_ratio *
                           (r.plastic_dissipation_rate + r.thermoelastic_heating_rate) /
                           (model.density() * model.heat_capacity());
      e.fixed_point = std::abs(dT_ad - x) / (1 + std::abs(x));
      e.stress      = relative(r.stress, adiabatic.stress);
      if (print)
        std::cout << "    x = " << x << " K, dT_ad(T + x) = " << dT_ad << " K" << std::endl;
    }
    // 2. Repeated updates (the point now starts from its x and ∂f/∂x), and a
    // sequence of increments against fresh points.
    for (const double scale : {1.0, 1.0, 1.003, 0.97, 1.01})
      {
        MaterialResponse r, fresh_r;
        point->update(increment(scale * de, true), request, r);
        auto fresh = model.create_point({true});
        fresh->set_stress(sigma_n);
        fresh->update(increment(scale * de, true), request, fresh_r);
        e.repeat = std::max({e.repeat, relative(r.stress, fresh_r.stress),
                             std::abs(r.adiabatic_temperature_increment -
                                      fresh_r.adiabatic_temperature_increment) /
                               (1 + std::abs(fresh_r.adiabatic_temperature_increment))});
        if (r.equivalent_plastic_strain == 0 && !r.sensitivity_is_identity)
          e.identity_ok = false;
      }
    return e;
  }

  /// A planar gradient: rotation by @p angle about z, stretch, hoop stretch.
  Tensor<2, 3> planar_gradient(const double angle, const double stretch)
  {
    Tensor<2, 3> F;
    F[0][0] = std::cos(angle) * (1 + stretch), F[0][1] = -std::sin(angle) * 0.98;
    F[1][0] = std::sin(angle) * (1 + stretch), F[1][1] = std::cos(angle) * 0.98;
    F[0][1] += 0.03;
    F[2][2] = 1 + 0.5 * stretch;
    return F;
  }

  /// 0 if every member of @p a equals @p b's bit for bit, else 1.
  unsigned int differs(const IncrementalKinematics &a, const IncrementalKinematics &b)
  {
    unsigned int n = 0;
    for (const auto member : {&IncrementalKinematics::F_inv, &IncrementalKinematics::F_half_inv,
                              &IncrementalKinematics::dL, &IncrementalKinematics::A_inv,
                              &IncrementalKinematics::A_half_inv,
                              &IncrementalKinematics::half_rotation,
                              &IncrementalKinematics::rotation_increment})
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = 0; j < 3; ++j)
          n += !((a.*member)[i][j] == (b.*member)[i][j]);
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = 0; j < 3; ++j)
        n += !(a.mid_strain[i][j] == b.mid_strain[i][j]) +
             !(a.strain_increment[i][j] == b.strain_increment[i][j]);
    n += !(a.J == b.J) + (a.planar != b.planar);
    return n;
  }
} // namespace

int main()
{
  const auto cases = testing::j2_softening_cases(testing::steel_elastic);
  SymmetricTensor<2, 3> plastic, elastic_de; // a plastic step, and a small elastic one
  plastic[0][0] = 0.012, plastic[1][1] = -0.004, plastic[2][2] = 0.001, plastic[0][1] = 0.008;
  elastic_de[0][0] = 1e-4, elastic_de[1][1] = -3e-5, elastic_de[2][2] = 2e-5, elastic_de[0][1] = 2e-5;
  SymmetricTensor<2, 3> inside, on_surface;
  inside[0][0] = 30, inside[1][1] = -10, inside[0][1] = 8;
  on_surface[0][0] = 150, on_surface[1][1] = -40, on_surface[0][1] = 35, on_surface[2][2] = 20;

  double fixed_point = 0, stress = 0, repeat = 0;
  bool   identity_ok = true;
  for (const auto &[name, settings] : cases)
    {
      const auto model = MaterialFactory::create_from_text(settings);
      std::cout << name << std::endl;
      for (const auto *de : {&plastic, &elastic_de})
        for (const auto *sigma_n : {&inside, &on_surface})
          {
            const Errors e = check(*model, *sigma_n, *de, de == &plastic && sigma_n == &inside);
            std::cout << "  " << (de == &plastic ? "plastic" : "elastic") << " step, sigma_n "
                      << (sigma_n == &inside ? "inside" : "on the surface")
                      << ": |dT_ad(T + x) - x| / (1 + |x|) = " << e.fixed_point
                      << ", stress " << e.stress << ", repeated / sequence " << e.repeat
                      << (e.identity_ok ? "" : "  (elastic point without identity sensitivity)")
                      << std::endl;
            fixed_point = std::max(fixed_point, e.fixed_point);
            stress      = std::max(stress, e.stress);
            repeat      = std::max(repeat, e.repeat);
            identity_ok = identity_ok && e.identity_ok;
          }
    }

  // 3. The planar path after the general one.
  unsigned int kinematics_differences = 0;
  for (unsigned int k = 0; k < 20; ++k)
    {
      const Tensor<2, 3> F = planar_gradient(0.05 * k, 0.01 * k), F_old = planar_gradient(0.04 * k, 0.008 * k);
      Tensor<2, 3>       G = F; // a general gradient first
      G[0][2] = 0.02, G[2][1] = -0.01;
      IncrementalKinematics reused, fresh;
      reused.reinit(G, F_old, ObjectiveRate::jaumann, kinematics_all);
      reused.reinit(F, F_old, ObjectiveRate::jaumann, kinematics_all);
      fresh.reinit(F, F_old, ObjectiveRate::jaumann, kinematics_all);
      kinematics_differences += differs(reused, fresh);
      reused.reinit(F_old, F, ObjectiveRate::jaumann, kinematics_all); // planar after planar
      fresh = IncrementalKinematics();
      fresh.reinit(F_old, F, ObjectiveRate::jaumann, kinematics_all);
      kinematics_differences += differs(reused, fresh);
    }
  std::cout << "planar kinematics after the general path: " << kinematics_differences
            << " entries differ from a fresh object's" << std::endl;

  const bool ok = fixed_point < 1e-11 && stress < 1e-11 && repeat < 1e-11 && identity_ok &&
                  kinematics_differences == 0;
  std::cout << (ok ? "PASS" : "FAIL") << " fixed point " << fixed_point << ", stress " << stress
            << ", repeated " << repeat << " (tolerance 1e-11), elastic identity "
            << (identity_ok ? "kept" : "lost") << std::endl;
  return ok ? 0 : 1;
}
