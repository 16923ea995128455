// The adiabatic J2 update's consistent tangent (Armero-Simo split) against
// central finite differences of the update itself, at a tolerance 100x tighter
// than tangent_fd's. With x = ΔT_ad the fixed point x = f(Δε, σ̃ₙ, x),
//   dσ/dΔε = C + ∂σ/∂T ⊗ ∂f/∂Δε / (1 − ∂f/∂x),   dσ/d ln J = ∂σ/∂T f / (1 − ∂f/∂x),
// so both carry ∂f/∂x = ∂ΔT_ad/∂T, now in closed form (j2_plasticity.cc: the
// moduli K(T) = K₀g(T), β(T) of eq. 19, the softened yield stress, for the
// linear law σ₀(T) = σ₀(T_ref)(1 − ω₀(T − T_ref)) of eq. 35, and the
// overstress). Cases: linear softening (the tube's), saturation hardening,
// Johnson-Cook, Perzyna with T-dependent η, n, m, tabulated E(T) and β(T);
// both heat-capacity conventions; a step that starts elastic and one that
// starts on the yield surface (the plastic work's q_start branches).
// Prints analytic and finite-difference values; fails above 1e-8 relative.
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/material/material_point.h>

#include "adiabatic_materials.h"

#include <cmath>
#include <iostream>

using namespace dealii;
using namespace anvil;

namespace
{
  struct Result
  {
    double tangent_error = 0, volume_error = 0, dT_ad = 0, d_eps = 0;
  };

  Result check(const MaterialModel &model, const SymmetricTensor<2, 3> &sigma_n,
               const SymmetricTensor<2, 3> &de, bool print)
  {
    auto update = [&](const SymmetricTensor<2, 3> &strain, const double J, MaterialResponse &r) {
      auto point = model.create_point({true});
      point->set_stress(sigma_n);
      MaterialIncrement inc;
      inc.strain_increment      = strain;
      inc.temperature           = 350;
      inc.temperature_increment = 5;
      inc.time_step             = 0.01;
      inc.volume_ratio          = J;
      inc.adiabatic             = true;
      point->update(inc, request_stress | request_tangent, r);
      return r.stress;
    };
    MaterialResponse response;
    const double     J0 = 1.02;
    update(de, J0, response);
    Result       result;
    const double h = 1e-7;
    double       max_C = 0, max_err = 0;
    for (unsigned int k = 0; k < 3; ++k)
      for (unsigned int l = k; l < 3; ++l)
        {
          SymmetricTensor<2, 3> E;
          E[k][l] = h; // symmetric: both (k, l) and (l, k)
          MaterialResponse              r;
          const SymmetricTensor<2, 3> fd = (update(de + E, J0, r) - update(de - E, J0, r)) / (2 * h);
          const SymmetricTensor<2, 3> an = (response.tangent * E) / h;
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = i; j < 3; ++j)
              {
                max_C   = std::max(max_C, std::abs(an[i][j]));
                max_err = std::max(max_err, std::abs(an[i][j] - fd[i][j]));
              }
          if (print && k == 0 && l == 0)
            std::cout << "    dsigma00/de00: analytic " << an[0][0] << "  finite difference "
                      << fd[0][0] << '\n';
        }
    result.tangent_error = max_err / max_C;
    {
      // dσ/d ln J is ~1e-3 of the stress: a longer step keeps the rounding of
      // the difference below its truncation (~h²).
      const double                  hJ = 1e-5;
      MaterialResponse              r;
      const SymmetricTensor<2, 3> fd =
        (update(de, J0 * std::exp(hJ), r) - update(de, J0 * std::exp(-hJ), r)) / (2 * hJ);
      const SymmetricTensor<2, 3> &an = response.volume_ratio_sensitivity;
      result.volume_error = (an - fd).norm() / std::max(fd.norm(), 1e-300);
      if (print)
        std::cout << "    dsigma00/dlnJ: analytic " << an[0][0] << "  finite difference " << fd[0][0]
                  << '\n';
    }
    result.dT_ad = response.adiabatic_temperature_increment;
    result.d_eps = response.equivalent_plastic_strain;
    return result;
  }
} // namespace

int main()
{
  const std::string &elastic = testing::steel_elastic;
  const std::string tabulated_elastic =
    "subsection Elasticity\n set Young's modulus = 70000\n set Poisson's ratio = 0.33\n"
    " set Thermal expansion = 5e-5\n set Reference temperature = 293\n"
    " subsection Modulus temperature factor\n set Model = table\n"
    " set Table = 250 : 1.02, 293 : 1, 347 : 0.95, 398 : 0.85, 600 : 0.6\n end\n"
    " subsection Thermal expansion temperature factor\n set Model = table\n"
    " set Table = 250 : 0.95, 293 : 1, 347 : 1.1, 398 : 1.05, 600 : 1.3\n end\n"
    "end\n";
  std::vector<std::pair<std::string, std::string>> cases = testing::j2_softening_cases(elastic);
  const std::vector<std::pair<std::string, std::string>> others = {
    {"Johnson-Cook model, multiplicative rate factor",
     "set Model = Johnson-Cook\n" + elastic +
       "subsection Johnson-Cook\n set A = 300\n set B = 292\n set n = 0.31\n set C = 0.025\n"
       " set Reference strain rate = 0.1\n set m = 1.09\n set Melting temperature = 1356\n"
       " set Transition temperature = 293\nend\n"},
    {"Perzyna, T-dependent eta, n, m",
     "set Model = Perzyna\n" + elastic +
       "subsection Hardening\n set Model = voce\n set Initial yield stress = 150\n"
       " set Saturation stress = 250\n set Saturation exponent = 10\nend\n"
       "subsection Viscosity\n subsection Eta\n set Model = linear\n set Value = 50\n"
       " set Softening = 1e-3\n end\n subsection n\n set Model = linear\n set Value = 1.5\n"
       " set Softening = 2e-4\n end\n subsection m\n set Model = linear\n set Value = 3\n"
       " set Softening = -5e-4\n end\n set Strain exponent = 0.3\n set Strain reference = 0.1\nend\n"},
    {"J2, tabulated E(T), beta(T), sigma_0(T), h(T)",
     "set Model = J2\n" + tabulated_elastic +
       "subsection Hardening\n set Model = temperature linear\n"
       " subsection Yield stress of T\n set Model = table\n"
       " set Table = 250 : 160, 293 : 150, 347 : 120, 398 : 70, 600 : 20\n end\n"
       " subsection Hardening modulus of T\n set Model = table\n"
       " set Table = 250 : 1100, 293 : 1000, 347 : 600, 398 : 900, 600 : 100\n end\nend\n"},
  };
  cases.insert(cases.end(), others.begin(), others.end());
  SymmetricTensor<2, 3> de; // plastic: a shear-dominated stretch with some dilatation
  de[0][0] = 0.012, de[1][1] = -0.004, de[2][2] = 0.001, de[0][1] = 0.008, de[1][2] = -0.003;
  SymmetricTensor<2, 3> inside, on_surface; // σₙ well inside, and at ~q = 200 MPa
  inside[0][0] = 30, inside[1][1] = -10, inside[0][1] = 8;
  on_surface[0][0] = 150, on_surface[1][1] = -40, on_surface[0][1] = 35, on_surface[2][2] = 20;
  double worst = 0;
  for (const std::string convention : {"constant stress", "constant volume"})
    for (const auto &[name, settings_in] : cases)
      {
        std::string       settings = settings_in;
        const std::string beta     = " set Thermal expansion = 5e-5\n";
        settings.replace(settings.find(beta), beta.size(),
                         beta + " set Heat capacity at = " + convention + "\n");
        const auto model = MaterialFactory::create_from_text(settings);
        std::cout << name << ", heat capacity at " << convention << std::endl;
        for (const auto *sigma_n : {&inside, &on_surface})
          {
            const Result r = check(*model, *sigma_n, de, sigma_n == &inside);
            std::cout << "  sigma_n " << (sigma_n == &inside ? "inside" : "on the surface")
                      << ": dT_ad = " << r.dT_ad << " K, eps_p = " << r.d_eps
                      << ", max |C - C_fd| / max |C| = " << r.tangent_error
                      << ", |dsigma/dlnJ - fd| / |fd| = " << r.volume_error << std::endl;
            worst = std::max({worst, r.tangent_error, r.volume_error});
          }
      }
  const bool ok = worst < 1e-8;
  std::cout << (ok ? "PASS" : "FAIL") << " worst relative error " << worst << " (tolerance 1e-8)"
            << std::endl;
  return ok ? 0 : 1;
}
