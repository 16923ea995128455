#pragma once

#include <deal.II/base/array_view.h>

#include <cstddef>
#include <vector>

namespace anvil
{
  /**
   * Data kept per quadrature point of the active cells of one triangulation:
   * material point state, heat sources, the temperature a point last saw.
   * The one place that knows how a (cell, q) pair becomes an index, so no
   * other file does `active_cell_index * n_q + q` arithmetic. Like deal.II's
   * CellDataStorage but contiguous and for any T (doubles included), which
   * keeps the hot assembly loops cache-friendly.
   *
   * Valid for one mesh: after refinement or load() call reinit() again.
   * Entries of cells that are not locally owned exist but are never touched.
   */
  template <typename T>
  class PointData
  {
  public:
    PointData() = default;

    template <class Triangulation>
    void reinit(const Triangulation &tria, const unsigned int n_points_per_cell,
                const T &value = T())
    {
      n_q = n_points_per_cell;
      data.assign(static_cast<std::size_t>(tria.n_active_cells()) * n_q, value);
    }

    void fill(const T &value) { std::fill(data.begin(), data.end(), value); }

    unsigned int points_per_cell() const { return n_q; }
    bool         empty() const { return data.empty(); }

    /// The points of one cell (any iterator with active_cell_index()).
    template <class CellIterator>
    dealii::ArrayView<T> operator[](const CellIterator &cell)
    {
      return dealii::ArrayView<T>(data.data() + index(cell, 0), n_q);
    }
    template <class CellIterator>
    dealii::ArrayView<const T> operator[](const CellIterator &cell) const
    {
      return dealii::ArrayView<const T>(data.data() + index(cell, 0), n_q);
    }
    template <class CellIterator>
    T &operator()(const CellIterator &cell, const unsigned int q)
    {
      return data[index(cell, q)];
    }
    template <class CellIterator>
    const T &operator()(const CellIterator &cell, const unsigned int q) const
    {
      return data[index(cell, q)];
    }

    /// Every point, in cell order (for whole-state copies: commit, revert).
    std::vector<T>       &raw() { return data; }
    const std::vector<T> &raw() const { return data; }

  private:
    template <class CellIterator>
    std::size_t index(const CellIterator &cell, const unsigned int q) const
    {
      return static_cast<std::size_t>(cell->active_cell_index()) * n_q + q;
    }

    unsigned int   n_q = 0;
    std::vector<T> data;
  };
} // namespace anvil
