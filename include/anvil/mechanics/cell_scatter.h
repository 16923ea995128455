#pragma once
// The assembly's copier: one cell's K, −R and force vectors added into the
// global objects. It runs serially and in cell order (WorkStream's copier),
// so the global sums are the serial loop's, bit for bit, on any number of
// threads.
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <anvil/mechanics/assembly_data.h>
#include <anvil/mechanics/assembly_mapping.h>

class Epetra_BlockMap;
class Epetra_CrsMatrix;

namespace anvil
{
  namespace MechanicsAssembly
  {
    /// Whether two maps number the same global indices in the same local
    /// order (the local part of Epetra's collective SameAs()).
    bool same_local_map(const Epetra_BlockMap &a, const Epetra_BlockMap &b);

    /// The global objects one assembly adds into.
    struct AssemblyTargets
    {
      dealii::TrilinosWrappers::SparseMatrix *matrix; // null: the residual only
      dealii::TrilinosWrappers::MPI::Vector  &rhs;
      dealii::TrilinosWrappers::MPI::Vector  &internal;
      dealii::TrilinosWrappers::MPI::Vector  &external;
      dealii::TrilinosWrappers::MPI::Vector  &inertia;
    };

    /**
     * A cell with no constrained dof and only owned rows and columns adds
     * its matrix straight into Epetra's CRS value array, at the positions of
     * its entries found once per cell and matrix pattern
     * (AssemblyMapping::matrix_slots, within rows numbered as the owned
     * vectors' entries), and its vectors by owned local
     * index: no search of a row, no global-to-local look-up. Each entry gets
     * the one addition SumIntoMyValues and Vector::add would make, in the
     * same cell order: the same bits. Otherwise local row and column numbers
     * or, with constraints, AffineConstraints.
     */
    template <int dim>
    class CellScatter
    {
    public:
      CellScatter(const AssemblyMapping<dim>               &mapping,
                  const dealii::AffineConstraints<double> &constraints,
                  const AssemblyTargets                   &targets,
                  unsigned int                             n_dofs,
                  bool                                     dynamic);

      void add(const CopyData &copy);

    private:
      using Vector = dealii::TrilinosWrappers::MPI::Vector;

      double    *owned_values(Vector &v) const;
      const int *owned_indices(const CopyData &copy) const;
      const unsigned char *matrix_slots(const CopyData &copy, const int *own) const;
      bool find_slots(const CopyData &copy, const int *own, unsigned char *slot) const;
      bool       add_by_local_indices(const CopyData &copy);
      bool       add_unconstrained(const CopyData &copy, const int *own);
      void       add_force(Vector &v, double *values, const int *own, const CopyData &copy,
                           const dealii::Vector<double> &local);

      const AssemblyMapping<dim>               &mapping;
      const dealii::AffineConstraints<double> &constraints;
      AssemblyTargets                          targets;
      const unsigned int                       n_dofs;
      const bool                               dynamic;
      const Epetra_BlockMap                   &owned_map;
      Epetra_CrsMatrix                        *matrix = nullptr;
      int    *row_start = nullptr, *row_columns = nullptr;
      double *matrix_values = nullptr; // null: no addition by slots
      double *rhs_values, *internal_values, *external_values, *inertia_values;
      signed char *constrained_cells;
    };
  } // namespace MechanicsAssembly
} // namespace anvil
