#pragma once

// Per-thread scratch and per-cell copy data of the heat problem's assembly
// (step-44's pattern): WorkStream gives every worker thread its own
// ScratchData (FEValues and point buffers) and hands each cell's CopyData to
// one serial copier, in cell order, so the global sums are those of a serial
// loop, bit for bit.

#include <deal.II/base/quadrature.h>
#include <deal.II/base/tensor.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <vector>

namespace anvil
{
  namespace thermal
  {
    /// Heat flux into the body at a boundary point and its derivative (mW/mm², mW/(mm² K)).
    struct BoundaryFlux
    {
      double into_body = 0; // q_in
      double d_dT      = 0; // ∂q_in/∂T
    };

    template <int dim>
    struct ScratchData
    {
      /**
       * @p mapping: the current configuration (volume and boundary terms);
       * @p reference_mapping: the reference one (heat capacity: ρ dv = ρ₀ dV).
       * A flag set of update_default leaves that FEValues object unused.
       */
      ScratchData(const dealii::Mapping<dim>        &mapping,
                  const dealii::Mapping<dim>        &reference_mapping,
                  const dealii::FiniteElement<dim>  &fe,
                  const dealii::Quadrature<dim>     &quadrature,
                  const dealii::Quadrature<dim - 1> &face_quadrature,
                  dealii::UpdateFlags                cell_flags,
                  dealii::UpdateFlags                reference_flags,
                  dealii::UpdateFlags                face_flags);
      /// WorkStream copies the sample for every thread; FEValues are rebuilt
      /// on a copy of the current mapping: MappingQEulerian computes its
      /// support points under a lock, which one copy per thread avoids.
      ScratchData(const ScratchData &other);

    private:
      std::unique_ptr<const dealii::Mapping<dim>> own_mapping; // null in the sample
      ScratchData(std::unique_ptr<const dealii::Mapping<dim>> mapping, const ScratchData &other);

    public:
      dealii::FEValues<dim>     fe_values;    // current configuration
      dealii::FEValues<dim>     fe_reference; // reference configuration
      dealii::FEFaceValues<dim> fe_face;      // current configuration

      // At the cell's quadrature points.
      std::vector<double>                 weight;    // JxW, × 2πr if axisymmetric
      std::vector<double>                 T;         // K
      std::vector<dealii::Tensor<1, dim>> grad_T;    // K/mm
      std::vector<double>                 rate;      // s − ρc ġ_D, mW/mm³
      dealii::Vector<double>              g_dot;     // ġ at the cell's dofs (Dirichlet lift), K/s
      // At the face's quadrature points.
      std::vector<double>       face_weight;
      std::vector<double>       face_T;
      std::vector<BoundaryFlux> face_flux;
    };

    /// One cell's contribution: local matrix, vector, row sums (lumped mass) and dof indices.
    struct CopyData
    {
      explicit CopyData(unsigned int dofs_per_cell);

      dealii::FullMatrix<double>                   matrix;
      dealii::Vector<double>                       vector, row_sums;
      std::vector<dealii::types::global_dof_index> dofs;
      unsigned int                                 cell_index = 0; // active cell index
      /// Loops that add each face on its own (the prescribed fluxes of the
      /// fast linear path): the first n_faces entries are this cell's faces.
      std::vector<dealii::Vector<double>> face_vectors;
      unsigned int                        n_faces = 0;
    };
  } // namespace thermal
} // namespace anvil
