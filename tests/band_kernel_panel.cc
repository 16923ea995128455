// The band LU's elimination in panels of four columns
// (source/core/band_elimination.cc) claims each entry gets dgbtf2's
// operations in dgbtf2's order, so its solution is that of plain Gaussian
// elimination with partial pivoting (first row of largest magnitude) on the
// same numbering, to the last bit. Independent answer: a dense LU written
// out here (n × n, every entry updated, no zero skipping, whole rows
// exchanged), its forward and back substitution column by column; the
// solutions must be equal (==: only the sign of an exact zero may differ).
// Matrices given directly in band storage (band_kernel::Band), no
// reordering: n = 1..13 and 37, 64, 101 (every n mod 4: the last panel of
// 1–3 columns), bandwidths 0–9 and 3 + 17, values dominant, not dominant,
// with a zero diagonal (every column pivots), with half the band's
// entries zero (the scans for zeros in L's columns and U's rows), and as a
// skyline (each row from a random first column, not dominant). Every case
// passes the bound on L's columns BandFactorization passes (the last row
// whose first entry lies at or left of the column): the elimination must
// not need what lies below it.
#include "check.h"

#include <anvil/core/band_elimination.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  anvil::testing::Checks check(anvil::testing::Checks::Print::failures_only);

  /// x = A⁻¹ b by dense Gaussian elimination with partial pivoting.
  std::vector<double> dense_solve(std::vector<std::vector<double>> a, std::vector<double> b)
  {
    const int n = b.size();
    for (int j = 0; j < n; ++j)
      {
        int p = j;
        for (int i = j + 1; i < n; ++i)
          if (std::abs(a[i][j]) > std::abs(a[p][j]))
            p = i;
        std::swap(a[j], a[p]);
        std::swap(b[j], b[p]);
        const double inverse_pivot = 1. / a[j][j]; // as the kernel rounds
        for (int i = j + 1; i < n; ++i)
          a[i][j] *= inverse_pivot;
        for (int i = j + 1; i < n; ++i)
          {
            b[i] -= b[j] * a[i][j];
            for (int c = j + 1; c < n; ++c)
              a[i][c] -= a[i][j] * a[j][c];
          }
      }
    for (int j = n - 1; j >= 0; --j)
      {
        b[j] /= a[j][j];
        for (int i = 0; i < j; ++i)
          b[i] -= b[j] * a[i][j];
      }
    return b;
  }
} // namespace

int main()
{
  std::mt19937                           random(16);
  std::uniform_real_distribution<double> value(-1., 1.);
  std::uniform_int_distribution<int>     coin(0, 1);
  const int sizes[]  = {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 37, 64, 101};
  const int widths[][2] = {{0, 0}, {1, 1}, {2, 1}, {1, 3}, {3, 3}, {5, 2}, {4, 9}, {9, 9}, {3, 17}};
  int       cases = 0, equal = 0;
  double    worst = 0;
  for (const int n : sizes)
    for (const auto &w : widths)
      for (int kind = 0; kind < 5; ++kind)
        {
          const int lower = w[0], upper = w[1];
          anvil::band_kernel::Band band{nullptr, n, lower, upper,
                                        anvil::band_kernel::column_stride(lower, upper),
                                        anvil::band_kernel::diagonal_row(lower, upper)};
          std::vector<double> storage(static_cast<std::size_t>(n) * band.stride, 0.);
          band.values = storage.data();
          std::vector<std::vector<double>> dense(n, std::vector<double>(n, 0.));
          std::vector<int>                 row_end(n);
          std::uniform_int_distribution<int> skyline(0, lower);
          for (int i = 0; i < n; ++i)
            {
              row_end[i]  = i;
              const int first = kind == 4 ? i - skyline(random) : i - lower;
              for (int j = std::max(0, i - lower); j <= std::min(n - 1, i + upper); ++j)
                {
                  double a = value(random);
                  if ((kind == 3 && i != j && coin(random)) || j < first)
                    a = 0;
                  if (i == j)
                    a = kind == 0 ? 3. * (lower + upper + 1) : kind == 2 ? 0. : kind == 3 ? 0.5 + a : a;
                  if (a == 0.)
                    continue;
                  dense[i][j] = a;
                  storage[static_cast<std::size_t>(j) * band.stride + band.diagonal + i - j] = a;
                  row_end[i] = std::max(row_end[i], j);
                }
            }
          std::vector<double> b(n);
          for (int i = 0; i < n; ++i)
            b[i] = std::cos(0.7 * i) + 0.2;
          std::vector<int> pivot(n), column_end(n, 0), column_top(n), first_row_of(n, 0);
          for (int i = 0; i < n; ++i)
            {
              int first = i;
              for (int j = 0; j < i; ++j)
                if (dense[i][j] != 0.)
                  {
                    first = j;
                    break;
                  }
              first_row_of[first] = std::max(first_row_of[first], i);
            }
          for (int j = 0, furthest = 0; j < n; ++j)
            {
              furthest      = std::max({furthest, first_row_of[j], j});
              column_end[j] = furthest - j;
            }
          const double     multiply_adds = anvil::band_kernel::eliminate(band, pivot.data(), column_end.data(),
                                                                     row_end.data(), column_top.data());
          ++cases;
          // A zero column (a singular draw) is reported as such; then dense
          // elimination divides by zero too: skip.
          if (multiply_adds < 0)
            {
              ++equal;
              continue;
            }
          std::vector<double> x = b;
          anvil::band_kernel::substitute(band, pivot.data(), column_end.data(), column_top.data(), x.data());
          const std::vector<double> y = dense_solve(dense, b);
          bool   same = true;
          double scale = 0, difference = 0;
          for (int i = 0; i < n; ++i)
            {
              same = same && x[i] == y[i];
              scale      = std::max(scale, std::abs(y[i]));
              difference = std::max(difference, std::abs(x[i] - y[i]));
            }
          equal += same;
          worst = std::max(worst, difference / scale);
          std::ostringstream name;
          name << "n = " << n << ", band " << lower << " + " << upper << ", kind " << kind
               << ": solution equal to dense LU's (largest difference " << difference / scale << ")";
          check(same, name.str());
        }
  std::ostringstream summary;
  summary << cases << " band matrices: " << equal
          << " solutions equal to dense Gaussian elimination's to the bit (largest relative difference "
          << worst << ", expected 0)";
  check.print_on_this_process(true);
  std::cout << "  " << summary.str() << std::endl;
  check(equal == cases, summary.str());
  return check.finish();
}
