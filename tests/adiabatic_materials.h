// Material texts shared by the adiabatic J2 tests (adiabatic_temperature_derivative,
// j2_adiabatic_fixed_point): a steel-like elastic block with a linear modulus
// softening, and J2 with eq. 35's linear softening of the yield stress on
// linear (the tube's laws) or saturation hardening. One copy, so the tests
// keep checking the same points when a law's parameters change.
#ifndef anvil_tests_adiabatic_materials_h
#define anvil_tests_adiabatic_materials_h

#include <deal.II/base/symmetric_tensor.h>

#include <anvil/material/material_point.h>

#include <string>
#include <utility>
#include <vector>

namespace anvil::testing
{
  inline const std::string steel_elastic =
    "subsection Elasticity\n set Young's modulus = 200000\n set Poisson's ratio = 0.3\n"
    " set Thermal expansion = 5e-5\n set Reference temperature = 293\n"
    " set Density = 7.8e-9\n set Heat capacity = 4.6e8\n"
    " subsection Modulus temperature factor\n set Model = linear\n set Softening = 4e-4\n end\n"
    "end\n";

  /// The tests' increment: Δε at T = 350 K, ΔT = 5 K, Δt = 1e-5 s, J = 1.01.
  inline MaterialIncrement adiabatic_test_increment(const dealii::SymmetricTensor<2, 3> &de,
                                                    const bool                           adiabatic)
  {
    MaterialIncrement inc;
    inc.strain_increment      = de;
    inc.temperature           = 350;
    inc.temperature_increment = 5;
    inc.time_step             = 1e-5;
    inc.volume_ratio          = 1.01;
    inc.adiabatic             = adiabatic;
    return inc;
  }

  /// (name, material text) of J2 with linear and with saturation hardening,
  /// both softened by eq. 35, on @p elastic.
  inline std::vector<std::pair<std::string, std::string>>
  j2_softening_cases(const std::string &elastic)
  {
    return {{"J2 linear hardening, linear softening (eq. 35; the tube's laws)",
             "set Model = J2\n" + elastic +
               "subsection Hardening\n set Model = linear\n set Initial yield stress = 150\n"
               " set Hardening modulus = 1000\n subsection Thermal softening\n set Model = linear\n"
               " set Softening coefficient = 0.002\n set Reference temperature = 293\n end\nend\n"},
            {"J2 saturation hardening, linear softening (eq. 35)",
             "set Model = J2\n" + elastic +
               "subsection Hardening\n set Model = saturation\n set Initial yield stress = 150\n"
               " set Hardening modulus = 129\n set Saturation stress = 300\n"
               " set Saturation exponent = 16.9\n subsection Thermal softening\n"
               " set Model = linear\n set Softening coefficient = 0.002\n"
               " set Reference temperature = 293\n end\nend\n"}};
  }
} // namespace anvil::testing

#endif
