// Consistent tangents against central finite differences, for every material
// model, in the elastic and the plastic branch:
//  1. A = dP/dF of the incremental (Hughes-Winget) update as the mechanics
//     assembles it (kinematics + material tangent + rotated-stress sensitivity),
//     2D and 3D, with prestress and incremental rotations up to 0.7 rad;
//  2. dsigma/dT of the material update at fixed strain increment;
//  3. dP/dF of the adiabatic update (Armero-Simo split: the point heats by its
//     own dissipation and thermoelastic effect within the step), which couples
//     through d(dT_ad)/d(strain), for every model and both heat-capacity
//     conventions, with a strong coupling (tau = 9 K beta^2 T/(rho c) ~ 0.4);
//  4. A = dP/dF with the Green-Naghdi and logarithmic rates (kinematics.h:
//     their dDelta eps/dF and dDelta R/dF are central differences of the
//     kinematics, chained with the exact material tangent), 2D and 3D, elastic
//     and plastic, at rotations up to 0.7 rad: checks that chain and the
//     step of the inner differences (tolerance 1e-6 as for the others).
// The tabulated cases (issue 13) put table kinks at 347 and 398 K: the
// increment 345 -> 350 K and the dsigma/dT check (293 -> 400 K) cross them,
// so the trapezoidal thermal strain and every T-derivative are exercised on
// both sides of a kink (the central differences stay inside one segment).
// Johnson-Cook (issue 16): the hardening law A + B eps^n and the model with
// its multiplicative rate factor (1 + C ln(eps_dot/eps_dot_0)).
// Prints analytic and finite-difference values and fails above 1e-6 relative.
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/core/scene.h>
#include <anvil/material/material_point.h>
#include <anvil/material/kinematics.h>

#include <cmath>
#include <iostream>

using namespace dealii;
using namespace anvil;

std::shared_ptr<const MaterialModel> make_model(const std::string &settings)
{
  return MaterialFactory::create_from_text(settings);
}

struct Case
{
  std::string name, settings;
  double      yield_scale; // prestress magnitude relative to which the increment is plastic
};

template <int dim>
double check_piola(const MaterialModel &model, const double angle, const double stretch,
                   const double T, const double dT, bool print, bool adiabatic = false,
                   const ObjectiveRate rate = ObjectiveRate::jaumann)
{
  // Prestress: well inside the yield surface for the elastic-branch case.
  SymmetricTensor<2, 3> sigma_n;
  sigma_n[0][0] = 150, sigma_n[1][1] = -40, sigma_n[0][1] = 35, sigma_n[2][2] = 20;
  if (dim == 3)
    sigma_n[0][2] = -12, sigma_n[1][2] = 8;
  if (stretch < 1e-3)
    sigma_n *= 0.1;

  Tensor<2, 3> F_old = unit_symmetric_tensor<3>();
  F_old[0][0] = 1.1, F_old[0][1] = 0.2, F_old[1][0] = -0.05, F_old[1][1] = 0.95;
  if (dim == 3)
    F_old[2][2] = 1.02, F_old[0][2] = 0.03, F_old[2][1] = -0.04;
  Tensor<2, 3> R = unit_symmetric_tensor<3>();
  R[0][0] = R[1][1] = std::cos(angle);
  R[0][1] = -std::sin(angle), R[1][0] = std::sin(angle);
  Tensor<2, 3> S = unit_symmetric_tensor<3>();
  S[0][0] = 1 + 3 * stretch, S[1][1] = 1 - stretch, S[0][1] = S[1][0] = 2 * stretch;
  if (dim == 3)
    S[2][2] = 1 + stretch, S[1][2] = S[2][1] = 1.5 * stretch;
  const Tensor<2, 3> F = R * S * F_old;

  auto piola = [&](const Tensor<2, 3> &Fx, MaterialResponse &response) {
    auto point = model.create_point({adiabatic});
    point->set_stress(sigma_n);
    IncrementalKinematics kin;
    kin.reinit(Fx, F_old, rate);
    MaterialIncrement inc;
    inc.strain_increment      = kin.strain_increment;
    inc.rotation_increment    = kin.rotation_increment;
    inc.temperature           = T;
    inc.temperature_increment = dT;
    inc.time_step             = 0.01;
    inc.adiabatic             = adiabatic;
    point->update(inc, request_stress | request_tangent, response);
    return std::make_pair(first_piola_stress(kin, response.stress), kin);
  };

  MaterialResponse     response;
  const auto [P, kin]  = piola(F, response);
  const Tensor<4, dim> A = first_piola_tangent<dim>(kin, sigma_n, response);
  const double         h = 1e-6;
  double               max_a = 0, max_err = 0;
  for (unsigned int k = 0; k < dim; ++k)
    for (unsigned int L = 0; L < dim; ++L)
      {
        Tensor<2, 3> Fp = F, Fm = F;
        Fp[k][L] += h, Fm[k][L] -= h;
        MaterialResponse r;
        const Tensor<2, 3> dP = (piola(Fp, r).first - piola(Fm, r).first) / (2 * h);
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int J = 0; J < dim; ++J)
            {
              max_a   = std::max(max_a, std::abs(A[i][J][k][L]));
              max_err = std::max(max_err, std::abs(A[i][J][k][L] - dP[i][J]));
              if (print && k == 0 && L == 1 && i == 0)
                std::cout << "    dP0" << J << "/dF01: analytic " << A[i][J][k][L]
                          << "  finite difference " << dP[i][J] << '\n';
            }
      }
  std::cout << "  dim " << dim << ", " << objective_rate_name(rate) << ", rotation " << angle << " rad, "
            << (adiabatic ? "adiabatic (dT_ad = " + std::to_string(response.adiabatic_temperature_increment) + " K), " : "")
            << (response.equivalent_plastic_strain > 0 ? "plastic" : "elastic")
            << ": max |A - A_fd| / max |A| = " << max_err / max_a << std::endl;
  return max_err / max_a;
}

double check_temperature(const MaterialModel &model, const double stretch, const double T)
{
  SymmetricTensor<2, 3> de;
  de[0][0] = 3 * stretch, de[1][1] = -stretch, de[0][1] = 2 * stretch;
  auto stress = [&](const double Tx, MaterialResponse &r) {
    auto point = model.create_point();
    point->set_stress(SymmetricTensor<2, 3>());
    MaterialIncrement inc;
    inc.strain_increment      = de;
    inc.temperature           = Tx;
    inc.temperature_increment = Tx - 293;
    inc.time_step             = 0.01;
    point->update(inc, request_stress | request_temperature_derivative, r);
    return r.stress;
  };
  MaterialResponse r, rr;
  stress(T, r);
  const double                h  = 1e-4;
  const SymmetricTensor<2, 3> fd = (stress(T + h, rr) - stress(T - h, rr)) / (2 * h);
  const double err = (fd - r.stress_temperature_derivative).norm() /
                     std::max(fd.norm(), 1e-300);
  std::cout << "  dsigma/dT, " << (r.equivalent_plastic_strain > 0 ? "plastic" : "elastic")
            << ": analytic dsxx/dT " << r.stress_temperature_derivative[0][0]
            << "  finite difference " << fd[0][0] << "  relative error " << err << std::endl;
  return err;
}

int main()
{
  const std::string elastic =
    "subsection Elasticity\n set Young's modulus = 200000\n set Poisson's ratio = 0.3\n"
    " set Thermal expansion = 1.2e-5\n set Reference temperature = 293\n"
    " subsection Modulus temperature factor\n set Model = linear\n set Softening = 4e-4\n end\n"
    "end\n";
  // Piecewise linear E(T) (through g) and beta(T) with kinks at 347 and 398 K.
  const std::string tabulated_elastic =
    "subsection Elasticity\n set Young's modulus = 70000\n set Poisson's ratio = 0.33\n"
    " set Thermal expansion = 1.2e-5\n set Reference temperature = 293\n"
    " subsection Modulus temperature factor\n set Model = table\n"
    " set Table = 250 : 1.02, 293 : 1, 347 : 0.95, 398 : 0.85, 600 : 0.6\n end\n"
    " subsection Thermal expansion temperature factor\n set Model = table\n"
    " set Table = 250 : 0.95, 293 : 1, 347 : 1.1, 398 : 1.05, 600 : 1.3\n end\n"
    "end\n";
  const std::vector<Case> cases = {
    {"hypoelastic", "set Model = hypoelastic\n" + elastic, 0},
    {"J2 linear hardening",
     "set Model = J2\n" + elastic +
       "subsection Hardening\n set Model = linear\n set Initial yield stress = 150\n"
       " set Hardening modulus = 1000\nend\n",
     1},
    {"J2 saturation hardening, linear thermal softening",
     "set Model = J2\n" + elastic +
       "subsection Hardening\n set Model = saturation\n set Initial yield stress = 150\n"
       " set Hardening modulus = 129\n set Saturation stress = 300\n set Saturation exponent = 16.9\n"
       " subsection Thermal softening\n set Model = linear\n set Softening coefficient = 0.002\n"
       " set Reference temperature = 293\n end\nend\n",
     1},
    {"J2 swift hardening, Johnson-Cook softening",
     "set Model = J2\n" + elastic +
       "subsection Hardening\n set Model = swift\n set Strength coefficient = 500\n"
       " set Reference strain = 0.01\n set Hardening exponent = 0.2\n"
       " subsection Thermal softening\n set Model = johnson-cook\n set Melting temperature = 1700\n"
       " set Exponent = 1.1\n set Reference temperature = 293\n end\nend\n",
     1},
    {"J2 johnson-cook hardening A + B eps^n, Johnson-Cook softening",
     "set Model = J2\n" + elastic +
       "subsection Hardening\n set Model = johnson-cook\n set Initial yield stress = 300\n"
       " set Strength coefficient = 292\n set Hardening exponent = 0.31\n"
       " subsection Thermal softening\n set Model = johnson-cook\n set Melting temperature = 1356\n"
       " set Exponent = 1.09\n set Reference temperature = 293\n end\nend\n",
     1},
    // The rate factor is active: Δε̄/Δt ~ 2/s in the plastic branch, 20 x ε̇₀. A = 300 MPa
    // keeps the small stretch elastic: just past yield from ε̄ = 0, B ε̄^0.31 is too
    // curved for central differences of step 1e-6 (the plastic branch checks the tangent).
    {"Johnson-Cook model, multiplicative rate factor",
     "set Model = Johnson-Cook\n" + elastic +
       "subsection Johnson-Cook\n set A = 300\n set B = 292\n set n = 0.31\n set C = 0.025\n"
       " set Reference strain rate = 0.1\n set m = 1.09\n set Melting temperature = 1356\n"
       " set Transition temperature = 293\nend\n",
     1},
    {"Perzyna, T-dependent eta, n, m",
     "set Model = Perzyna\n" + elastic +
       "subsection Hardening\n set Model = voce\n set Initial yield stress = 150\n"
       " set Saturation stress = 250\n set Saturation exponent = 10\nend\n"
       "subsection Viscosity\n subsection Eta\n set Model = linear\n set Value = 50\n"
       " set Softening = 1e-3\n end\n subsection n\n set Model = linear\n set Value = 1.5\n"
       " set Softening = 2e-4\n end\n subsection m\n set Model = linear\n set Value = 3\n"
       " set Softening = -5e-4\n end\n set Strain exponent = 0.3\n set Strain reference = 0.1\nend\n",
     1},
    {"J2, every parameter tabulated in T (E, beta, sigma_0, h)",
     "set Model = J2\n" + tabulated_elastic +
       "subsection Hardening\n set Model = temperature linear\n"
       " subsection Yield stress of T\n set Model = table\n"
       " set Table = 250 : 160, 293 : 150, 347 : 120, 398 : 70, 600 : 20\n end\n"
       " subsection Hardening modulus of T\n set Model = table\n"
       " set Table = 250 : 1100, 293 : 1000, 347 : 600, 398 : 900, 600 : 100\n end\nend\n",
     1},
    {"Perzyna, tabulated eta(T), n(T), m(T), sigma_0(T), h(T)",
     "set Model = Perzyna\n" + tabulated_elastic +
       "subsection Hardening\n set Model = temperature linear\n"
       " subsection Yield stress of T\n set Model = table\n"
       " set Table = 250 : 160, 293 : 150, 347 : 120, 398 : 70, 600 : 20\n end\n"
       " subsection Hardening modulus of T\n set Model = table\n"
       " set Table = 250 : 1100, 293 : 1000, 347 : 600, 398 : 900, 600 : 100\n end\nend\n"
       "subsection Viscosity\n subsection Eta\n set Model = table\n"
       " set Table = 250 : 60, 293 : 50, 347 : 80, 398 : 30, 600 : 10\n end\n"
       " subsection n\n set Model = table\n set Table = 250 : 1.5, 293 : 1.5, 347 : 1.2, 398 : 1.8, 600 : 1\n end\n"
       " subsection m\n set Model = table\n set Table = 250 : 3, 293 : 3, 347 : 4, 398 : 2.5, 600 : 5\n end\n"
       "end\n",
     1},
    {"Perzyna, eta(T) and m(T) as expressions with a Range",
     "set Model = Perzyna\n" + tabulated_elastic +
       "subsection Hardening\n set Model = linear\n set Initial yield stress = 100\n"
       " set Hardening modulus = 500\nend\n"
       "subsection Viscosity\n subsection Eta\n set Model = expression\n"
       " set Expression = 50*exp(-(T-293)/200)\n set Range = 200, 1000\n end\n"
       " subsection m\n set Model = expression\n set Expression = 2 + 0.01*(T-293)\n"
       " set Range = 200, 1000\n end\nend\n",
     1},
  };
  double worst = 0;
  for (const auto &c : cases)
    {
      std::cout << c.name << std::endl;
      const auto model = make_model(c.settings);
      for (const double stretch : {1e-4, 2e-2}) // elastic, then plastic branch
        {
          for (const double angle : {0.0, 0.1, 0.7})
            worst = std::max({worst, check_piola<2>(*model, angle, stretch, 350, 5, angle == 0.1),
                              check_piola<3>(*model, angle, stretch, 350, 5, false)});
          worst = std::max(worst, check_temperature(*model, stretch, 400));
        }
    }
  // Adiabatic updates: strong thermoelastic coupling and plastic heating.
  for (const std::string convention : {"constant stress", "constant volume"})
    for (const auto &c : cases)
      {
        std::string settings = c.settings;
        const auto  at       = settings.find(" set Thermal expansion = 1.2e-5\n");
        settings.replace(at, std::string(" set Thermal expansion = 1.2e-5\n").size(),
                         " set Thermal expansion = 5e-5\n set Heat capacity at = " + convention +
                           "\n");
        std::cout << c.name << ", adiabatic, heat capacity at " << convention << std::endl;
        const auto model = make_model(settings);
        for (const double stretch : {1e-4, 2e-2})
          worst = std::max({worst, check_piola<2>(*model, 0.1, stretch, 350, 5, false, true),
                            check_piola<3>(*model, 0.1, stretch, 350, 5, false, true)});
      }
  // Other objective rates: the hypoelastic body and one plastic model.
  for (const ObjectiveRate rate : {ObjectiveRate::green_naghdi, ObjectiveRate::logarithmic})
    for (const unsigned int c : {0u, 1u})
      {
        std::cout << cases[c].name << ", " << objective_rate_name(rate) << " rate" << std::endl;
        const auto model = make_model(cases[c].settings);
        for (const double stretch : {1e-4, 2e-2})
          for (const double angle : {0.0, 0.1, 0.7})
            worst = std::max({worst, check_piola<2>(*model, angle, stretch, 350, 5, false, false, rate),
                              check_piola<3>(*model, angle, stretch, 350, 5, false, false, rate)});
      }
  const bool ok = worst < 1e-6;
  std::cout << (ok ? "PASS" : "FAIL") << " worst relative error " << worst << " (tolerance 1e-6)"
            << std::endl;
  return ok ? 0 : 1;
}
