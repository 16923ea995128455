// The thermal cell loops' WorkStream over the locally owned cells, shared by
// the assembly files of source/thermal (private header).
#pragma once

#include <deal.II/base/work_stream.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/grid/filtered_iterator.h>

#include <anvil/thermal/assembly_data.h>

#include <functional>

namespace anvil::thermal
{
  /// WorkStream over the locally owned cells of @p dofs, in their order.
  template <int dim, class Worker, class Copier>
  void for_owned_cells(const dealii::DoFHandler<dim> &dofs, const Worker &worker, const Copier &copier,
                       const ScratchData<dim> &scratch)
  {
    using Iterator = dealii::FilteredIterator<typename dealii::DoFHandler<dim>::active_cell_iterator>;
    const std::function<void(const Iterator &, ScratchData<dim> &, CopyData &)> work =
      [&worker](const Iterator &cell, ScratchData<dim> &s, CopyData &c) {
        worker(static_cast<const typename dealii::DoFHandler<dim>::active_cell_iterator &>(cell), s, c);
      };
    const std::function<void(const CopyData &)> copy = copier;
    dealii::WorkStream::run(Iterator(dealii::IteratorFilters::LocallyOwnedCell(), dofs.begin_active()),
                    Iterator(dealii::IteratorFilters::LocallyOwnedCell(), dofs.end()), work, copy, scratch,
                    CopyData(dofs.get_fe().n_dofs_per_cell()));
  }
} // namespace anvil::thermal
