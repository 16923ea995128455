#pragma once

// A small dense solve for the material-point driver's local Newton loop on
// the stress-controlled components (at most 6 unknowns): no library needed.

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace anvil
{
  namespace point_driver
  {
    /// A small dense solve with partial pivoting: A x = b, b overwritten by x.
    /// Returns false if A is singular (relative to its largest entry).
    inline bool solve(std::vector<std::vector<double>> A, std::vector<double> &b)
    {
      const unsigned int n     = b.size();
      double             scale = 0;
      for (const auto &row : A)
        for (const double a : row)
          scale = std::max(scale, std::abs(a));
      if (!(scale > 0) || !std::isfinite(scale))
        return false;
      for (unsigned int k = 0; k < n; ++k)
        {
          unsigned int p = k;
          for (unsigned int i = k + 1; i < n; ++i)
            if (std::abs(A[i][k]) > std::abs(A[p][k]))
              p = i;
          if (std::abs(A[p][k]) <= 1e-14 * scale)
            return false;
          std::swap(A[k], A[p]);
          std::swap(b[k], b[p]);
          for (unsigned int i = k + 1; i < n; ++i)
            {
              const double m = A[i][k] / A[k][k];
              for (unsigned int j = k; j < n; ++j)
                A[i][j] -= m * A[k][j];
              b[i] -= m * b[k];
            }
        }
      for (unsigned int k = n; k-- > 0;)
        {
          for (unsigned int j = k + 1; j < n; ++j)
            b[k] -= A[k][j] * b[j];
          b[k] /= A[k][k];
        }
      return true;
    }

  } // namespace point_driver
} // namespace anvil
