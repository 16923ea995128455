// The single-precision nodal-block copy of a smoothed level's matrix
// (float_block_matrix.h): its layout, made from Epetra's rows, and its product.
#include <deal.II/base/config.h>

#include <deal.II/base/exceptions.h>

#include "float_block_matrix.h"

#include <algorithm>

DEAL_II_DISABLE_EXTRA_DIAGNOSTICS
#include <Epetra_Comm.h>
#include <Epetra_CrsMatrix.h>
#include <Epetra_Import.h>
#include <Epetra_Map.h>
#include <Epetra_MultiVector.h>
#include <Epetra_Vector.h>
DEAL_II_ENABLE_EXTRA_DIAGNOSTICS

namespace anvil
{
  using namespace dealii;

  std::unique_ptr<FloatBlockMatrix> FloatBlockMatrix::make(const Epetra_CrsMatrix &A, const unsigned int block)
  {
    // Only a square matrix whose range is its row layout (the cycle's
    // levels): then Epetra itself multiplies into Y's own entries.
    const int rows = A.NumMyRows(), columns = A.ColMap().NumMyElements();
    bool      fits = block >= 2 && block <= 3 && A.Filled() && A.Exporter() == nullptr &&
                A.OperatorDomainMap().SameAs(A.OperatorRangeMap()) && rows % block == 0 &&
                columns % block == 0;
    // The blocks must be nodes, or zeros would fill them: every run of
    // `block` owned rows (and of column-map entries) is one node's
    // consecutive global indices.
    for (int i = 0; fits && i < rows; i += block)
      for (unsigned int c = 1; c < block; ++c)
        fits = fits && A.RowMap().GID64(i + c) == A.RowMap().GID64(i) + c;
    for (int i = 0; fits && i < columns; i += block)
      for (unsigned int c = 1; c < block; ++c)
        fits = fits && A.ColMap().GID64(i + c) == A.ColMap().GID64(i) + c;
    // Every process takes the same path, so that GMRES sees one operator.
    int here = fits ? 1 : 0, all = 0;
    A.Comm().MinAll(&here, &all, 1);
    if (all == 0)
      return nullptr;
    return std::unique_ptr<FloatBlockMatrix>(new FloatBlockMatrix(A, block));
  }

  FloatBlockMatrix::FloatBlockMatrix(const Epetra_CrsMatrix &A, const unsigned int block)
    : block(block)
    , domain(std::make_unique<Epetra_Map>(A.OperatorDomainMap()))
    , column_map(std::make_unique<Epetra_Map>(A.ColMap()))
    , importer(A.Importer() ? std::make_unique<Epetra_Import>(*A.Importer()) : nullptr)
  {
    const int        n_block_rows = A.NumMyRows() / block;
    std::vector<int> slot(A.ColMap().NumMyElements() / block, -1);
    std::vector<int> row_blocks;
    row_start.assign(n_block_rows + 1, 0);
    // Two passes: the blocks' columns (each row's in increasing order, so
    // that x is read forward), then the values into their slots.
    columns.reserve(A.NumMyNonzeros() / block + n_block_rows);
    for (int i = 0; i < n_block_rows; ++i)
      {
        row_blocks.clear();
        for (unsigned int r = 0; r < block; ++r)
          {
            int     n;
            double *v;
            int    *cols;
            A.ExtractMyRowView(i * block + r, n, v, cols);
            for (int e = 0; e < n; ++e)
              if (slot[cols[e] / block] == -1)
                {
                  slot[cols[e] / block] = 0;
                  row_blocks.push_back(cols[e] / block);
                }
          }
        std::sort(row_blocks.begin(), row_blocks.end());
        for (const int k : row_blocks)
          slot[k] = -1;
        columns.insert(columns.end(), row_blocks.begin(), row_blocks.end());
        row_start[i + 1] = columns.size();
      }
    columns.shrink_to_fit();
    const unsigned int bb = block * block;
    values.assign(columns.size() * bb, 0.f);
    for (int i = 0; i < n_block_rows; ++i)
      {
        for (int s = row_start[i]; s < row_start[i + 1]; ++s)
          slot[columns[s]] = s;
        for (unsigned int r = 0; r < block; ++r)
          {
            int     n;
            double *v;
            int    *cols;
            A.ExtractMyRowView(i * block + r, n, v, cols);
            for (int e = 0; e < n; ++e)
              values[std::size_t(slot[cols[e] / block]) * bb + r * block + cols[e] % block] = static_cast<float>(v[e]);
          }
        for (int s = row_start[i]; s < row_start[i + 1]; ++s)
          slot[columns[s]] = -1;
      }
  }

  FloatBlockMatrix::~FloatBlockMatrix() = default;

  template <int B>
  void FloatBlockMatrix::multiply(const double *x, double *y) const
  {
    const int    n_block_rows = row_start.size() - 1;
    const int   *start        = row_start.data();
    const int   *col          = columns.data();
    const float *v            = values.data();
    for (int i = 0; i < n_block_rows; ++i)
      {
        double s[B] = {};
        for (int e = start[i]; e < start[i + 1]; ++e)
          {
            const float  *a  = v + std::size_t(e) * B * B;
            const double *xx = x + B * col[e];
            for (int r = 0; r < B; ++r)
              for (int c = 0; c < B; ++c)
                s[r] += a[r * B + c] * xx[c];
          }
        for (int r = 0; r < B; ++r)
          y[B * i + r] = s[r];
      }
  }

  int FloatBlockMatrix::Apply(const Epetra_MultiVector &X, Epetra_MultiVector &Y) const
  {
    if (X.NumVectors() != Y.NumVectors())
      return -1;
    for (int k = 0; k < X.NumVectors(); ++k)
      {
        const double *x = X[k];
        if (importer)
          {
            if (!x_columns)
              x_columns = std::make_unique<Epetra_Vector>(*column_map, false);
            Epetra_Vector column(View, X.Map(), X[k]);
            if (x_columns->Import(column, *importer, Insert) != 0)
              return -2;
            x = x_columns->Values();
          }
        if (block == 3)
          multiply<3>(x, Y[k]);
        else
          multiply<2>(x, Y[k]);
      }
    return 0;
  }

  const Epetra_Comm &FloatBlockMatrix::Comm() const
  {
    return domain->Comm();
  }

  const Epetra_Map &FloatBlockMatrix::OperatorDomainMap() const
  {
    return *domain;
  }

  // Range = domain: make() takes only square matrices without an exporter.
  const Epetra_Map &FloatBlockMatrix::OperatorRangeMap() const
  {
    return *domain;
  }

  std::size_t FloatBlockMatrix::memory_consumption() const
  {
    return row_start.capacity() * sizeof(int) + columns.capacity() * sizeof(int) + values.capacity() * sizeof(float) +
           (x_columns ? std::size_t(x_columns->MyLength()) * sizeof(double) : 0);
  }
} // namespace anvil
