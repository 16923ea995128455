#pragma once

#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/tria.h>

#include <anvil/mechanics/reference_values.h>

#include <array>
#include <memory>
#include <vector>

namespace anvil
{
  namespace MechanicsAssembly
  {
    /**
     * The Q1 mapping of the assembly, made independent of the order in which
     * a thread visits cells.
     *
     * deal.II's FEValues reuses the Jacobians, JxW and shape gradients of the
     * previous cell it was reinit()ed on when the new cell is a translation
     * of it (CellSimilarity::translation): on a regular mesh a serial loop
     * computes them once per run of translated cells and keeps them, which
     * differs from a fresh computation by round-off. With threads, each
     * ScratchData sees another sequence of cells, so the bits would depend on
     * the number of threads and on scheduling.
     *
     * This mapping gives every cell the values the serial loop gives it: it
     * computes them at the first cell of the cell's run of translations in
     * the loop's order (its "chain start", from reinit()) and then moves
     * the quadrature points to the cell. The result depends on the cell
     * alone, so the assembly is the serial loop's bit for bit on any number
     * of threads.
     */
    template <int dim>
    class AssemblyMapping : public dealii::MappingQ<dim>
    {
    public:
      AssemblyMapping();
      AssemblyMapping(const AssemblyMapping &other);

      /// The chain starts for @p cells, the cells in the order of the serial
      /// loop (FEValues would compare each with its predecessor).
      void reinit(const std::vector<typename dealii::Triangulation<dim>::cell_iterator> &cells,
                  unsigned int n_active_cells);

      std::unique_ptr<dealii::Mapping<dim>> clone() const override;

      /**
       * The reference values of the loop's cells under this mapping
       * (ReferenceValues), computed at the first call after reinit() and kept
       * while the element, quadrature and radius request stay the same; null
       * when they would take more than @p max_bytes (the assembly then runs
       * FEValues per cell). Not thread-safe: call it before the loop.
       */
      const ReferenceValues<dim> *reference_values(const dealii::FiniteElement<dim> &fe,
                                                   const dealii::Quadrature<dim>    &quadrature,
                                                   const std::vector<unsigned int>  &component,
                                                   bool                              with_radius,
                                                   std::size_t max_bytes = 64u << 20) const;

      /**
       * Per active cell index, @p n_dofs Epetra local row numbers of the
       * cell's dofs then @p n_dofs local column numbers (first −2: not
       * looked up yet), for the assembly's copier: kept with the reference
       * values, valid while the matrix is (forget_local_indices() when a new
       * matrix is made). Not thread-safe: the copier runs serially.
       */
      int *local_indices(unsigned int active_cell_index, unsigned int n_dofs) const
      {
        if (local_ids.empty())
          local_ids.assign(std::size_t(2) * n_dofs * n_active_cells, -2);
        return &local_ids[std::size_t(2) * n_dofs * active_cell_index];
      }
      void forget_local_indices() const
      {
        local_ids.clear();
        matrix_slots_.clear();
      }

      /// matrix_slots(): not looked up yet (first slot of a cell), and the
      /// cell has a row or column this process cannot add by position.
      static constexpr unsigned char slot_unknown = 255, slot_refused = 254;

      /**
       * Per active cell index, where the cell's @p n_dofs² matrix entries
       * (i, j), row-major, sit in their rows of the matrix's CRS storage
       * (Epetra_CrsMatrix::ExtractCrsDataPointers): entry (i, j) is at
       * row_start[row i] + slot, so that the copier adds each entry where
       * SumIntoMyValues would have found it, without searching the row. One
       * byte per entry (rows of at most 254 entries; longer rows: the cell is
       * refused): 4× less than whole positions, 663 → 166 B/DoF in 3D
       * (doc/memory.md). First slot slot_unknown: not looked up yet;
       * slot_refused: add otherwise. Kept with local_indices()
       * (forget_local_indices() when a new matrix is made); null when all
       * cells' slots would take more than @p max_bytes. Not thread-safe: the
       * copier runs serially.
       */
      unsigned char *matrix_slots(unsigned int active_cell_index, unsigned int n_dofs,
                                  std::size_t max_bytes = 64u << 20) const
      {
        const std::size_t per_cell = std::size_t(n_dofs) * n_dofs;
        if (matrix_slots_.empty())
          {
            if (per_cell * n_active_cells > max_bytes)
              return nullptr;
            matrix_slots_.assign(per_cell * n_active_cells, slot_unknown);
          }
        return &matrix_slots_[per_cell * active_cell_index];
      }

      /**
       * Per active cell index, the local numbers of its @p n_dofs dofs in the
       * owned (non-ghosted) vectors' map, −1 for a dof owned elsewhere (first
       * −2: not looked up yet), for the copier's additions into the force
       * vectors. Valid while the dof numbering is (cleared by reinit()).
       */
      int *owned_vector_indices(unsigned int active_cell_index, unsigned int n_dofs) const
      {
        if (owned_ids.empty())
          owned_ids.assign(std::size_t(n_dofs) * n_active_cells, -2);
        return &owned_ids[std::size_t(n_dofs) * active_cell_index];
      }

      /**
       * Per active cell index, the local numbers of its @p n_dofs dofs in the
       * ghosted vectors' map (first −2: not looked up yet), so that the
       * worker reads u, uₙ, vₙ, aₙ without a global-to-local look-up per
       * value. Sized by reserve_vector_indices() before the loop (serially);
       * a worker then fills and reads only its own cell's entries.
       */
      void reserve_vector_indices(const unsigned int n_dofs) const
      {
        if (vector_ids.empty())
          vector_ids.assign(std::size_t(n_dofs) * n_active_cells, -2);
      }
      int *vector_indices(unsigned int active_cell_index, unsigned int n_dofs) const
      {
        return &vector_ids[std::size_t(n_dofs) * active_cell_index];
      }

      /// owned_vector_indices() of a cell, looked up in @p owned_map on first use.
      template <typename Map, typename Indices>
      int *owned_vector_indices(unsigned int active_cell_index, unsigned int n_dofs, const Indices &dofs,
                                const Map &owned_map) const
      {
        int *const own = owned_vector_indices(active_cell_index, n_dofs);
        if (own[0] == -2)
          for (unsigned int i = 0; i < n_dofs; ++i)
            own[i] = owned_map.LID(static_cast<decltype(owned_map.GID(0))>(dofs[i]));
        return own;
      }

      /// A cell's flag in constrained_cells()'s table, looked up on first use.
      template <typename Constraints, typename Indices>
      static bool is_constrained(signed char &flag, const Indices &dofs, unsigned int n_dofs,
                                 const Constraints &constraints)
      {
        if (flag < 0)
          {
            flag = 0;
            for (unsigned int i = 0; i < n_dofs; ++i)
              if (constraints.is_constrained(dofs[i]))
                flag = 1;
          }
        return flag;
      }

      /**
       * Per active cell index, whether one of its dofs is constrained (1),
       * none is (0) or not looked up yet (−1), for the constraints whose
       * constrained dofs are @p constrained (sorted): the copier then adds a
       * cell by positions without asking AffineConstraints about each of its
       * dofs at every assembly. Kept for the two sets seen last (the
       * predictor's and the iterations' constraints alternate in every
       * step) while the dof numbering is (cleared by reinit()). Not
       * thread-safe: the copier runs serially.
       */
      template <typename Lines>
      signed char *constrained_cells(const Lines &constrained) const
      {
        const auto same = [&](const std::vector<std::size_t> &dofs) {
          if (dofs.size() != constrained.size())
            return false;
          std::size_t k = 0;
          for (const auto &line : constrained)
            if (dofs[k++] != line.index)
              return false;
          return true;
        };
        for (auto &set : constrained_sets)
          if (!set.flags.empty() && same(set.dofs))
            return set.flags.data();
        auto &set = constrained_sets[next_constrained_set];
        next_constrained_set ^= 1;
        set.dofs.clear();
        for (const auto &line : constrained)
          set.dofs.push_back(line.index);
        set.flags.assign(n_active_cells, -1);
        return set.flags.data();
      }

    protected:
      dealii::CellSimilarity::Similarity
      fill_fe_values(const typename dealii::Triangulation<dim>::cell_iterator &cell,
                     dealii::CellSimilarity::Similarity                     cell_similarity,
                     const dealii::Quadrature<dim>                          &quadrature,
                     const typename dealii::Mapping<dim>::InternalDataBase  &internal_data,
                     dealii::internal::FEValuesImplementation::MappingRelatedData<dim, dim>
                       &output_data) const override;

    private:
      /// Per active cell index: the first cell of its run of translations.
      std::vector<typename dealii::Triangulation<dim>::cell_iterator> chain_start;
      /// The loop's cells (reinit()) and their values, once computed.
      std::vector<typename dealii::Triangulation<dim>::cell_iterator> loop_cells;
      unsigned int                                                     n_active_cells = 0;
      mutable std::shared_ptr<ReferenceValues<dim>>                    values;
      mutable bool                                                     values_refused = false;
      mutable std::vector<int>           local_ids, vector_ids, owned_ids;
      mutable std::vector<unsigned char> matrix_slots_;
      struct ConstrainedSet
      {
        std::vector<std::size_t> dofs;
        std::vector<signed char> flags;
      };
      mutable std::array<ConstrainedSet, 2> constrained_sets;
      mutable unsigned int                  next_constrained_set = 0;
    };
  } // namespace MechanicsAssembly
} // namespace anvil
