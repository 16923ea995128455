#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/material/laws.h>

namespace anvil
{
  class Scene;

  /**
   * Isotropic thermo-elasticity of a material point (seed eq. 9, 10, 19):
   * K(T), G(T), linear thermal expansion β(T) and the thermal and Taylor–Quinney
   * data a material point needs for its dissipation and adiabatic heating.
   *
   * K(T) = K₀ g(T), G(T) = G₀ g(T) with g a TemperatureLaw (constant by
   * default), so ν does not change with temperature.
   */
  class ElasticLaw
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    /// @p path is the subsection path (for error messages).
    void parse_parameters(dealii::ParameterHandler &prm, const Scene &scene, const std::string &path);

    double bulk_modulus(double T) const { return K0 * factor.value(T); }
    double shear_modulus(double T) const { return G0 * factor.value(T); }
    /// d(K, G)/dT divided by (K, G).
    double relative_modulus_derivative(double T) const
    {
      return factor.derivative(T) / factor.value(T);
    }
    /// g(T) and f(T) constant: K(T) = K₀ g, G(T) = G₀ g, β(T) = β₀ f everywhere.
    bool constant() const { return factor.is_constant() && beta_factor.is_constant(); }
    double bulk_modulus() const { return K0; }
    double shear_modulus() const { return G0; }

    /// H(T) = K δ⊗δ + 2G (I − ⅓ δ⊗δ), eq. (10).
    dealii::SymmetricTensor<4, 3> elasticity(double T) const;

    /// β(T) = β₀ f(T), eq. (19), and the thermal strain over a step from
    /// T − ΔT to T by the trapezoidal rule, ½(β(T − ΔT) + β(T)) ΔT (exact for
    /// constant and linear β), with its derivative in T at fixed Tₙ = T − ΔT.
    double thermal_expansion(double T) const { return beta0 * beta_factor.value(T); }
    /// dβ/dT.
    double thermal_expansion_derivative(double T) const { return beta0 * beta_factor.derivative(T); }
    double thermal_strain(double T, double dT) const
    {
      if (beta_factor.is_constant())
        return beta0 * beta_factor.value(T) * dT;
      return 0.5 * (thermal_expansion(T - dT) + thermal_expansion(T)) * dT;
    }
    double thermal_strain_derivative(double T, double dT) const
    {
      if (beta_factor.is_constant())
        return beta0 * beta_factor.value(T);
      return 0.5 * (thermal_expansion(T - dT) + thermal_expansion(T)) +
             0.5 * beta0 * beta_factor.derivative(T) * dT;
    }

    double density            = 7.8e-9; // t/mm³
    double heat_capacity      = 4.6e8;  // mm²/(s² K)
    double reference_temperature = 293; // K: where the moduli are K₀, G₀
    double taylor_quinney     = 0.9;    // χ
    /// c is at constant volume (the seed's c_v, eq. 8; Ẇthel from all of
    /// tr D) rather than at constant stress (handbook c_p; Ẇthel from the
    /// stress-producing tr(D − βṪ I)). doc/thermodynamics.md.
    bool capacity_at_constant_volume = false;

  private:
    double         K0 = 0, G0 = 0, beta0 = 0;
    TemperatureLaw factor, beta_factor;
  };
} // namespace anvil
