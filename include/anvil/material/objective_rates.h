#pragma once

#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <string>

namespace anvil
{
  /**
   * The objective stress rate the incremental update integrates
   * (Mechanics/Objective rate, doc/mechanics.md "Objective rates"):
   *
   *  - jaumann: spin W = skew L (seed eq. 9); in simple shear of a
   *    hypoelastic body σ_xy = G sin γ oscillates past γ = π/2;
   *  - green_naghdi: spin Ṙ Rᵀ of the polar decomposition F = R U
   *    (Dienes 1979): monotone shear stress, but σ_xx grows without bound;
   *  - logarithmic: the log spin of Xiao, Bruhns & Meyers (1997), the only
   *    rate for which hypoelasticity integrates to a hyperelastic (Hencky)
   *    model: σ = λ tr(ln V) I + 2G ln V exactly for isochoric motions.
   */
  enum class ObjectiveRate
  {
    jaumann,
    green_naghdi,
    logarithmic
  };

  /// The scene's spelling: "Jaumann", "Green-Naghdi" or "logarithmic".
  ObjectiveRate      objective_rate_from_string(const std::string &name);
  std::string        objective_rate_name(ObjectiveRate rate);
  /// The Patterns::Selection text of the three spellings.
  inline const char *objective_rate_selection()
  {
    return "Jaumann|Green-Naghdi|logarithmic";
  }

  /// The rotation R of the polar decomposition F = R U (det F > 0).
  dealii::Tensor<2, 3> polar_rotation(const dealii::Tensor<2, 3> &F);

  /**
   * The log spin times the step, Ω^log Δt, at the mid-point configuration
   * F_½ with the increment gradient ΔL (Xiao, Bruhns & Meyers 1997, eq. 38):
   *
   *   Ω^log = W + Σ_{σ≠τ} f(b_σ/b_τ) B_σ D B_τ,  f(x) = (1+x)/(1−x) + 2/ln x,
   *
   * b_σ, B_σ the eigenvalues and eigenprojections of B = F_½ F_½ᵀ,
   * W = skew ΔL, D = sym ΔL.
   */
  dealii::Tensor<2, 3> logarithmic_spin_increment(const dealii::Tensor<2, 3> &F_half,
                                                  const dealii::Tensor<2, 3> &dL);
} // namespace anvil
