#include <anvil/core/scene.h>
#include <anvil/material/material_point.h>

namespace anvil
{
  using namespace dealii;

  namespace MaterialFactory
  {
    void declare_parameters(ParameterHandler &prm)
    {
      const auto &registry = MaterialModelRegistry::instance();
      prm.enter_subsection("Material");
      prm.declare_entry("Model", "hypoelastic", Patterns::Selection(registry.names_pattern()),
                        "The constitutive law of this body (seed sec. 1.3): " +
                          registry.documentation(" "));
      registry.declare_parameters(prm);
      prm.leave_subsection();
    }

    std::shared_ptr<const MaterialModel> create(ParameterHandler  &prm,
                                                const Scene       &scene,
                                                const std::string &path_prefix)
    {
      prm.enter_subsection("Material");
      std::shared_ptr<MaterialModel> m = MaterialModelRegistry::instance().create(prm.get("Model"));
      m->parse_parameters(prm, scene, path_prefix.empty() ? "Material" : path_prefix + "/Material");
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
