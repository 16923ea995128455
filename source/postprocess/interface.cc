#include <anvil/postprocess/interface.h>

namespace anvil
{
  template <int dim>
  void declare_postprocessor_parameters(dealii::ParameterHandler &prm)
  {
    prm.enter_subsection("Output");
    PostprocessorRegistry<dim>::instance().declare_parameters(prm);
    prm.leave_subsection();
  }

#define INSTANTIATE(dim) template void declare_postprocessor_parameters<dim>(dealii::ParameterHandler &);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
