#pragma once

#include <anvil/material/material_point.h>

namespace anvil
{
  /**
   * Isotropic hypoelasticity, eq. (9)–(10) of the seed without plastic or
   * thermal rate: σ̊ = H : D with H = K δ⊗δ + 2G (I − ⅓ δ⊗δ). Integrated
   * incrementally objectively: σ_{n+1} = ΔR σ_n ΔRᵀ + H : Δε.
   */
  class HypoelasticModel : public MaterialModel
  {
  public:
    struct Parameters
    {
      double bulk_modulus  = 0; // MPa
      double shear_modulus = 0; // MPa
      double density       = 0; // t/mm³
    };

    /// Declares Young's modulus / Bulk modulus, Poisson's ratio, Density.
    static void declare_parameters(dealii::ParameterHandler &prm);
    /// @p path is e.g. "Bodies/body/Material/Hypoelastic" (for error messages).
    static Parameters parse_parameters(dealii::ParameterHandler &prm,
                                       const Scene              &scene,
                                       const std::string        &path);

    explicit HypoelasticModel(const Parameters &parameters);

    std::unique_ptr<MaterialPoint> create_point() const override;
    double      bulk_modulus() const override { return parameters.bulk_modulus; }
    double      shear_modulus() const override { return parameters.shear_modulus; }
    double      density() const override { return parameters.density; }
    std::string name() const override { return "hypoelastic"; }

    /// H = K δ⊗δ + 2G(I − ⅓δ⊗δ), eq. (10).
    const dealii::SymmetricTensor<4, 3> &elasticity() const { return hooke; }

  private:
    Parameters                    parameters;
    dealii::SymmetricTensor<4, 3> hooke;
  };
} // namespace anvil
