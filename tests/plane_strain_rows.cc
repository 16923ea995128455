// The plane-strain rows of the Jaumann tangent (mechanics/plane_strain_rows.cc:
// the four in-plane directions at once, the factored C and S on the rows and
// columns 00, 11, 01 only) against two references on random planar
// kinematics, committed stresses and factored tangents (with and without the
// rank-one part, the normal term, an identity sensitivity):
//  - planar_cauchy_tangent_in_plane (planar_tangent.cc), whose operations it
//    repeats: expected the same bits in the components 00, 11, 01;
//  - the general cauchy_tangent (kinematics.cc, 3x3 tensors) on the dense C
//    and S of FactoredTangent::expand: expected within 1e-12 of the largest entry.
// Cases where it does not apply (out-of-plane σₙ, a dense tangent) must
// return false.
#include <anvil/material/kinematics.h>
#include <anvil/material/planar_tangent.h>
#include <anvil/mechanics/plane_strain_rows.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

using namespace dealii;
using namespace anvil;

namespace
{
  std::mt19937                           rng(11);
  std::uniform_real_distribution<double> uniform(-1, 1);

  Tensor<2, 3> random_planar_gradient(const double size)
  {
    Tensor<2, 3> F;
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        F[i][j] = (i == j ? 1. : 0.) + size * uniform(rng);
    F[2][2] = 1;
    return F;
  }

  FactoredTangent random_factored(const bool rank_one, const bool normal)
  {
    FactoredTangent f;
    f.active                 = true;
    f.rank_one               = rank_one;
    f.bulk                   = 7e4 * (1 + 0.1 * uniform(rng));
    f.deviatoric             = 5e4 * (1 + 0.1 * uniform(rng));
    f.normal                 = normal ? -3e4 * (1 + 0.1 * uniform(rng)) : 0.;
    f.sensitivity_deviatoric = 0.3 * uniform(rng);
    f.sensitivity_normal     = normal ? 0.2 * uniform(rng) : 0.;
    for (unsigned int p = 0; p < 6; ++p)
      {
        f.n[p] = uniform(rng);
        f.u[p] = rank_one ? 100 * uniform(rng) : 0.;
        f.v[p] = rank_one ? 100 * uniform(rng) : 0.;
        f.w[p] = rank_one ? 0.1 * uniform(rng) : 0.;
      }
    return f;
  }
} // namespace

int main()
{
  const TangentDirections directions = TangentDirections::in_plane(2, false);
  const unsigned int      rows[3]    = {0, 1, 3};
  double                  worst_general = 0;
  unsigned int            differ_bits = 0, n_cases = 0;
  bool                    refusals_ok = true;
  for (unsigned int trial = 0; trial < 400; ++trial)
    {
      const double         size = trial % 4 == 0 ? 1e-6 : 0.05;
      IncrementalKinematics kin;
      kin.reinit(random_planar_gradient(size), random_planar_gradient(size), ObjectiveRate::jaumann,
                 kinematics_all);
      SymmetricTensor<2, 3> stress_old;
      for (const unsigned int r : {0u, 1u, 2u, 3u})
        stress_old.access_raw_entry(r) = 200 * uniform(rng);
      MaterialResponse response;
      response.factored                = random_factored(trial % 2 == 1, trial % 3 != 0);
      response.sensitivity_is_identity = trial % 5 == 0;
      std::array<SymmetricTensor<2, 3>, 9> fast, planar, general;
      if (!MechanicsAssembly::plane_strain_tangent_rows(kin, stress_old, response, directions,
                                                        fast.data()))
        {
          std::printf("case %u refused\n", trial);
          return 1;
        }
      planar_cauchy_tangent_in_plane(kin, stress_old, response, directions, planar.data());
      MaterialResponse dense = response;
      dense.factored.active  = false;
      response.factored.expand(dense.tangent, response.sensitivity_is_identity ?
                                                nullptr :
                                                &dense.rotated_stress_sensitivity);
      cauchy_tangent(kin, stress_old, dense, directions, general.data());
      double scale = 0, diff = 0;
      for (unsigned int d = 0; d < 4; ++d)
        for (const unsigned int r : rows)
          {
            const double a = fast[d].access_raw_entry(r), b = planar[d].access_raw_entry(r),
                         g = general[d].access_raw_entry(r);
            differ_bits += a != b;
            scale = std::max(scale, std::abs(g));
            diff  = std::max(diff, std::abs(a - g));
          }
      worst_general = std::max(worst_general, diff / scale);
      ++n_cases;
      // Where it does not apply: out-of-plane σₙ, a dense tangent.
      SymmetricTensor<2, 3> shear = stress_old;
      shear[0][2]                 = 10;
      refusals_ok = refusals_ok &&
                    !MechanicsAssembly::plane_strain_tangent_rows(kin, shear, response, directions,
                                                                  fast.data()) &&
                    !MechanicsAssembly::plane_strain_tangent_rows(kin, stress_old, dense, directions,
                                                                  fast.data());
    }
  const bool ok = differ_bits == 0 && worst_general <= 1e-12 && refusals_ok;
  std::printf("%u cases: entries different from planar_cauchy_tangent_in_plane %u (expected 0); "
              "max |rows - general cauchy_tangent| / max |general| = %.2e (expected <= 1e-12); "
              "refused out-of-plane stress and dense tangent: %s\n%s\n",
              n_cases, differ_bits, worst_general, refusals_ok ? "yes" : "NO",
              ok ? "PASSED" : "FAILED");
  return ok ? 0 : 1;
}
