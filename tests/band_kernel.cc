// The band LU's elimination kernel (source/core/band_factorization.cc): its
// update runs whole blocks of 4 rows into padding rows and two columns of U
// at a time, so every residue of a column's length mod 4 and odd counts of
// U's nonzeros must come out right. BandFactorization on its own (CSR in,
// arrays out), on w × 40 grids of 2 unknowns per point, 9-point couplings,
// w = 1..9 (columns of 1 to ~40 multipliers), numbered at random; and w = 3, 6
// with three far couplings (a band several times the envelope's width).
// Independent answers:
// - diagonally dominant values (no row exchange): the kernel's multiply-adds
//   equal the envelope's flops / 2, counted from the pattern alone (Σ_j l_j u_j);
// - values with no dominant diagonal, and with a zero diagonal (every column
//   pivots): backward error |b − A x|∞ / (|A|∞ |x|∞) ≤ 1e-14, and the
//   solution equal to dense Gaussian elimination with partial pivoting in the
//   original numbering to 1e-11 relative.
#include "check.h"

#include <anvil/core/band_factorization.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <numeric>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
  anvil::testing::Checks check;

  struct Csr
  {
    int                 n = 0;
    std::vector<int>    offsets, columns;
    std::vector<double> values;
  };

  /// kind 0: dominant diagonal; 1: diagonal ±1.5 beside entries in [−1, 1]; 2: zero diagonal.
  /// @p links: couplings between random far-apart points (as contact
  /// couples two faces): the band widens, most rows' envelope does not.
  Csr grid(const int w, const int h, const int kind, std::mt19937 &random, const int links = 0)
  {
    const int        n = 2 * w * h;
    std::vector<int> number(n);
    std::iota(number.begin(), number.end(), 0);
    std::shuffle(number.begin(), number.end(), random);
    std::vector<std::vector<int>> rows(n);
    for (int p = 0; p < w * h; ++p)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx)
          {
            const int x = p % w + dx, y = p / w + dy;
            if (x >= 0 && x < w && y >= 0 && y < h)
              for (int a = 0; a < 2; ++a)
                for (int b = 0; b < 2; ++b)
                  rows[number[2 * p + a]].push_back(number[2 * (y * w + x) + b]);
          }
    std::uniform_int_distribution<int> point(0, w * h - 1);
    for (int k = 0; k < links; ++k)
      {
        const int p = point(random), q = point(random);
        for (int a = 0; a < 2; ++a)
          for (int b = 0; b < 2; ++b)
            {
              rows[number[2 * p + a]].push_back(number[2 * q + b]);
              rows[number[2 * q + b]].push_back(number[2 * p + a]);
            }
      }
    for (auto &row : rows)
      {
        std::sort(row.begin(), row.end());
        row.erase(std::unique(row.begin(), row.end()), row.end());
      }
    std::uniform_real_distribution<double> value(-1, 1);
    Csr                                    A;
    A.n = n;
    A.offsets.push_back(0);
    for (int i = 0; i < n; ++i)
      {
        std::sort(rows[i].begin(), rows[i].end());
        for (const int j : rows[i])
          {
            A.columns.push_back(j);
            const double v = value(random);
            A.values.push_back(i != j ? v : kind == 0 ? 40 + v : kind == 1 ? (v > 0 ? 1.5 : -1.5) : 0.);
          }
        A.offsets.push_back(A.columns.size());
      }
    return A;
  }

  /// Dense Gaussian elimination with partial pivoting: x = A⁻¹ b.
  std::vector<double> dense_solve(const Csr &A, std::vector<double> b)
  {
    const int           n = A.n;
    std::vector<double> M(static_cast<std::size_t>(n) * n, 0.);
    for (int i = 0; i < n; ++i)
      for (int k = A.offsets[i]; k < A.offsets[i + 1]; ++k)
        M[std::size_t(i) * n + A.columns[k]] = A.values[k];
    for (int j = 0; j < n; ++j)
      {
        int p = j;
        for (int i = j + 1; i < n; ++i)
          if (std::abs(M[std::size_t(i) * n + j]) > std::abs(M[std::size_t(p) * n + j]))
            p = i;
        for (int c = 0; c < n; ++c)
          std::swap(M[std::size_t(j) * n + c], M[std::size_t(p) * n + c]);
        std::swap(b[j], b[p]);
        for (int i = j + 1; i < n; ++i)
          {
            const double l = M[std::size_t(i) * n + j] / M[std::size_t(j) * n + j];
            if (l == 0.)
              continue;
            for (int c = j; c < n; ++c)
              M[std::size_t(i) * n + c] -= l * M[std::size_t(j) * n + c];
            b[i] -= l * b[j];
          }
      }
    for (int j = n - 1; j >= 0; --j)
      {
        for (int c = j + 1; c < n; ++c)
          b[j] -= M[std::size_t(j) * n + c] * b[c];
        b[j] /= M[std::size_t(j) * n + j];
      }
    return b;
  }

  std::string sci(const double v)
  {
    std::ostringstream s;
    s << v;
    return s.str();
  }

  double largest(const std::vector<double> &v)
  {
    double m = 0;
    for (const double x : v)
      m = std::max(m, std::abs(x));
    return m;
  }
} // namespace

int main()
{
  std::mt19937 random(14);
  // w = 1..9 plain; then w = 3, 6 with 3 far couplings (the scans' bounds
  // of each row's and column's nonzeros, U's column tops in the solve).
  for (int test = 0; test < 11; ++test)
    for (int kind = 0; kind < 3; ++kind)
      {
        const int                 w = test < 9 ? test + 1 : 3 * (test - 8), links = test < 9 ? 0 : 3;
        const Csr                 A = grid(w, 40, kind, random, links);
        anvil::BandFactorization band;
        band.analyze(A.n, A.offsets.data(), A.columns.data());
        band.factorize(A.offsets.data(), A.columns.data(), A.values.data());
        std::vector<double> b(A.n), x(A.n), r(A.n);
        for (int i = 0; i < A.n; ++i)
          b[i] = std::sin(0.37 * i) + 0.1 * (i % 3);
        band.solve(x.data(), b.data());
        double norm = 0;
        for (int i = 0; i < A.n; ++i)
          {
            double s = 0, row = 0;
            for (int k = A.offsets[i]; k < A.offsets[i + 1]; ++k)
              {
                s += A.values[k] * x[A.columns[k]];
                row += std::abs(A.values[k]);
              }
            r[i] = s - b[i];
            norm = std::max(norm, row);
          }
        const double backward = largest(r) / (norm * largest(x));
        const std::string name = "w = " + std::to_string(w) + (links ? " + 3 links" : "") + (kind == 0 ? ", dominant" : kind == 1 ? ", not dominant" : ", zero diagonal") +
                                 " (band " + std::to_string(band.lower_bandwidth()) + " + " +
                                 std::to_string(band.upper_bandwidth()) + "): ";
        if (kind == 0 && links == 0)
          check(2 * band.last_multiply_adds == band.estimated_flops(),
                name + "multiply-adds " + sci(band.last_multiply_adds) +
                  " = envelope flops / 2 " + sci(band.estimated_flops() / 2));
        std::vector<double> y = dense_solve(A, b);
        for (int i = 0; i < A.n; ++i)
          y[i] -= x[i];
        const double difference = largest(y) / largest(x);
        check(backward <= 1e-14 && difference <= 1e-11,
              name + "backward error " + sci(backward) + " (<= 1e-14), against dense LU " +
                sci(difference) + " (<= 1e-11)");
      }
  return check.finish();
}
