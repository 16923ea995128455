#include <anvil/core/scene.h>
#include <anvil/material/hypoelastic.h>
#include <anvil/material/material_point.h>

namespace anvil
{
  using namespace dealii;

  namespace MaterialFactory
  {
    // Registered models. Each has a subsection of the same (capitalised) name.
    // Plastic laws (J2, Perzyna) register here as they are added.
    void declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Material");
      prm.declare_entry("Model", "hypoelastic", Patterns::Selection("hypoelastic"),
                        "The constitutive law of this body: hypoelastic (isotropic, "
                        "Jaumann rate via Hughes-Winget increments).");
      prm.enter_subsection("Hypoelastic");
      HypoelasticModel::declare_parameters(prm);
      prm.leave_subsection();
      prm.leave_subsection();
    }

    std::shared_ptr<const MaterialModel> create(ParameterHandler  &prm,
                                                const Scene       &scene,
                                                const std::string &path_prefix)
    {
      prm.enter_subsection("Material");
      const std::string                    model = prm.get("Model");
      std::shared_ptr<const MaterialModel> result;
      if (model == "hypoelastic")
        {
          prm.enter_subsection("Hypoelastic");
          const auto p =
            HypoelasticModel::parse_parameters(prm, scene, path_prefix + "/Material/Hypoelastic");
          prm.leave_subsection();
          result = std::make_shared<HypoelasticModel>(p);
        }
      prm.leave_subsection();
      if (!result)
        scene.fail(path_prefix + "/Material/Model", "names no known model");
      return result;
    }
  } // namespace MaterialFactory
} // namespace anvil
