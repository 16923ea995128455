#pragma once

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/symmetric_tensor.h>

#include <anvil/material/laws.h>

namespace anvil
{
  class Scene;

  /**
   * Isotropic thermo-elasticity of a material point (seed eq. 9, 10, 19):
   * K(T), G(T), linear thermal expansion β and the thermal and Taylor–Quinney
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
    double bulk_modulus() const { return K0; }
    double shear_modulus() const { return G0; }

    /// H(T) = K δ⊗δ + 2G (I − ⅓ δ⊗δ), eq. (10).
    dealii::SymmetricTensor<4, 3> elasticity(double T) const;

    double density            = 7.8e-9; // t/mm³
    double heat_capacity      = 4.6e8;  // mm²/(s² K)
    double thermal_expansion  = 0;      // 1/K (β, eq. 19)
    double reference_temperature = 293; // K: where the moduli are K₀, G₀
    double taylor_quinney     = 0.9;    // χ
    /// c is at constant volume (the seed's c_v, eq. 8; Ẇthel from all of
    /// tr D) rather than at constant stress (handbook c_p; Ẇthel from the
    /// stress-producing tr(D − βṪ I)). doc/thermodynamics.md.
    bool capacity_at_constant_volume = false;

  private:
    double         K0 = 0, G0 = 0;
    TemperatureLaw factor;
  };
} // namespace anvil
