#pragma once

#include <deal.II/base/types.h>
#include <deal.II/lac/trilinos_vector.h>

#include <functional>

namespace anvil
{
  /**
   * Heat exchanged at nodes outside the cells' coupling (contact conduction
   * and frictional heat, seed eq. 30–33), linear in T over a step:
   * f += q(T), ∂q/∂T applied matrix-free. Each function writes only locally
   * owned entries of its output. It lives in core/ because it is the whole
   * interface between its maker (contact) and its user (the heat problem):
   * neither includes the other.
   */
  struct HeatExchange
  {
    using Vector = dealii::TrilinosWrappers::MPI::Vector;
    std::function<void(double t, const Vector &T, Vector &f)> add_rhs;      // f += q(T)
    std::function<void(const Vector &v, Vector &Jv)>          add_jacobian; // Jv += ∂q/∂T v
    std::function<void(Vector &diagonal)>                     add_diagonal; // += −diag(∂q/∂T)
  };
} // namespace anvil
