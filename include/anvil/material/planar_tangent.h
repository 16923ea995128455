#pragma once

#include <anvil/material/kinematics.h>

namespace anvil
{
  /**
   * planar_cauchy_tangent (kinematics.h) with only the raw components 00,
   * 11, 22, 01 of each δσ written (02, 12 are left as they were): what a
   * planar element formulation reads, whose F⁻¹ meets the others with zeros
   * (stress_divergence.cc). The same bits as planar_cauchy_tangent in these
   * components. Needs IncrementalKinematics::planar and the Jaumann rate.
   */
  void planar_cauchy_tangent_in_plane(const IncrementalKinematics          &kin,
                                      const dealii::SymmetricTensor<2, 3> &stress_old,
                                      const MaterialResponse              &response,
                                      const TangentDirections             &directions,
                                      dealii::SymmetricTensor<2, 3>       *dsigma);
} // namespace anvil
