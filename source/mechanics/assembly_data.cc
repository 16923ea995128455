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
      , own_values(ReferenceValues<dim>::entry_size(quadrature.size(), fe.n_dofs_per_cell()))
      , own_radii(quadrature.size() + 1)
      , local_u(fe.n_dofs_per_cell())
      , local_u_old(fe.n_dofs_per_cell())
      , local_v_old(fe.n_dofs_per_cell())
      , local_a_old(fe.n_dofs_per_cell())
      , local_a(fe.n_dofs_per_cell())
      , T_new(quadrature.size())
      , center_trace(fe.n_dofs_per_cell())
      , points(quadrature.size())
      , G(fe.n_dofs_per_cell())
      , Gt(9 * fe.n_dofs_per_cell())
      , AGt(10 * fe.n_dofs_per_cell())
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

    template <int dim>
    void ScratchData<dim>::reinit(const typename Triangulation<dim>::active_cell_iterator &c,
                                  const ReferenceValues<dim>      *reference,
                                  const std::vector<unsigned int> &component,
                                  const bool                       centre,
                                  const bool                       with_radius)
    {
      if (reference)
        {
          cell = reference->cell(c->active_cell_index());
          return;
        }
      fe_values.reinit(c);
      if (centre)
        fe_center.reinit(c);
      double *x = with_radius ? own_radii.data() : nullptr;
      ReferenceValues<dim>::fill(fe_values, centre ? &fe_center : nullptr, component,
                                 own_values.data(), x);
      cell = ReferenceValues<dim>::view(own_values.data(), x, fe_values.n_quadrature_points,
                                        fe_values.dofs_per_cell);
    }

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
