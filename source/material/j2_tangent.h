// Raw-storage helpers of the J2 point's tangents (j2_finish.cc and
// j2_plasticity.cc): filling and updating SymmetricTensor<4,3> entries
// without deal.II's temporaries. Internal linkage (an unnamed namespace):
// with external linkage GCC stops inlining the single-caller
// fill_tangent/fill_sensitivity (+7 % instructions per J2 update).
#pragma once

#include <deal.II/base/symmetric_tensor.h>

namespace anvil
{
  namespace
  {
    using dealii::SymmetricTensor;

    /// C += s a⊗b on raw storage (deal.II's outer_product() and operator+= build
    /// two 6x6 temporaries for it). Entries where a or b is zero are skipped
    /// (adding s (0 · b) changes no entry's value): nothing if b = 0 (an elastic
    /// adiabatic point has no ∂ΔT_ad/∂σ̃ₙ), the 4x4 block of the normal and
    /// (0,1) components if the out-of-plane shears are zero (plane problems).
    inline void add_outer_product(SymmetricTensor<4, 3> &C, const double s,
                                  const SymmetricTensor<2, 3> &a, const SymmetricTensor<2, 3> &b)
    {
      double       *c  = C.begin_raw();
      const double *ar = a.begin_raw(), *br = b.begin_raw();
      if (br[0] == 0 && br[1] == 0 && br[2] == 0 && br[3] == 0 && br[4] == 0 && br[5] == 0)
        return;
      const unsigned int n = ar[4] == 0 && ar[5] == 0 && br[4] == 0 && br[5] == 0 ? 4 : 6;
      for (unsigned int p = 0; p < n; ++p)
        for (unsigned int q = 0; q < n; ++q)
          c[6 * p + q] += s * (ar[p] * br[q]);
    }

    // The unrolled (raw) storage of SymmetricTensor<2,3> is 00, 11, 22, 01, 02, 12,
    // that of SymmetricTensor<4,3> the 6x6 matrix of components C_{(ij)(kl)} in
    // that order, row by row (deal.II's contractions weigh the off-diagonal
    // pairs themselves). In that storage I_dev has 2/3, −1/3 in the normal
    // block and 1/2 on the shear diagonal, δ⊗δ ones in the normal block, and
    // I_sym 1, 1/2 on the diagonal.

    /// C = K δ⊗δ + c_d I_dev (+ c_n n⊗n if @p with_n), raw storage. Row by
    /// row, c_n n_p once per row and the entries in runs of three (the
    /// compiler pairs them): each entry the sum it always was,
    /// (K + c_d(δ_pq − ⅓)) + (c_n n_p) n_q, the zero bases of the shear block
    /// added as before (0 + x is not x for x = −0).
    template <bool with_n>
    inline void fill_tangent(double *C, const double K, const double cd, const double cn,
                             const double *n)
    {
      const double diag = K + cd * (1. - 1. / 3), off = K + cd * (0. - 1. / 3);
#pragma GCC unroll 6
      for (unsigned int p = 0; p < 6; ++p)
        {
          double      *row = C + 6 * p;
          const double f   = with_n ? cn * n[p] : 0.;
          if (p < 3)
            {
              #pragma GCC unroll 6
              for (unsigned int q = 0; q < 3; ++q)
                row[q] = (p == q ? diag : off) + (with_n ? f * n[q] : 0.);
              #pragma GCC unroll 6
              for (unsigned int q = 3; q < 6; ++q)
                row[q] = with_n ? f * n[q] : 0.;
            }
          else
            {
              #pragma GCC unroll 6
              for (unsigned int q = 0; q < 3; ++q)
                row[q] = with_n ? f * n[q] : 0.;
              #pragma GCC unroll 6
              for (unsigned int q = 3; q < 6; ++q)
                row[q] = (p == q ? 0.5 * cd : 0.) + (with_n ? f * n[q] : 0.);
            }
        }
    }

    /// S = I_sym − b n⊗n − a (I_dev − n⊗n) = I_sym − a I_dev + (a − b) n⊗n, raw
    /// storage, row by row like fill_tangent().
    inline void fill_sensitivity(double *S, const double a, const double b, const double *n)
    {
      const double c    = a - b;
      const double diag = 1. - a * (2. / 3), off = a * (1. / 3), shear = 0.5 * (1 - a);
#pragma GCC unroll 6
      for (unsigned int p = 0; p < 6; ++p)
        {
          double      *row = S + 6 * p;
          const double f   = c * n[p];
          if (p < 3)
            {
              #pragma GCC unroll 6
              for (unsigned int q = 0; q < 3; ++q)
                row[q] = (p == q ? diag : off) + f * n[q];
              #pragma GCC unroll 6
              for (unsigned int q = 3; q < 6; ++q)
                row[q] = f * n[q];
            }
          else
            {
              #pragma GCC unroll 6
              for (unsigned int q = 0; q < 3; ++q)
                row[q] = f * n[q];
              #pragma GCC unroll 6
              for (unsigned int q = 3; q < 6; ++q)
                row[q] = (p == q ? shear : 0.) + f * n[q];
            }
        }
    }
  } // namespace
} // namespace anvil
