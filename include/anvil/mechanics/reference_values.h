#pragma once

#include <deal.II/base/quadrature.h>
#include <deal.II/fe/fe.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/grid/tria.h>

#include <cstddef>
#include <vector>

namespace anvil
{
  namespace MechanicsAssembly
  {
    /**
     * What the mechanical kernels read of FEValues for one cell, as raw
     * arrays: per quadrature point q and shape function a the gradient and
     * value of a's own vector component, JxW, and the same at the cell centre
     * (F-bar). The updated-Lagrangian residual is integrated on the reference
     * mesh (P = J σ F⁻ᵀ, stress_divergence.cc), so none of this changes
     * between assemblies.
     */
    struct ReferenceCellValues
    {
      const double *grad         = nullptr; // [q][a][d]
      const double *value        = nullptr; // [q][a]
      const double *JxW          = nullptr; // [q]
      const double *centre_grad  = nullptr; // [a][d]
      const double *centre_value = nullptr; // [a]
      /// First coordinate of the points, then of the centre (the radius of
      /// the hoop term); null when the formulation needs no radius.
      const double *x = nullptr; // [q], [n_q] the centre
    };

    /**
     * The ReferenceCellValues of every cell of the assembly loop, computed once per
     * mesh by FEValues with the assembly's mapping: the same bits a fresh
     * FEValues::reinit() gives at every assembly (AssemblyMapping makes them
     * depend on the cell alone). Cells whose values are equal share one entry
     * (on a regular mesh the translated cells of a chain, AssemblyMapping):
     * the tube's 1200 cells keep a handful. Per cell only the radii, and only
     * if asked for.
     */
    template <int dim>
    class ReferenceValues
    {
    public:
      /// Number of doubles of one entry (@p n_q points, @p n_dofs shape functions).
      static std::size_t entry_size(unsigned int n_q, unsigned int n_dofs)
      {
        return n_q * n_dofs * dim + n_q * n_dofs + n_q + n_dofs * dim + n_dofs;
      }

      /// Copies what @p v (at the cell's points) and @p centre (at its centre,
      /// if not null) hold into @p entry (entry_size()) and the radii into @p x
      /// (n_q + 1, if not null).
      static void fill(const dealii::FEValues<dim>     &v,
                       const dealii::FEValues<dim>     *centre,
                       const std::vector<unsigned int> &component,
                       double                          *entry,
                       double                          *x);
      /// The view of @p entry and @p x as filled by fill().
      static ReferenceCellValues view(const double *entry, const double *x, unsigned int n_q,
                                unsigned int n_dofs);

      /**
       * Computes the values of @p cells (the loop's order), keeping at most
       * @p max_bytes of entries: false (and empty) if they need more.
       */
      bool build(const dealii::Mapping<dim>                                          &mapping,
                 const dealii::FiniteElement<dim>                                    &fe,
                 const dealii::Quadrature<dim>                                       &quadrature,
                 const std::vector<unsigned int>                                     &component,
                 const std::vector<typename dealii::Triangulation<dim>::cell_iterator> &cells,
                 unsigned int n_active_cells,
                 bool         with_radius,
                 std::size_t  max_bytes);

      /// Built for this element, quadrature and radius request.
      bool matches(const dealii::FiniteElement<dim> &fe, const dealii::Quadrature<dim> &quadrature,
                   bool with_radius) const
      {
        return &fe == fe_ptr && quadrature.size() == n_q && with_radius == radius;
      }

      ReferenceCellValues cell(const unsigned int active_cell_index) const
      {
        return view(entries.data() + entry_of[active_cell_index] * size,
                    radius ? radii.data() + static_cast<std::size_t>(active_cell_index) * (n_q + 1) :
                             nullptr,
                    n_q, n_dofs);
      }

      std::size_t n_entries() const { return size ? entries.size() / size : 0; }

    private:
      const dealii::FiniteElement<dim> *fe_ptr = nullptr;
      unsigned int                      n_q = 0, n_dofs = 0;
      std::size_t                       size   = 0;
      bool                              radius = false;
      std::vector<double>               entries;  // entry k at k * size
      std::vector<unsigned int>         entry_of; // per active cell index
      std::vector<double>               radii;    // per active cell index, n_q + 1
    };
  } // namespace MechanicsAssembly
} // namespace anvil
