#include <anvil/core/scene.h>
#include <anvil/material/j2_plasticity.h>
#include <anvil/material/material_point.h>

namespace anvil
{
  using namespace dealii;

  namespace MaterialFactory
  {
    void declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Material");
      prm.declare_entry(
        "Model", "hypoelastic", Patterns::Selection("hypoelastic|J2|Perzyna"),
        "The constitutive law of this body (seed sec. 1.3): hypoelastic (thermo-elastic, "
        "Jaumann rate, subsection Elasticity); J2 (rate-independent von Mises plasticity with "
        "isotropic hardening, radial return: Elasticity, Hardening); Perzyna (J2 "
        "viscoplasticity returning to the generalized criterion of eq. 18: Elasticity, "
        "Hardening, Viscosity).");
      J2Model::declare_parameters(prm);
      prm.leave_subsection();
    }

    std::shared_ptr<const MaterialModel> create(ParameterHandler  &prm,
                                                const Scene       &scene,
                                                const std::string &path_prefix)
    {
      prm.enter_subsection("Material");
      const std::string model = prm.get("Model");
      auto              m     = std::make_shared<J2Model>();
      m->plastic              = model != "hypoelastic";
      const std::string path = path_prefix.empty() ? "Material" : path_prefix + "/Material";
      m->parse_parameters(prm, scene, path);
      if (model == "Perzyna")
        m->viscosity.parse_parameters(prm, scene, path, m->elastic.reference_temperature);
      prm.leave_subsection();
      return m;
    }

    std::shared_ptr<const MaterialModel> create_from_text(const std::string &settings)
    {
      ParameterHandler prm;
      declare_parameters(prm);
      prm.parse_input_from_string("subsection Material\n" + settings + "\nend\n");
      return create(prm, Scene(), "");
    }
  } // namespace MaterialFactory
} // namespace anvil
