// The single-precision nodal-block copy of a smoothed level's matrix
// (float_block_matrix.h): its layout, made from Epetra's rows, and its product.
#include <deal.II/base/config.h>

#include <deal.II/base/exceptions.h>

#include "float_block_matrix.h"

#include <algorithm>
#include <cstdlib>
#include <string>

#include <immintrin.h>

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
    // levels): then the product lands in Y's own entries.
    const int rows = A.NumMyRows();
    bool      fits = block >= 2 && block <= 3 && A.Filled() && A.Exporter() == nullptr &&
                A.OperatorDomainMap().SameAs(A.OperatorRangeMap()) && A.RowMap().SameAs(A.OperatorRangeMap()) &&
                rows % block == 0;
    // The blocks must be nodes, or zeros would fill them: every run of
    // `block` owned rows is one node's global indices block·n … block·n +
    // block − 1. Then every process's are, and a ghost column's node is
    // its index / block.
    for (int i = 0; fits && i < rows; i += block)
      for (unsigned int c = 0; c < block; ++c)
        fits = fits && A.RowMap().GID64(i + c) == A.RowMap().GID64(i) + c && A.RowMap().GID64(i) % block == 0;
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
  {
    // x's layout: the owned entries (row order), then every component of
    // each ghost node that A's columns touch. A's column map holds only the
    // ghost columns with entries: a node on a Dirichlet face (uz given)
    // brings ux and uy alone, which would break the blocks; its uz is
    // imported too (a zero column of the block).
    const int         rows = A.NumMyRows(), n_columns = A.NumMyCols();
    n_owned_blocks         = rows / block;
    // position[j]: column j's place in x's layout (owned: its row; a ghost:
    // after the owned rows, its node's place among the ghost nodes).
    std::vector<int>  position(n_columns);
    std::vector<long> ghost_nodes;
    for (int j = 0; j < n_columns; ++j)
      {
        const long long gid = A.ColMap().GID64(j);
        position[j]         = A.RowMap().LID(gid);
        if (position[j] < 0)
          ghost_nodes.push_back(gid / block);
      }
    std::sort(ghost_nodes.begin(), ghost_nodes.end());
    ghost_nodes.erase(std::unique(ghost_nodes.begin(), ghost_nodes.end()), ghost_nodes.end());
    for (int j = 0; j < n_columns; ++j)
      if (position[j] < 0)
        {
          const long long gid  = A.ColMap().GID64(j);
          const auto      node = std::lower_bound(ghost_nodes.begin(), ghost_nodes.end(), gid / block);
          position[j]          = block * (n_owned_blocks + static_cast<int>(node - ghost_nodes.begin())) + gid % block;
        }
    // The ghosts alone are imported (an import into owned and ghost entries
    // copies the owned ones too: 3 % of np 2's products at 40³); the
    // product reads owned x from X itself.
    if (A.Comm().NumProc() > 1)
      {
        std::vector<int> ghosts;
        for (const long n : ghost_nodes)
          for (unsigned int c = 0; c < block; ++c)
            ghosts.push_back(static_cast<int>(n * block + c));
        column_map = std::make_unique<Epetra_Map>(-1, static_cast<int>(ghosts.size()), ghosts.data(), 0, A.Comm());
        importer   = std::make_unique<Epetra_Import>(*column_map, *domain);
      }
    const int        n_block_rows = rows / block;
    std::vector<int> slot(n_owned_blocks + ghost_nodes.size(), -1);
    std::vector<int> row_blocks;
    row_start.assign(n_block_rows + 1, 0);
    ghosts_from.assign(n_block_rows, 0);
    // f(row in the block, position in x's layout, value) for block row i's entries.
    const auto for_each_entry = [&](const int i, const auto &f) {
      for (unsigned int r = 0; r < block; ++r)
        {
          int     n;
          double *v;
          int    *cols;
          A.ExtractMyRowView(i * block + r, n, v, cols);
          for (int e = 0; e < n; ++e)
            f(r, position[cols[e]], v[e]);
        }
    };
    // Two passes: the blocks' columns (each row's in increasing order, so
    // that x is read forward), then the values into their slots.
    // At least entries / block² blocks; a row's partial blocks (a Dirichlet
    // dof's zero column) are few, so one spare per row rarely regrows.
    columns.reserve(A.NumMyNonzeros() / (block * block) + n_block_rows);
    for (int i = 0; i < n_block_rows; ++i)
      {
        row_blocks.clear();
        for_each_entry(i, [&](unsigned int, const int p, double) {
          if (slot[p / block] == -1)
            {
              slot[p / block] = 0;
              row_blocks.push_back(p / block);
            }
        });
        std::sort(row_blocks.begin(), row_blocks.end());
        for (const int k : row_blocks)
          slot[k] = -1;
        columns.insert(columns.end(), row_blocks.begin(), row_blocks.end());
        row_start[i + 1] = columns.size();
        ghosts_from[i]   = row_start[i] + (std::lower_bound(row_blocks.begin(), row_blocks.end(), n_owned_blocks) -
                                         row_blocks.begin());
      }
    columns.shrink_to_fit();
    // Column-major blocks, and `block` floats past the last: the vector
    // kernel loads four floats from each column's start.
    const unsigned int bb = block * block;
    values.assign(columns.size() * bb + block, 0.f);
    for (int i = 0; i < n_block_rows; ++i)
      {
        for (int s = row_start[i]; s < row_start[i + 1]; ++s)
          slot[columns[s]] = s;
        for_each_entry(i, [&](const unsigned int r, const int p, const double v) {
          values[std::size_t(slot[p / block]) * bb + (p % block) * block + r] = static_cast<float>(v);
        });
        for (int s = row_start[i]; s < row_start[i + 1]; ++s)
          slot[columns[s]] = -1;
      }
  }

  FloatBlockMatrix::~FloatBlockMatrix() = default;

  namespace
  {
    /// What the kernels read: block row i's blocks [start[i], start[i + 1]),
    /// those from ghost[i] on in ghost columns (x_ghost, numbered from
    /// n_owned), the others in owned ones (x).
    struct Layout
    {
      int           n_block_rows, n_owned;
      const int    *start, *ghost, *col;
      const float  *v;
      const double *x, *x_ghost;
    };

    /// y = A x, blocks of B × B floats (column-major), sums in double.
    template <int B>
    void multiply_portable(const Layout &m, double *y)
    {
      const auto add = [&](double *s, const int e, const double *xx) {
        const float *a = m.v + std::size_t(e) * B * B;
        for (int c = 0; c < B; ++c)
          for (int r = 0; r < B; ++r)
            s[r] += a[c * B + r] * xx[c];
      };
      for (int i = 0; i < m.n_block_rows; ++i)
        {
          double s[B] = {};
          for (int e = m.start[i]; e < m.ghost[i]; ++e)
            add(s, e, m.x + B * m.col[e]);
          for (int e = m.ghost[i]; e < m.start[i + 1]; ++e)
            add(s, e, m.x_ghost + B * (m.col[e] - m.n_owned));
          for (int r = 0; r < B; ++r)
            y[B * i + r] = s[r];
        }
    }

    /// The 3 × 3 product with AVX2 and FMA: a block's column (3 floats and
    /// the next one, ignored) widened to four doubles times the broadcast
    /// x_c; one accumulator per column, so that the FMAs do not wait on each
    /// other. The portable loop spends ~4 instructions an entry converting
    /// and multiplying one at a time, and so was bound by instructions, not
    /// by the memory it set out to save.
    __attribute__((target("avx2,fma"))) inline void add_3_avx2(__m256d &s0, __m256d &s1, __m256d &s2, const float *a,
                                                                const double *xx)
    {
      s0 = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(a)), _mm256_broadcast_sd(xx), s0);
      s1 = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(a + 3)), _mm256_broadcast_sd(xx + 1), s1);
      s2 = _mm256_fmadd_pd(_mm256_cvtps_pd(_mm_loadu_ps(a + 6)), _mm256_broadcast_sd(xx + 2), s2);
    }

    __attribute__((target("avx2,fma"))) void multiply_3_avx2(const Layout &m, double *y)
    {
      for (int i = 0; i < m.n_block_rows; ++i)
        {
          __m256d s0 = _mm256_setzero_pd(), s1 = _mm256_setzero_pd(), s2 = _mm256_setzero_pd();
          for (int e = m.start[i]; e < m.ghost[i]; ++e)
            add_3_avx2(s0, s1, s2, m.v + std::size_t(e) * 9, m.x + 3 * m.col[e]);
          for (int e = m.ghost[i]; e < m.start[i + 1]; ++e)
            add_3_avx2(s0, s1, s2, m.v + std::size_t(e) * 9, m.x_ghost + 3 * (m.col[e] - m.n_owned));
          alignas(32) double s[4];
          _mm256_store_pd(s, _mm256_add_pd(_mm256_add_pd(s0, s1), s2));
          y[3 * i]     = s[0];
          y[3 * i + 1] = s[1];
          y[3 * i + 2] = s[2];
        }
    }

    /// The processor's choice; ANVIL_FLOAT_KERNEL=portable forces the other
    /// (tests/float_block_matrix.cc checks both on one machine).
    bool use_avx2_fma()
    {
      static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
      const char       *forced = std::getenv("ANVIL_FLOAT_KERNEL");
      return has && !(forced && std::string(forced) == "portable");
    }
  } // namespace

  int FloatBlockMatrix::Apply(const Epetra_MultiVector &X, Epetra_MultiVector &Y) const
  {
    if (X.NumVectors() != Y.NumVectors())
      return -1;
    for (int k = 0; k < X.NumVectors(); ++k)
      {
        Layout m{static_cast<int>(ghosts_from.size()), n_owned_blocks, row_start.data(), ghosts_from.data(),
                 columns.data(), values.data(), X[k], nullptr};
        if (importer)
          {
            if (!x_columns)
              x_columns = std::make_unique<Epetra_Vector>(*column_map, false);
            Epetra_Vector column(View, X.Map(), X[k]);
            if (x_columns->Import(column, *importer, Insert) != 0)
              return -2;
            m.x_ghost = x_columns->Values();
          }
        if (block == 3 && use_avx2_fma())
          multiply_3_avx2(m, Y[k]);
        else if (block == 3)
          multiply_portable<3>(m, Y[k]);
        else
          multiply_portable<2>(m, Y[k]);
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
    return (row_start.capacity() + ghosts_from.capacity() + columns.capacity()) * sizeof(int) +
           values.capacity() * sizeof(float) +
           (x_columns ? std::size_t(x_columns->MyLength()) * sizeof(double) : 0);
  }
} // namespace anvil
