#include <anvil/core/scene.h>
#include <anvil/material/softening/interface.h>

namespace anvil
{
  using namespace dealii;

  void ThermalSoftening::parse_parameters(ParameterHandler &, const Scene &, const std::string &) {}

  void declare_thermal_softening_parameters(ParameterHandler &prm)
  {
    const auto &registry = ThermalSofteningRegistry::instance();
    prm.enter_subsection("Thermal softening");
    prm.declare_entry("Model", "none", Patterns::Selection(registry.names_pattern()),
                      "Factor theta(T) on the softened yield parameters. " +
                        registry.documentation(" "));
    prm.declare_entry("Reference temperature", "293", Patterns::Double(0),
                      "T_ref in K: the temperature at which the yield parameters are given.");
    registry.declare_parameters(prm);
    prm.leave_subsection();
  }

  std::unique_ptr<ThermalSoftening> create_thermal_softening(ParameterHandler  &prm,
                                                             const Scene       &scene,
                                                             const std::string &path)
  {
    prm.enter_subsection("Thermal softening");
    auto law   = ThermalSofteningRegistry::instance().create(prm.get("Model"));
    law->T_ref = prm.get_double("Reference temperature");
    if (!(law->T_ref > 0))
      scene.fail(path + "/Thermal softening/Reference temperature",
                 "= " + std::to_string(law->T_ref) + " K: expected an absolute temperature > 0 K");
    law->parse_parameters(prm, scene, path + "/Thermal softening");
    const std::string entry = path + "/Thermal softening/" + law->vanishing_entry();
    law->vanishing_location = scene.where(entry) + ": '" + entry + "'";
    prm.leave_subsection();
    return law;
  }
} // namespace anvil
