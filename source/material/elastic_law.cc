#include <deal.II/base/utilities.h>
#include <anvil/core/scene.h>
#include <anvil/material/elastic_law.h>

namespace anvil
{
  using namespace dealii;

  void ElasticLaw::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Young's modulus", "0", Patterns::Double(0),
                      "Young's modulus E in MPa at the reference temperature. Give either this or "
                      "Bulk modulus (the other 0).");
    prm.declare_entry("Bulk modulus", "0", Patterns::Double(0),
                      "Bulk modulus K in MPa at the reference temperature (seed eq. 10). Give "
                      "either this or Young's modulus.");
    prm.declare_entry("Poisson's ratio", "0.3", Patterns::Double(),
                      "Poisson's ratio, dimensionless, -1 < nu < 0.5.");
    prm.declare_entry("Density", "7.8e-9", Patterns::Double(0),
                      "Mass density rho in t/mm^3 (= N s^2/mm^4); steel 7.8e-9, aluminium 2.7e-9.");
    prm.declare_entry("Heat capacity", "4.6e8", Patterns::Double(0),
                      "Specific heat c in mm^2/(s^2 K) (= mJ/(t K)); steel 4.6e8, aluminium 9e8.");
    prm.declare_entry("Heat capacity at", "constant stress",
                      Patterns::Selection("constant stress|constant volume"),
                      "What Heat capacity is: constant stress (c_p, as handbooks give it; the "
                      "thermoelastic heat comes from the stress-producing volume change "
                      "tr(D - beta dT/dt I)) or constant volume (c_v, the seed's eq. 8; the "
                      "thermoelastic heat comes from all of tr D = dJ/dt / J, eq. 22). The two are "
                      "the same material when c_p = c_v + 9 K beta^2 T / rho; "
                      "doc/thermodynamics.md.");
    prm.declare_entry("Thermal expansion", "0", Patterns::Double(0),
                      "Linear thermal expansion coefficient beta in 1/K (seed eq. 19).");
    prm.declare_entry("Reference temperature", "293", Patterns::Double(0),
                      "Temperature in K at which the moduli are given and thermal strain is zero.");
    prm.declare_entry("Taylor-Quinney coefficient", "0.9", Patterns::Double(0, 1),
                      "chi: share of the plastic work that becomes heat (seed sec. 1.4.1), 0 to 1.");
    prm.enter_subsection("Modulus temperature factor");
    TemperatureLaw::declare_parameters(prm, "1",
                                       "dimensionless factor g(T) on K and G, g(T_ref) = 1");
    prm.leave_subsection();
    prm.enter_subsection("Thermal expansion temperature factor");
    TemperatureLaw::declare_parameters(prm, "1",
                                       "dimensionless factor f(T) on beta: beta(T) = beta f(T)");
    prm.leave_subsection();
  }

  void ElasticLaw::parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path)
  {
    const double E  = prm.get_double("Young's modulus");
    const double K  = prm.get_double("Bulk modulus");
    const double nu = prm.get_double("Poisson's ratio");
    if (!(nu > -1. && nu < 0.5))
      scene.fail(path + "/Poisson's ratio", "= " + std::to_string(nu) + ": expected -1 < nu < 0.5");
    // Both 0 is allowed here: a thermal-only scene needs no elastic
    // constants; a scene with mechanics refuses a zero modulus where it
    // builds the mechanics (CoupledProblem::parse_parameters).
    if (E > 0 && K > 0)
      scene.fail(path + "/Young's modulus",
                 "and 'Bulk modulus': expected exactly one of them > 0 (the other 0)");
    K0                    = K > 0 ? K : E / (3. * (1. - 2. * nu));
    G0                    = 3. * K0 * (1. - 2. * nu) / (2. * (1. + nu));
    // Far above any solid (steel: K = 1.7e5 MPa), yet below where a unit
    // strain's stress squared (J2 norms, energies) leaves double precision.
    const double modulus_limit = 1e15;
    if (!(K0 + 4. / 3. * G0 <= modulus_limit))
      scene.fail(path + (K > 0 ? "/Bulk modulus" : "/Young's modulus"),
                 "= " + Utilities::to_string(K > 0 ? K : E) + " MPa gives the P-wave modulus K + 4G/3 = " +
                   Utilities::to_string(K0 + 4. / 3. * G0) + " MPa: expected at most " +
                   Utilities::to_string(modulus_limit) +
                   " MPa (stresses and their squares must stay finite)");
    density               = prm.get_double("Density");
    heat_capacity         = prm.get_double("Heat capacity");
    beta0                 = prm.get_double("Thermal expansion");
    capacity_at_constant_volume = prm.get("Heat capacity at") == "constant volume";
    reference_temperature = prm.get_double("Reference temperature");
    if (!(reference_temperature > 0))
      scene.fail(path + "/Reference temperature",
                 "= " + Utilities::to_string(reference_temperature) +
                   " K: expected an absolute temperature > 0 K");
    taylor_quinney        = prm.get_double("Taylor-Quinney coefficient");
    prm.enter_subsection("Modulus temperature factor");
    factor.parse_parameters(prm, scene, path + "/Modulus temperature factor", reference_temperature);
    factor.require_above(scene, 0, true, "the modulus factor g");
    prm.leave_subsection();
    prm.enter_subsection("Thermal expansion temperature factor");
    beta_factor.parse_parameters(prm, scene, path + "/Thermal expansion temperature factor",
                                 reference_temperature);
    prm.leave_subsection();
  }

  SymmetricTensor<4, 3> ElasticLaw::elasticity(const double T) const
  {
    const SymmetricTensor<2, 3> I = unit_symmetric_tensor<3>();
    return bulk_modulus(T) * outer_product(I, I) + 2. * shear_modulus(T) * deviator_tensor<3>();
  }
} // namespace anvil
