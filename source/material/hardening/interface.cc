#include <deal.II/base/utilities.h>

#include <anvil/core/scene.h>
#include <anvil/material/hardening/interface.h>

#include <algorithm>
#include <stdexcept>

namespace anvil
{
  using namespace dealii;

  void HardeningLaw::declare_common_entry(ParameterHandler &prm, const std::string &entry)
  {
    if (entry == "Initial yield stress")
      prm.declare_entry("Initial yield stress", "0", Patterns::Double(),
                        "s0 in MPa (linear, voce, saturation), A (johnson-cook); > 0.");
    else if (entry == "Hardening modulus")
      prm.declare_entry("Hardening modulus", "0", Patterns::Double(),
                        "h in MPa (linear, saturation): slope of yield stress against plastic strain.");
    else if (entry == "Saturation stress")
      prm.declare_entry("Saturation stress", "0", Patterns::Double(),
                        "s_inf in MPa (voce, saturation).");
    else if (entry == "Saturation exponent")
      prm.declare_entry("Saturation exponent", "0", Patterns::Double(0),
                        "delta, dimensionless (voce, saturation).");
    else if (entry == "Strength coefficient")
      prm.declare_entry("Strength coefficient", "0", Patterns::Double(0), "K in MPa (swift), B (johnson-cook).");
    else if (entry == "Reference strain")
      prm.declare_entry("Reference strain", "0.002", Patterns::Double(0),
                        "eps0, dimensionless (swift), > 0.");
    else if (entry == "Hardening exponent")
      prm.declare_entry("Hardening exponent", "0.2", Patterns::Double(0),
                        "n, dimensionless (swift, johnson-cook).");
    else if (entry == "Table")
      prm.declare_entry("Table", "", Patterns::Anything(),
                        "Table model: 'eps1 : s1, eps2 : s2, ...' (dimensionless : MPa), eps from 0 "
                        "increasing; extrapolated with the last slope.");
    else
      throw std::logic_error("anvil: '" + entry + "' is not a common hardening entry");
  }

  bool HardeningLaw::softened(const std::string &parameter) const
  {
    const auto &s = softened_parameters;
    return std::find(s.begin(), s.end(), parameter) != s.end() ||
           std::find(s.begin(), s.end(), "all") != s.end();
  }

  HardeningLaw::StrengthLimit HardeningLaw::strength_limit() const
  {
    return softening_limit(softened("initial yield stress") || softened("strength coefficient"));
  }

  HardeningLaw::StrengthLimit HardeningLaw::softening_limit(const bool yield_stress_softened) const
  {
    if (!yield_stress_softened || !thermal)
      return {};
    return {thermal->vanishing_temperature(), thermal->vanishing_location,
            thermal->vanishing_formula()};
  }

  void declare_hardening_parameters(ParameterHandler &prm)
  {
    const auto &registry = HardeningLawRegistry::instance();
    prm.enter_subsection("Hardening");
    prm.declare_entry("Model", "linear", Patterns::Selection(registry.names_pattern()),
                      "Yield stress sigma_v(eps, T): " + registry.documentation(" "));
    prm.declare_entry("Softened parameters", "all",
                      Patterns::MultipleSelection("all|none|initial yield stress|hardening modulus|"
                                                  "saturation stress|strength coefficient"),
                      "Which parameters the thermal softening factor multiplies (all: the whole "
                      "yield stress).");
    registry.declare_parameters(prm);
    declare_thermal_softening_parameters(prm);
    prm.leave_subsection();
  }

  std::unique_ptr<HardeningLaw> create_hardening_law(ParameterHandler  &prm,
                                                     const Scene       &scene,
                                                     const std::string &path)
  {
    const std::string p = path + "/Hardening";
    prm.enter_subsection("Hardening");
    auto law = HardeningLawRegistry::instance().create(prm.get("Model"));
    law->softened_parameters = Utilities::split_string_list(prm.get("Softened parameters"));
    law->thermal             = create_thermal_softening(prm, scene, p);
    law->parse_parameters(prm, scene, p);
    law->location = scene.where(p + "/Model") + ": '" + p + "'";
    prm.leave_subsection();
    return law;
  }
} // namespace anvil
