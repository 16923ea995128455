// Scratch and copy data of the mechanical assembly (assembly_data.h).
#include <deal.II/base/quadrature_lib.h>

#include <anvil/core/instantiate.h>
#include <anvil/mechanics/assembly_data.h>

namespace anvil
{
  namespace MechanicsAssembly
  {
    using namespace dealii;

    template <int dim>
    ScratchData<dim>::ScratchData(const Mapping<dim>        &mapping,
                                  const FiniteElement<dim>  &fe,
                                  const Quadrature<dim>     &quadrature,
                                  const Quadrature<dim - 1> &face_quadrature,
                                  const UpdateFlags          cell_flags)
      : cell_flags(cell_flags)
      , fe_values(mapping, fe, quadrature, cell_flags)
      , fe_center(mapping, fe, QMidpoint<dim>(),
                  update_gradients | update_values | update_quadrature_points)
      , fe_face_values(mapping, fe, face_quadrature,
                       update_values | update_gradients | update_normal_vectors |
                         update_JxW_values | update_quadrature_points)
      , local_u(fe.n_dofs_per_cell())
      , local_u_old(fe.n_dofs_per_cell())
      , local_v_old(fe.n_dofs_per_cell())
      , local_a_old(fe.n_dofs_per_cell())
      , local_a(fe.n_dofs_per_cell())
      , T_new(quadrature.size())
      , center_trace(fe.n_dofs_per_cell())
      , points(quadrature.size())
      , G(fe.n_dofs_per_cell())
      , AG(fe.n_dofs_per_cell())
      , cell_mass(fe.n_dofs_per_cell(), fe.n_dofs_per_cell())
      , face_grad_u(face_quadrature.size())
      , face_u(face_quadrature.size())
      , face_d_nda(fe.n_dofs_per_cell())
    {}

    template <int dim>
    ScratchData<dim>::ScratchData(const ScratchData &other)
      : ScratchData(other.fe_values.get_mapping(), other.fe_values.get_fe(),
                    other.fe_values.get_quadrature(), other.fe_face_values.get_quadrature(),
                    other.cell_flags)
    {}

    CopyData::CopyData(const unsigned int n_dofs, const unsigned int n_q_points)
      : matrix(n_dofs, n_dofs)
      , rhs(n_dofs)
      , internal(n_dofs)
      , external(n_dofs)
      , inertia(n_dofs)
      , dof_indices(n_dofs)
      , audit(n_q_points)
    {}

    ANVIL_INSTANTIATE_CLASS(ScratchData)
  } // namespace MechanicsAssembly
} // namespace anvil
