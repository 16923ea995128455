// The consistent tangent A = dP/dF of the incremental (Hughes-Winget) update,
// as assembled by the mechanics, against central finite differences of P(F).
// Prestressed state, large increment with rotation; elastic material.
// Prints both and the relative error; fails above 1e-6.
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/material/hypoelastic.h>
#include <anvil/mechanics/kinematics.h>

#include <cmath>
#include <iostream>

using namespace dealii;
using namespace anvil;

template <int dim>
double check(const double angle)
{
  HypoelasticModel::Parameters p;
  p.bulk_modulus  = 70000;
  p.shear_modulus = 26923;
  HypoelasticModel model(p);

  SymmetricTensor<2, 3> sigma_n;
  sigma_n[0][0] = 150;
  sigma_n[1][1] = -40;
  sigma_n[0][1] = 35;
  sigma_n[2][2] = 20;
  if (dim == 3)
    {
      sigma_n[0][2] = -12;
      sigma_n[1][2] = 8;
    }

  Tensor<2, 3> F_old = unit_symmetric_tensor<3>();
  F_old[0][0] = 1.1, F_old[0][1] = 0.2, F_old[1][0] = -0.05, F_old[1][1] = 0.95;
  if (dim == 3)
    F_old[2][2] = 1.02, F_old[0][2] = 0.03, F_old[2][1] = -0.04;
  // Increment: a rotation by `angle` and a stretch.
  Tensor<2, 3> R = unit_symmetric_tensor<3>();
  R[0][0] = R[1][1] = std::cos(angle);
  R[0][1]           = -std::sin(angle);
  R[1][0]           = std::sin(angle);
  Tensor<2, 3> S = unit_symmetric_tensor<3>();
  S[0][0] = 1.03, S[1][1] = 0.98, S[0][1] = S[1][0] = 0.02;
  if (dim == 3)
    S[2][2] = 1.01, S[1][2] = S[2][1] = 0.015;
  const Tensor<2, 3> F = R * S * F_old;

  auto piola = [&](const Tensor<2, 3> &Fx, MaterialResponse &response) {
    auto                  point = model.create_point();
    point->set_stress(sigma_n);
    IncrementalKinematics kin;
    kin.reinit(Fx, F_old);
    MaterialIncrement inc;
    inc.strain_increment   = kin.strain_increment;
    inc.rotation_increment = kin.rotation_increment;
    point->update(inc, request_stress | request_tangent, response);
    return std::make_pair(first_piola_stress(kin, response.stress), kin);
  };

  MaterialResponse response;
  const auto [P, kin]        = piola(F, response);
  const Tensor<4, dim> A     = first_piola_tangent<dim>(kin, sigma_n, response);
  const double         h     = 1e-6;
  double               max_a = 0, max_err = 0;
  for (unsigned int k = 0; k < dim; ++k)
    for (unsigned int L = 0; L < dim; ++L)
      {
        Tensor<2, 3> Fp = F, Fm = F;
        Fp[k][L] += h;
        Fm[k][L] -= h;
        MaterialResponse r;
        const Tensor<2, 3> dP = (piola(Fp, r).first - piola(Fm, r).first) / (2 * h);
        for (unsigned int i = 0; i < dim; ++i)
          for (unsigned int J = 0; J < dim; ++J)
            {
              max_a   = std::max(max_a, std::abs(A[i][J][k][L]));
              max_err = std::max(max_err, std::abs(A[i][J][k][L] - dP[i][J]));
              if (k == 0 && L == 1)
                std::cout << "  dim " << dim << " dP" << i << J << "/dF01: analytic "
                          << A[i][J][k][L] << "  finite difference " << dP[i][J] << '\n';
            }
      }
  std::cout << "dim " << dim << ", rotation " << angle << " rad: max |A - A_fd| / max |A| = "
            << max_err / max_a << std::endl;
  return max_err / max_a;
}

int main()
{
  double worst = 0;
  for (const double angle : {0.0, 0.1, 0.7})
    worst = std::max({worst, check<2>(angle), check<3>(angle)});
  const bool ok = worst < 1e-6;
  std::cout << (ok ? "PASS" : "FAIL") << " worst relative error " << worst << " (tolerance 1e-6)"
            << std::endl;
  return ok ? 0 : 1;
}
