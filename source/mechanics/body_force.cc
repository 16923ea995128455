// The body force ∫ ρ₀ g · δv dV (gravity), assembly_kernels.h.
#include <anvil/core/instantiate.h>
#include <anvil/mechanics/assembly_kernels.h>

namespace anvil
{
  namespace MechanicsAssembly
  {
    using namespace dealii;

    template <int dim>
    void BodyForce<dim>::assemble(ScratchData<dim> &scratch, CopyData &copy) const
    {
      // Reference configuration: ρ₀ dV is conserved.
      const Formulation<dim> &formulation = *context.formulation;
      for (unsigned int q = 0; q < scratch.points.size(); ++q)
        {
          const double w = scratch.points[q].w;
          for (unsigned int a = 0; a < formulation.n_dofs; ++a)
            {
              const unsigned int ca = formulation.component[a];
              const double       Na = scratch.cell.value[q * formulation.n_dofs + a];
              copy.external(a) += scratch.rho * context.gravity[ca] * Na * w;
            }
        }
    }

    ANVIL_INSTANTIATE_CLASS(BodyForce)
  } // namespace MechanicsAssembly
} // namespace anvil
