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
  /**
   * Entry (p, q) of the factored C (or S if @p SENSITIVITY) on raw 6x6
   * storage, with fp = n[p] times the normal coefficient and @p r = v (or w):
   * the sums fill_tangent()/fill_sensitivity() (j2_tangent.h) form, the same
   * bits. One place for the planar rows (planar_tangent.cc) and the
   * plane-strain kernel's rows (plane_strain_rows.cc), which must agree bit
   * for bit (test plane_strain_rows).
   */
  template <bool SENSITIVITY>
  [[gnu::always_inline]] inline double factored_entry(const FactoredTangent &f, const unsigned int p,
                                                      const unsigned int q, const double fp,
                                                      const double *r)
  {
    double e = fp * f.n[q];
    if (SENSITIVITY)
      {
        const double a = f.sensitivity_deviatoric;
        if (p < 3 && q < 3)
          e = (p == q ? 1. - a * (2. / 3) : a * (1. / 3)) + e;
        else if (p == q)
          e = 0.5 * (1 - a) + e;
      }
    else if (p < 3 && q < 3)
      e = (f.bulk + f.deviatoric * ((p == q ? 1. : 0.) - 1. / 3)) + e;
    else if (p == q)
      e = 0.5 * f.deviatoric + e;
    if (f.rank_one)
      e += f.u[p] * r[q];
    return e;
  }
} // namespace anvil
