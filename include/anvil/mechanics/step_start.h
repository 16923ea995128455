#pragma once

#include <deal.II/base/tensor.h>

#include <anvil/core/point_data.h>

#include <limits>

namespace anvil
{
  namespace MechanicsAssembly
  {
    /// What the kinematics of a point take from the start of the step, where
    /// u_n is constant: F_n and F-bar's root β_n = (J₀ₙ/det F_n)^α (1 without
    /// F-bar). The material's F̄_n = bar(F_n, β_n) is formed again at each
    /// read (9 products, the same bits): kept whole it was 72 B more per
    /// point, ~190 B/DoF in 3D (doc/memory.md).
    struct PointStart
    {
      dealii::Tensor<2, 3> F_old;
      double               beta_old;
    };

    /**
     * The points' start-of-step data (PointStart) of every cell, with the
     * dof values of u_n they were computed from: a cell's entries are set by
     * its first update in a step (u_n not the kept one) and read by the
     * later ones, so F_n and the root (J₀ₙ/det F_n)^α of F̄_n are computed
     * once per cell and step, not at every Newton iteration. Values, not a
     * memo of a computation's inputs: the key is u_n itself, so a cut-back,
     * a restart or a new mesh (reinit()) cannot leave stale entries. Owned
     * by the mechanical problem; a cell's entries belong to the thread that
     * assembles it.
     */
    struct StepStart
    {
      PointData<double>     u_old;  // per cell, n_dofs values (NaN: not set)
      PointData<PointStart> points; // per cell, n_q points

      template <class Triangulation>
      void reinit(const Triangulation &tria, const unsigned int n_dofs, const unsigned int n_q)
      {
        u_old.reinit(tria, n_dofs, std::numeric_limits<double>::quiet_NaN());
        points.reinit(tria, n_q);
      }
    };
  } // namespace MechanicsAssembly
} // namespace anvil
