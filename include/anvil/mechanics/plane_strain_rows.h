#pragma once

#include <anvil/material/kinematics.h>

namespace anvil
{
  namespace MechanicsAssembly
  {
    /**
     * planar_cauchy_tangent_in_plane (material/planar_tangent.h) for what the
     * plane-strain Q1 kernel reads: the four in-plane directions (0,0), (0,1),
     * (1,0), (1,1), and of each δσ the raw components 00, 11, 01 only (22 is
     * set to 0: a plane-strain A never reads it, stress_divergence.cc). The
     * material's factored C and S are expanded on those rows and columns only
     * (9 + 9 entries instead of 16 + 12). The same bits as the general
     * function in these components. Returns false, writing nothing, where it
     * does not apply (a dense tangent, out-of-plane σₙ, other directions):
     * the caller takes the general function.
     */
    bool plane_strain_tangent_rows(const IncrementalKinematics          &kin,
                                   const dealii::SymmetricTensor<2, 3> &stress_old,
                                   const MaterialResponse              &response,
                                   const TangentDirections             &directions,
                                   dealii::SymmetricTensor<2, 3>       *dsigma);
  } // namespace MechanicsAssembly
} // namespace anvil
