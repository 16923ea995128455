// The kinematics' special paths against the general 3x3 one (kinematics.h):
//  1. plane strain / axisymmetric gradients F = [F_2x2, 0; 0, F33] through the
//     2x2 path (kinematics_planar_path) and the general path: every quantity
//     equal to round-off (1e-13 of its size), random F, F_n with rotations up
//     to 0.7 rad and stretches up to 30 %;
//     and cauchy_tangent's planar form (planar_tangent.cc) against the
//     general one, for random material tangents, prestress with and without
//     the out-of-plane shears 02, 12, identity or general sensitivity;
//  2. the closed-form Cayley transforms of the Jaumann path against
//     (I - h)^-1 (I + h) by deal.II's invert(), h = 1/4 (dL - dL^T), in 3D.
// Prints the largest relative difference of each check; fails above 1e-13.
#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <anvil/material/kinematics.h>
#include <anvil/material/material_point.h>

#include <cmath>
#include <cstdio>
#include <random>

using namespace dealii;
using namespace anvil;

namespace
{
  std::mt19937                           rng(42);
  std::uniform_real_distribution<double> uniform(-1, 1);

  /// A gradient R U: rotation about z (planar) or about a random axis, stretch U.
  Tensor<2, 3> random_gradient(const bool planar)
  {
    Tensor<2, 3> U;
    for (unsigned int i = 0; i < 3; ++i)
      for (unsigned int j = i; j < 3; ++j)
        U[i][j] = U[j][i] = (i == j ? 1 : 0) + 0.15 * uniform(rng);
    Tensor<1, 3> axis({planar ? 0. : uniform(rng), planar ? 0. : uniform(rng), 1.});
    axis /= axis.norm();
    const double angle = 0.7 * uniform(rng);
    Tensor<2, 3> W, I = unit_symmetric_tensor<3>();
    W[0][1] = -axis[2], W[1][0] = axis[2], W[0][2] = axis[1], W[2][0] = -axis[1];
    W[1][2] = -axis[0], W[2][1] = axis[0];
    const Tensor<2, 3> R = I + std::sin(angle) * W + (1 - std::cos(angle)) * W * W;
    Tensor<2, 3>       F = R * U;
    if (planar)
      F[0][2] = F[1][2] = F[2][0] = F[2][1] = 0;
    return F;
  }

  double relative(const Tensor<2, 3> &a, const Tensor<2, 3> &b)
  {
    return (a - b).norm() / std::max(b.norm(), 1e-300);
  }
  double relative(const SymmetricTensor<2, 3> &a, const SymmetricTensor<2, 3> &b)
  {
    return (a - b).norm() / std::max(b.norm(), 1e-300);
  }
} // namespace

int main()
{
  const double tolerance = 1e-13;
  double       planar_worst = 0, cayley_worst = 0, tangent_worst = 0;
  for (unsigned int trial = 0; trial < 1000; ++trial)
    {
      const Tensor<2, 3> F = random_gradient(true), F_old = random_gradient(true);
      IncrementalKinematics planar, general;
      planar.reinit(F, F_old, ObjectiveRate::jaumann, kinematics_all);
      general.reinit(F, F_old, ObjectiveRate::jaumann, kinematics_all & ~kinematics_planar_path);
      for (const double d :
           {relative(planar.F_inv, general.F_inv), std::abs(planar.J - general.J) / general.J,
            relative(planar.F_half_inv, general.F_half_inv), relative(planar.dL, general.dL),
            relative(planar.A_inv, general.A_inv), relative(planar.A_half_inv, general.A_half_inv),
            relative(planar.half_rotation, general.half_rotation),
            relative(planar.rotation_increment, general.rotation_increment),
            relative(planar.mid_strain, general.mid_strain) * general.mid_strain.norm() /
              std::max(general.dL.norm(), 1e-300),
            relative(planar.strain_increment, general.strain_increment) *
              general.strain_increment.norm() / std::max(general.dL.norm(), 1e-300)})
        planar_worst = std::max(planar_worst, d);

      // cauchy_tangent: directions of an axisymmetric element (with the hoop).
      MaterialResponse response;
      for (unsigned int p = 0; p < 36; ++p)
        {
          response.tangent.begin_raw()[p]                    = 1e5 * uniform(rng);
          response.rotated_stress_sensitivity.begin_raw()[p] = uniform(rng);
        }
      response.sensitivity_is_identity = trial % 2 == 0;
      SymmetricTensor<2, 3> sigma_n;
      for (unsigned int c = 0; c < 6; ++c)
        sigma_n.access_raw_entry(c) = (c >= 4 && trial % 3 == 0) ? 0. : 200 * uniform(rng);
      const TangentDirections directions = TangentDirections::in_plane(2, true);
      SymmetricTensor<2, 3>   ds_planar[9], ds_general[9];
      cauchy_tangent(planar, sigma_n, response, directions, ds_planar);
      cauchy_tangent(general, sigma_n, response, directions, ds_general);
      double scale = 0;
      for (unsigned int d = 0; d < directions.n; ++d)
        scale = std::max(scale, ds_general[d].norm());
      for (unsigned int d = 0; d < directions.n; ++d)
        tangent_worst = std::max(tangent_worst, (ds_planar[d] - ds_general[d]).norm() / scale);

      // 3D: the closed forms against explicit inverses.
      const Tensor<2, 3> G = random_gradient(false), G_old = random_gradient(false);
      IncrementalKinematics kin;
      kin.reinit(G, G_old, ObjectiveRate::jaumann);
      const Tensor<2, 3> I  = unit_symmetric_tensor<3>();
      const Tensor<2, 3> dL = (G - G_old) * invert(0.5 * (G + G_old));
      const Tensor<2, 3> h  = 0.25 * (dL - transpose(dL));
      for (const double d :
           {relative(kin.A_inv, invert(I - h)), relative(kin.A_half_inv, invert(I - 0.5 * h)),
            relative(kin.rotation_increment, invert(I - h) * (I + h)),
            relative(kin.half_rotation, invert(I - 0.5 * h) * (I + 0.5 * h))})
        cayley_worst = std::max(cayley_worst, d);
    }
  std::printf("planar path vs general path, 1000 random F, F_n: largest relative difference %.2e "
              "(tolerance %.0e)\n", planar_worst, tolerance);
  std::printf("closed-form Cayley transforms vs invert(), 1000 random 3D F, F_n: largest relative "
              "difference %.2e (tolerance %.0e)\n", cayley_worst, tolerance);
  std::printf("planar cauchy_tangent vs general, 1000 random cases: largest difference %.2e of "
              "the largest dsigma (tolerance %.0e)\n", tangent_worst, tolerance);
  const bool ok = planar_worst <= tolerance && cayley_worst <= tolerance &&
                  tangent_worst <= tolerance;
  std::printf("%s\n", ok ? "PASS" : "FAIL");
  return ok ? 0 : 1;
}
