// The assembly's Q1 mapping whose values do not depend on the order of the
// cells a thread visits (assembly_mapping.h).
#include <deal.II/fe/fe_values.h>

#include <anvil/core/instantiate.h>
#include <anvil/mechanics/assembly_mapping.h>

namespace anvil
{
  namespace MechanicsAssembly
  {
    using namespace dealii;

    template <int dim>
    AssemblyMapping<dim>::AssemblyMapping()
      : MappingQ<dim>(1)
    {}

    template <int dim>
    AssemblyMapping<dim>::AssemblyMapping(const AssemblyMapping &other)
      : MappingQ<dim>(other)
      , chain_start(other.chain_start)
      , loop_cells(other.loop_cells)
      , n_active_cells(other.n_active_cells)
      , values(other.values)
      , values_refused(other.values_refused)
    {}

    template <int dim>
    std::unique_ptr<Mapping<dim>> AssemblyMapping<dim>::clone() const
    {
      return std::make_unique<AssemblyMapping<dim>>(*this);
    }

    template <int dim>
    void AssemblyMapping<dim>::reinit(
      const std::vector<typename Triangulation<dim>::cell_iterator> &cells,
      const unsigned int                                              n_active_cells_)
    {
      n_active_cells = n_active_cells_;
      loop_cells     = cells;
      values.reset();
      values_refused = false;
      local_ids.clear();
      vector_ids.clear();
      matrix_slots_.clear();
      owned_ids.clear();
      for (auto &set : constrained_sets)
        set.flags.clear();
      // The test FEValues::reinit() makes against the cell it saw before.
      chain_start.assign(n_active_cells, typename Triangulation<dim>::cell_iterator());
      for (unsigned int i = 0; i < cells.size(); ++i)
        chain_start[cells[i]->active_cell_index()] =
          (i > 0 && cells[i]->is_translation_of(cells[i - 1])) ?
            chain_start[cells[i - 1]->active_cell_index()] :
            cells[i];
    }

    template <int dim>
    const ReferenceValues<dim> *
    AssemblyMapping<dim>::reference_values(const FiniteElement<dim>        &fe,
                                           const Quadrature<dim>           &quadrature,
                                           const std::vector<unsigned int> &component,
                                           const bool                       with_radius,
                                           const std::size_t                max_bytes) const
    {
      if (values && values->matches(fe, quadrature, with_radius))
        return values.get();
      if (values_refused)
        return nullptr;
      auto v = std::make_shared<ReferenceValues<dim>>();
      if (!v->build(*this, fe, quadrature, component, loop_cells, n_active_cells, with_radius,
                    max_bytes))
        {
          values_refused = true;
          return nullptr;
        }
      values = v;
      return values.get();
    }

    template <int dim>
    CellSimilarity::Similarity AssemblyMapping<dim>::fill_fe_values(
      const typename Triangulation<dim>::cell_iterator &cell,
      const CellSimilarity::Similarity,
      const Quadrature<dim>                                                &quadrature,
      const typename Mapping<dim>::InternalDataBase                        &internal_data,
      internal::FEValuesImplementation::MappingRelatedData<dim, dim> &output_data) const
    {
      const unsigned int index = cell->active_cell_index();
      if (index < chain_start.size() && chain_start[index].state() == IteratorState::valid &&
          chain_start[index] != cell)
        {
          // The chain start's Jacobians and JxW, then this cell's quadrature
          // points (a translation keeps the rest).
          MappingQ<dim>::fill_fe_values(chain_start[index], CellSimilarity::none, quadrature,
                                        internal_data, output_data);
          MappingQ<dim>::fill_fe_values(cell, CellSimilarity::translation, quadrature,
                                        internal_data, output_data);
        }
      else
        MappingQ<dim>::fill_fe_values(cell, CellSimilarity::none, quadrature, internal_data,
                                      output_data);
      // The finite element then computes its gradients from these Jacobians,
      // as the serial loop did at the chain start.
      return CellSimilarity::none;
    }

    ANVIL_INSTANTIATE_CLASS(AssemblyMapping)
  } // namespace MechanicsAssembly
} // namespace anvil
