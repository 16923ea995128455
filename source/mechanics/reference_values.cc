// The reference-mesh values of the mechanical assembly, computed once per
// mesh (reference_values.h).
#include <deal.II/base/quadrature_lib.h>

#include <anvil/core/instantiate.h>
#include <anvil/mechanics/reference_values.h>

#include <algorithm>
#include <cstring>

namespace anvil
{
  namespace MechanicsAssembly
  {
    using namespace dealii;

    template <int dim>
    void ReferenceValues<dim>::fill(const FEValues<dim>             &v,
                                    const FEValues<dim>             *centre,
                                    const std::vector<unsigned int> &component,
                                    double                          *entry,
                                    double                          *x)
    {
      const unsigned int n_q = v.n_quadrature_points, n_dofs = v.dofs_per_cell;
      double *grad = entry, *value = grad + n_q * n_dofs * dim, *JxW = value + n_q * n_dofs;
      double *centre_grad = JxW + n_q, *centre_value = centre_grad + n_dofs * dim;
      const bool values = v.get_update_flags() & update_values;
      for (unsigned int q = 0; q < n_q; ++q)
        {
          for (unsigned int a = 0; a < n_dofs; ++a)
            {
              const Tensor<1, dim> g = v.shape_grad_component(a, q, component[a]);
              for (unsigned int d = 0; d < dim; ++d)
                grad[(q * n_dofs + a) * dim + d] = g[d];
              value[q * n_dofs + a] = values ? v.shape_value_component(a, q, component[a]) : 0.;
            }
          JxW[q] = v.JxW(q);
          if (x)
            x[q] = v.quadrature_point(q)[0];
        }
      if (centre)
        {
          for (unsigned int a = 0; a < n_dofs; ++a)
            {
              const Tensor<1, dim> g = centre->shape_grad_component(a, 0, component[a]);
              for (unsigned int d = 0; d < dim; ++d)
                centre_grad[a * dim + d] = g[d];
              centre_value[a] = centre->shape_value_component(a, 0, component[a]);
            }
          if (x)
            x[n_q] = centre->quadrature_point(0)[0];
        }
    }

    template <int dim>
    ReferenceCellValues ReferenceValues<dim>::view(const double *entry, const double *x,
                                             const unsigned int n_q, const unsigned int n_dofs)
    {
      ReferenceCellValues c;
      c.grad         = entry;
      c.value        = c.grad + n_q * n_dofs * dim;
      c.JxW          = c.value + n_q * n_dofs;
      c.centre_grad  = c.JxW + n_q;
      c.centre_value = c.centre_grad + n_dofs * dim;
      c.x            = x;
      return c;
    }

    template <int dim>
    bool ReferenceValues<dim>::build(const Mapping<dim>                                     &mapping,
                                     const FiniteElement<dim>                               &fe,
                                     const Quadrature<dim>                                  &quadrature,
                                     const std::vector<unsigned int>                        &component,
                                     const std::vector<typename Triangulation<dim>::cell_iterator> &cells,
                                     const unsigned int n_active_cells,
                                     const bool         with_radius,
                                     const std::size_t  max_bytes)
    {
      fe_ptr = &fe;
      n_q    = quadrature.size();
      n_dofs = fe.n_dofs_per_cell();
      size   = entry_size(n_q, n_dofs);
      radius = with_radius;
      entries.clear();
      entry_of.assign(n_active_cells, 0);
      radii.assign(with_radius ? static_cast<std::size_t>(n_active_cells) * (n_q + 1) : 0, 0.);

      // The flags of the assembly's own FEValues and fe_center (assembly_data.cc).
      FEValues<dim> v(mapping, fe, quadrature,
                      update_gradients | update_values | update_JxW_values | update_quadrature_points);
      FEValues<dim> centre(mapping, fe, QMidpoint<dim>(),
                           update_gradients | update_values | update_quadrature_points);
      std::vector<double> entry(size);
      for (const auto &cell : cells)
        {
          v.reinit(cell);
          centre.reinit(cell);
          const unsigned int index = cell->active_cell_index();
          fill(v, &centre, component, entry.data(),
               with_radius ? radii.data() + static_cast<std::size_t>(index) * (n_q + 1) : nullptr);
          // A cell equal bit for bit to the last entry (the next cell of a
          // chain of translations) shares it.
          if (entries.empty() ||
              std::memcmp(entries.data() + entries.size() - size, entry.data(),
                          size * sizeof(double)) != 0)
            {
              if ((entries.size() + size) * sizeof(double) > max_bytes)
                {
                  *this = ReferenceValues();
                  return false;
                }
              entries.insert(entries.end(), entry.begin(), entry.end());
            }
          entry_of[index] = entries.size() / size - 1;
        }
      return true;
    }

    ANVIL_INSTANTIATE_CLASS(ReferenceValues)
  } // namespace MechanicsAssembly
} // namespace anvil
