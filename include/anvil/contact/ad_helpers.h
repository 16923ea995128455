#pragma once

#include <deal.II/base/tensor.h>
#include <deal.II/differentiation/ad.h>

namespace anvil
{
  namespace contact
  {
    /// Small helpers shared by the rigid tools and the contact elements, which
    /// evaluate their geometry with doubles or with forward-AD numbers.
    namespace internal
    {
      using ADNumber = Sacado::Fad::DFad<double>;

      inline double value_of(const double x) { return x; }
      inline double value_of(const ADNumber &x) { return x.val(); }

      /// a . b for tensors of possibly different number types (a carries the result type).
      template <int dim, typename Number, typename Other>
      Number dot(const dealii::Tensor<1, dim, Number> &a, const dealii::Tensor<1, dim, Other> &b)
      {
        Number s = 0;
        for (unsigned int d = 0; d < dim; ++d)
          s += a[d] * b[d];
        return s;
      }
    } // namespace internal
  }   // namespace contact
} // namespace anvil
