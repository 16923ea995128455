#include <anvil/coupling/interface.h>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  void declare_coupling_parameters(ParameterHandler &prm)
  {
    const auto &schemes = CouplingSchemeRegistry<dim>::instance();
    prm.enter_subsection("Physics");
    prm.declare_entry("Coupling", "mechanical only", Patterns::Selection(schemes.names_pattern()),
                      "Which physics the scene solves and how they are coupled (seed sec. 2.2). " +
                        schemes.documentation(" "));
    schemes.declare_parameters(prm);
    prm.leave_subsection();
  }

#define INSTANTIATE(dim) template void declare_coupling_parameters<dim>(ParameterHandler &);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
