// The J2 point's fast paths against independent answers:
// 1. the linear hardening law read as plain numbers (HardeningLaw::LinearForm,
//    evaluated inline by the point) against the closed form of eq. 16 with
//    eq. 35's softening, σᵥ = θ σ₀ + θ_h h ε̄, θ = 1 − ω (T − T_ref) (1e-14),
//    and against the law's own evaluate() (bit for bit: the point's answers
//    must not depend on the path);
// 2. the adiabatic update (Armero–Simo), whose stress now comes from the
//    converged iterate of its fixed point: the stress equals an isothermal
//    update at the converged temperature T + ΔT_ad (bit for bit), and ΔT_ad
//    satisfies the heat balance ρ₀c ΔT_ad / J = Δt (χ Ẇirr + Ẇthel) (to the
//    fixed point's tolerance, 1e-12 K (1 + |ΔT_ad|)).
// Prints values against expected; fails otherwise.
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/material/j2_plasticity.h>

#include "adiabatic_materials.h"

#include <cmath>
#include <cstdio>
#include <string>

using namespace dealii;
using namespace anvil;

namespace
{
  const std::string elastic =
    "subsection Elasticity\n set Bulk modulus = 70000\n set Poisson's ratio = 0.3\n"
    " set Density = 2.7e-9\n set Heat capacity = 0.9e9\n set Thermal expansion = 23.86e-6\nend\n";

  std::string hardening(const std::string &softened, const std::string &softening)
  {
    return "set Model = J2\n" + elastic +
           "subsection Hardening\n set Initial yield stress = 150\n set Hardening modulus = 50\n"
           " set Softened parameters = " + softened + "\n subsection Thermal softening\n"
           "  set Model = " + softening + "\n  set Softening coefficient = 2e-3\n"
           "  set Reference temperature = 293\n end\nend\n";
  }

  int failures = 0;
  void expect(const bool ok, const char *what, const double value, const double expected)
  {
    std::printf("%-58s %.17g expected %.17g %s\n", what, value, expected, ok ? "ok" : "FAILED");
    failures += ok ? 0 : 1;
  }
} // namespace

int main()
{
  // 1. LinearForm against eq. 16/35 and against the law.
  struct Case
  {
    std::string softened, softening;
    bool        soft_s0, soft_h, linear_theta;
  };
  for (const Case &c : {Case{"initial yield stress", "linear", true, false, true},
                        Case{"all", "linear", true, true, true},
                        Case{"initial yield stress", "none", true, false, false}})
    {
      const auto  model = MaterialFactory::create_from_text(hardening(c.softened, c.softening));
      const auto &j2    = dynamic_cast<const J2Model &>(*model);
      HardeningLaw::LinearForm form;
      const bool               has_form = j2.hardening->linear_form(form);
      expect(has_form, ("linear form exists: " + c.softened + ", " + c.softening).c_str(), has_form, 1);
      double max_closed = 0, max_bits = 0;
      for (const double eps : {0., 0.013, 0.7})
        for (const double T : {293., 351.25, 612.})
          {
            const double theta  = c.linear_theta ? 1 - 2e-3 * (T - 293) : 1.;
            const double dtheta = c.linear_theta ? -2e-3 : 0.;
            const double s0 = c.soft_s0 ? theta : 1., sh = c.soft_h ? theta : 1.;
            const double closed = s0 * 150 + sh * 50 * eps;
            const double closed_dT =
              (c.soft_s0 ? dtheta : 0.) * 150 + (c.soft_h ? dtheta : 0.) * 50 * eps;
            const auto inline_value = form.evaluate(eps, T);
            const auto law_value    = j2.hardening->evaluate(eps, T);
            max_closed = std::max({max_closed, std::abs(inline_value.stress - closed) / 150,
                                   std::abs(inline_value.slope - sh * 50) / 150,
                                   std::abs(inline_value.temperature_derivative - closed_dT)});
            if (inline_value.stress != law_value.stress || inline_value.slope != law_value.slope ||
                inline_value.temperature_derivative != law_value.temperature_derivative ||
                form.is_nondecreasing(T) != j2.hardening->is_nondecreasing(T))
              max_bits = 1;
          }
      expect(max_closed <= 1e-14, "  inline sigma_y against eq. 16/35, max rel. error", max_closed, 0);
      expect(max_bits == 0, "  inline sigma_y equals the law's evaluate() bit for bit", max_bits, 0);
    }

  // 2. The adiabatic update's stress is an isothermal update's at T + ΔT_ad.
  const auto model = MaterialFactory::create_from_text(hardening("initial yield stress", "linear"));
  for (const double scale : {0.1, 10.}) // elastic, plastic (× the yield strain 150/84000)
    for (const bool tangent : {false, true})
      {
        SymmetricTensor<2, 3> sigma_n, de;
        sigma_n[0][0] = 60, sigma_n[1][1] = -20, sigma_n[0][1] = 35;
        const double f = scale * 150 / 84000;
        de[0][0] = 1.0 * f, de[1][1] = -0.4 * f, de[2][2] = -0.3 * f, de[0][1] = 0.5 * f;
        const MaterialIncrement inc = testing::adiabatic_test_increment(de, true);
        const MaterialRequest request =
          tangent ? request_stress | request_tangent : request_stress;
        auto adiabatic = model->create_point({true});
        adiabatic->set_stress(sigma_n);
        MaterialResponse r;
        adiabatic->update(inc, request, r);
        const double x = r.adiabatic_temperature_increment;

        MaterialIncrement iso = inc;
        iso.adiabatic         = false;
        iso.temperature += x;
        iso.temperature_increment += x;
        auto isothermal = model->create_point();
        isothermal->set_stress(sigma_n);
        MaterialResponse ri;
        isothermal->update(iso, request_stress, ri);
        double diff = 0;
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            diff = std::max(diff, std::abs(r.stress[i][j] - ri.stress[i][j]));
        const std::string what = std::string(scale > 1 ? "plastic" : "elastic") +
                                 (tangent ? ", stress|tangent" : ", stress") + ": ";
        expect(diff == 0 && r.equivalent_plastic_strain == ri.equivalent_plastic_strain,
               (what + "adiabatic stress = isothermal at T + dT_ad").c_str(), diff, 0);
        // ρ₀c ΔT/J = Δt (χẆirr + Ẇthel), eq. 20–22 (the rates are the isothermal update's at T + x).
        const double lhs = 2.7e-9 * 0.9e9 * x / inc.volume_ratio;
        const double rhs = inc.time_step * (ri.plastic_dissipation_rate + ri.thermoelastic_heating_rate);
        // In kelvin, against the fixed point's tolerance 1e-12 (1 + |ΔT_ad|).
        const double err = std::abs(lhs - rhs) / (2.7e-9 * 0.9e9 / inc.volume_ratio);
        expect(err <= 2e-12 * (1 + std::abs(x)) && (scale < 1 || r.equivalent_plastic_strain > 0),
               (what + "heat balance rho c dT/J = dt (chi W_irr + W_thel), K").c_str(), err, 0);
      }
  std::printf("%s\n", failures == 0 ? "PASSED" : "FAILED");
  return failures == 0 ? 0 : 1;
}
