// The log spin of Xiao, Bruhns & Meyers (1997): with it, hypoelasticity
// integrates to Hencky's hyperelastic model (doc/mechanics.md, "Objective rates").
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/material/objective_rates.h>

#include <cmath>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// f(x) = (1+x)/(1−x) + 2/ln x with u = ln x: f = 2/u − coth(u/2), odd in
    /// u and → 0 as u → 0; the series avoids the cancellation of two ~2/u terms.
    double log_spin_coefficient(const double u)
    {
      if (std::abs(u) < 0.05)
        return -u / 6 + u * u * u / 360 - std::pow(u, 5) / 15120;
      return 2 / u - 1 / std::tanh(0.5 * u);
    }
  } // namespace

  Tensor<2, 3> logarithmic_spin_increment(const Tensor<2, 3> &F_half, const Tensor<2, 3> &dL)
  {
    const SymmetricTensor<2, 3> B   = symmetrize(F_half * transpose(F_half));
    const auto                  eig = eigenvectors(B, SymmetricTensorEigenvectorMethod::jacobi);
    const Tensor<2, 3>          D   = 0.5 * (dL + transpose(dL));
    Tensor<2, 3>                spin = 0.5 * (dL - transpose(dL));
    // Σ_{σ≠τ} f(b_σ/b_τ) B_σ D B_τ = Σ f (n_σ·D n_τ) n_σ ⊗ n_τ. Coincident
    // eigenvalues contribute nothing (f(1) = 0), so their arbitrary
    // eigenvectors do not matter.
    for (unsigned int s = 0; s < 3; ++s)
      for (unsigned int t = 0; t < 3; ++t)
        if (s != t)
          {
            const double u = std::log(eig[s].first / eig[t].first);
            const double c = log_spin_coefficient(u) * (eig[s].second * (D * eig[t].second));
            spin += c * outer_product(eig[s].second, eig[t].second);
          }
    return spin;
  }
} // namespace anvil
