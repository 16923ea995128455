#pragma once

#include <anvil/material/elastic_law.h>
#include <anvil/material/laws.h>
#include <anvil/material/material_point.h>

namespace anvil
{
  /**
   * Perzyna viscous overstress of eq. (14), (17), (18):
   *
   *   f̄ = σ̄ − σᵥ(ε̄, T) − η(ε̄, T)^{1/n(T)} (ε̄̇)^{1/m(T)} = 0,
   *   η(ε̄, T) = η_T(T) (1 + ε̄/ε_η)^a.
   *
   * η = 0 is rate-independent J2 (f = 0) exactly. Units: the overstress is in
   * MPa, ε̄̇ in 1/s, so η carries MPa^n s^{n/m}.
   */
  class PerzynaLaw
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm,
                                 const Scene              &scene,
                                 const std::string        &path,
                                 double                    reference_temperature);
    bool active() const { return enabled; }

    struct Value
    {
      double stress = 0;                 // the overstress η^{1/n} ε̄̇^{1/m}, MPa
      double derivative = 0;             // d/dΔε̄ at fixed T (incl. η's ε̄ dependence)
      double temperature_derivative = 0; // ∂/∂T at fixed Δε̄
    };
    /// Overstress at plastic strain @p eps after an increment @p dp over @p dt.
    Value evaluate(double eps, double dp, double dt, double T) const;

  private:
    bool           enabled = false;
    TemperatureLaw eta, n, m;
    double         strain_reference = 1, strain_exponent = 0;
  };

  /**
   * J2 (von Mises) thermo-elasto-viscoplasticity with isotropic hardening,
   * seed §1.3 and §2.3: hypoelastic trial state (eq. 9, 10, 19), radial return
   * to f = 0 (eq. 11, rate-independent) or to the generalized criterion
   * f̄ = 0 (eq. 18, Perzyna), consistent tangent, ∂σ/∂T, plastic work
   * (eq. 21), thermoelastic heating (eq. 22, sign from thermodynamics) and
   * the adiabatic temperature change of the Armero–Simo split.
   */
  class J2Model : public MaterialModel
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    /// @p path: the Material subsection's path, for error messages.
    void parse_parameters(dealii::ParameterHandler &prm, const Scene &scene, const std::string &path);

    std::unique_ptr<MaterialPoint> create_point() const override;
    double      bulk_modulus() const override { return elastic.bulk_modulus(); }
    double      shear_modulus() const override { return elastic.shear_modulus(); }
    double      density() const override { return elastic.density; }
    std::string name() const override
    {
      return !plastic ? "hypoelastic" : viscosity.active() ? "Perzyna" : "J2";
    }

    ElasticLaw   elastic;
    HardeningLaw hardening;
    PerzynaLaw   viscosity;
    bool         plastic = true; // false: thermo-hypoelastic only
  };
} // namespace anvil
