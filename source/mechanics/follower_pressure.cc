// Follower pressure on boundary faces and its linearisation (assembly_kernels.h).
#include <anvil/core/instantiate.h>
#include <anvil/mechanics/assembly_kernels.h>

namespace anvil
{
  namespace MechanicsAssembly
  {
    using namespace dealii;

    template <int dim>
    void FollowerPressure<dim>::assemble(const CellIterator<dim> &cell, ScratchData<dim> &scratch,
                                         CopyData &copy) const
    {
      // f_ext = −∫ p n da N, n da = J F⁻ᵀ N dA (Nanson); in the axisymmetric
      // case per radian of the current radius r = R + u_r (times 2π: per ring).
      const Formulation<dim>          &formulation  = *context.formulation;
      const bool                       axisymmetric = formulation.axisymmetric;
      const unsigned int               n_dofs       = formulation.n_dofs;
      const auto                      &component    = formulation.component;
      FEFaceValues<dim>               &fe_face_values = scratch.fe_face_values;
      const FEValuesExtractors::Vector displacements(0);
      // By face number: a face iterator only for the cell's boundary faces
      // (the iterators of every face of every cell were most of this term's cost).
      for (const unsigned int f : cell->face_indices())
        if (cell->at_boundary(f))
          for (const auto &load : context.boundary_conditions->pressures())
            if (cell->face(f)->boundary_id() == load.boundary)
              {
                fe_face_values.reinit(cell, f);
                fe_face_values[displacements].get_function_gradients(*context.solution,
                                                                     scratch.face_grad_u);
                fe_face_values[displacements].get_function_values(*context.solution, scratch.face_u);
                for (unsigned int q = 0; q < fe_face_values.n_quadrature_points; ++q)
                  {
                    // The function's time is set before the threads start (value() is reentrant).
                    const double p = load.value->value(fe_face_values.quadrature_point(q));
                    const Tensor<2, dim> F     = unit_symmetric_tensor<dim>() + scratch.face_grad_u[q];
                    const double         J     = determinant(F);
                    const Tensor<2, dim> F_inv = invert(F);
                    const Tensor<1, dim> FiT_N = transpose(F_inv) * fe_face_values.normal_vector(q);
                    const double r = axisymmetric ? 2 * numbers::PI *
                                                      (fe_face_values.quadrature_point(q)[0] +
                                                       scratch.face_u[q][0]) :
                                                    1.;
                    const double JxW = fe_face_values.JxW(q);
                    // Per column j, δ(n da) for every row component: it does not
                    // depend on the row, so it is computed once, not once per (i, j).
                    if (context.with_matrix)
                      for (unsigned int j = 0; j < n_dofs; ++j)
                        {
                          const unsigned int   cj = component[j];
                          const Tensor<1, dim> g  = fe_face_values.shape_grad_component(j, q, cj);
                          double tr = 0; // tr(F⁻¹ δF) with δF = e_cj ⊗ g
                          for (unsigned int m = 0; m < dim; ++m)
                            tr += F_inv[m][cj] * g[m];
                          const Tensor<1, dim> FiT_g = transpose(F_inv) * g;
                          for (unsigned int c = 0; c < dim; ++c)
                            {
                              double d_nda = r * J * (tr * FiT_N[c] - FiT_g[c] * FiT_N[cj]);
                              if (axisymmetric && cj == 0) // δr = N_j
                                d_nda += 2 * numbers::PI * fe_face_values.shape_value(j, q) * J *
                                         FiT_N[c];
                              scratch.face_d_nda[j][c] = d_nda;
                            }
                        }
                    for (unsigned int i = 0; i < n_dofs; ++i)
                      {
                        const double Ni = fe_face_values.shape_value(i, q);
                        if (Ni == 0) // not a dof of this face: a row of zeros
                          continue;
                        const unsigned int ci = component[i];
                        copy.external(i) -= p * r * J * FiT_N[ci] * Ni * JxW;
                        if (context.with_matrix)
                          for (unsigned int j = 0; j < n_dofs; ++j)
                            // K = ∂f_int/∂u − ∂f_ext/∂u
                            copy.matrix(i, j) += p * scratch.face_d_nda[j][ci] * Ni * JxW;
                      }
                  }
              }
    }

    ANVIL_INSTANTIATE_CLASS(FollowerPressure)
  } // namespace MechanicsAssembly
} // namespace anvil
