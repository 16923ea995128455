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
                     MPI_Comm                          comm);

      /// Whether @p copy is this object's (a dof owned elsewhere, or constrained).
      bool takes(const CopyData &copy) const;
      void add(const CopyData &copy);
      /// Collective: every process's rows owned elsewhere added by their owners.
      void exchange();

      /// Number of rows owned elsewhere this assembly touched (a test's figure).
      std::size_t n_rows() const { return rows.size(); }

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
      struct Row
      {
        int                               row;
        std::vector<std::pair<int, double>> entries; // by column, sorted
        std::array<double, 4>             vectors{};
      };

      Row    &remote_row(Index row);
      void    add_remote(Index row, unsigned int n, const Index *columns, const double *values);
      void    add_owned(int local_row, Index row, unsigned int n, const Index *columns, const double *values);
      double &vector_entry(unsigned int k, Index row);

      const AssemblyMapping<dim>              &mapping;
      const dealii::AffineConstraints<double> &constraints;
      Epetra_CrsMatrix                        *matrix;
      std::array<double *, 4>                  vectors;
      const Epetra_BlockMap                   &owned_map;
      const unsigned int                       n_dofs;
      const bool                               dynamic;
      const MPI_Comm                           comm;
      signed char                             *constrained_cells;
      std::vector<Row>                         rows;
      std::unordered_map<Index, unsigned int>  row_at;
      std::vector<int>                         columns; // work space
    };
  } // namespace MechanicsAssembly
} // namespace anvil
