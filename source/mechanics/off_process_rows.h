// The assembly's rows owned by other processes, gathered per process and sent
// to their owners in one exchange (private to source/mechanics: assembly.cc
// and off_process_rows.cc).
#pragma once

#include <deal.II/lac/affine_constraints.h>

#include <anvil/mechanics/assembly_data.h>
#include <anvil/mechanics/assembly_mapping.h>

#include <mpi.h>

#include <array>
#include <unordered_map>
#include <utility>
#include <vector>

class Epetra_BlockMap;
class Epetra_CrsMatrix;

namespace anvil
{
  namespace MechanicsAssembly
  {
    /**
     * On several processes, the cells CellScatter would add through deal.II
     * (a dof owned elsewhere, or a constrained dof): their owned rows go
     * straight into the Epetra matrix and vectors, as deal.II's add would
     * put them (Epetra_CrsMatrix::SumIntoGlobalValues, by owned local index),
     * their other rows into this object's per-row sums. exchange() sends
     * those to their owners at once — one Alltoallv of values, not deal.II's
     * compress (Epetra_FECrsMatrix::GlobalAssemble builds a map, a matrix
     * and an Export of the off-process rows at every call, and every
     * process pays its collectives even with nothing to send).
     *
     * The matrix then needs no compress(): nothing in it went through
     * deal.II. The four vectors (−R, f_int, f_ext, M a) get only owned
     * entries, by local index.
     */
    /**
     * What OffProcessRows keeps while the matrix's pattern stays
     * (MechanicalProblem::off_process_plan, reset by setup_matrix()): the
     * rows owned elsewhere with their entries, where each interface cell's
     * entries are summed (sender), and where each value received lands in
     * the owned CRS storage (owner). The first assembly of a pattern finds
     * them by searching; the next ones add by position.
     */
    struct OffProcessPlan
    {
      using Index = dealii::types::global_dof_index;
      struct Row
      {
        int                                 row;
        std::vector<std::pair<int, double>> entries; // by column, sorted
        std::array<double, 4>               vectors{};
      };
      std::vector<Row>                        rows;
      std::unordered_map<Index, unsigned int> row_at;
      /// Changes when a row or an entry is added (the pointers below are then stale).
      unsigned int version = 1;

      /// Sender: per cell with rows owned elsewhere (active cell index), its
      /// offset into slots (per such row in the cell's order, the pointers to
      /// its n_dofs entries' sums, by the cell's column order) and into
      /// slot_rows (those rows' places in rows). Valid for slots_version.
      std::unordered_map<unsigned int, std::pair<std::size_t, std::size_t>> cell_slots;
      std::vector<double *>     slots;
      std::vector<unsigned int> slot_rows;
      unsigned int              slots_version = 0;

      /// Owner: per sending process, the sender's version its positions
      /// were found for, and per row received its local row then per entry
      /// its index in the CRS values.
      std::vector<unsigned int>     received_version;
      std::vector<std::vector<int>> received_positions;
    };

    template <int dim>
    class OffProcessRows
    {
    public:
      /// @p matrix null: the residual only. @p vectors: −R, f_int, f_ext,
      /// M a, each the owned values in @p owned_map's order (M a may be null
      /// when not dynamic).
      OffProcessRows(const AssemblyMapping<dim>       &mapping,
                     const dealii::AffineConstraints<double> &constraints,
                     Epetra_CrsMatrix                 *matrix,
                     const std::array<double *, 4>    &vectors,
                     const Epetra_BlockMap            &owned_map,
                     unsigned int                      n_dofs,
                     bool                              dynamic,
                     MPI_Comm                          comm,
                     OffProcessPlan                   &plan);

      /// Whether @p copy is this object's (a dof owned elsewhere, or constrained).
      bool takes(const CopyData &copy) const;
      void add(const CopyData &copy);
      /// Collective: every process's rows owned elsewhere added by their owners.
      void exchange();

      /// Number of rows owned elsewhere this assembly touched (a test's figure).
      std::size_t n_rows() const { return plan.rows.size(); }

      // The targets deal.II's AffineConstraints writes into (its templates
      // call add() and operator() on them).
      struct MatrixTarget
      {
        using value_type = double;
        using size_type  = dealii::types::global_dof_index;
        // Polymorphic: deal.II's template dynamic_casts it to its own SparseMatrix.
        explicit MatrixTarget(OffProcessRows *rows) : rows(rows) {}
        virtual ~MatrixTarget() = default;
        OffProcessRows *rows;
        size_type       m() const;
        size_type       n() const { return m(); }
        void add(size_type row, size_type n, const size_type *columns, const double *values, bool, bool);
        void add(size_type row, size_type column, double value) { add(row, 1, &column, &value, false, true); }
      };
      struct VectorTarget
      {
        using value_type = double;
        using size_type  = dealii::types::global_dof_index;
        OffProcessRows *rows;
        unsigned int    k; // which vector
        size_type       size() const;
        double         &operator()(size_type i);
        void add(const std::vector<size_type> &indices, const std::vector<double> &values)
        {
          for (std::size_t i = 0; i < indices.size(); ++i)
            (*this)(indices[i]) += values[i];
        }
      };

    private:
      using Index = dealii::types::global_dof_index;
      using Row   = OffProcessPlan::Row;

      unsigned int remote_row(Index row);
      /// The entry (row, column)'s sum, made (−0: the sum of nothing, so
      /// that adding to it gives the value's bits) if new.
      double &remote_entry(Row &row, int column);
      void    add_remote(Index row, unsigned int n, const Index *columns, const double *values);
      void    add_owned(int local_row, Index row, unsigned int n, const Index *columns, const double *values);
      double &vector_entry(unsigned int k, Index row);
      /// The cell's slots and remote rows (OffProcessPlan::cell_slots), found on first use.
      std::pair<double *const *, const unsigned int *> cell_slots(const CopyData &copy, const int *own);
      /// The received rows added (by the positions found for @p sender's version, else by searching).
      void add_received(unsigned int sender, unsigned int version, const double *begin, const double *end);

      const AssemblyMapping<dim>              &mapping;
      const dealii::AffineConstraints<double> &constraints;
      Epetra_CrsMatrix                        *matrix;
      std::array<double *, 4>                  vectors;
      const Epetra_BlockMap                   &owned_map;
      const unsigned int                       n_dofs;
      const bool                               dynamic;
      const MPI_Comm                           comm;
      signed char                             *constrained_cells;
      OffProcessPlan                          &plan;
      std::vector<int>                         columns; // work space
    };
  } // namespace MechanicsAssembly
} // namespace anvil
