#pragma once

#include <anvil/material/elastic_law.h>
#include <anvil/material/laws.h>
#include <anvil/material/material_point.h>

#include <cmath>
#include <mutex>

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

    /**
     * What does not change during one update: the temperature and time step
     * parts of the overstress, evaluated once per update (the return map
     * evaluates the overstress at every iteration).
     */
    struct Rate
    {
      double eta_root = 0;     // η_T(T)^{1/n(T)}; 0: no overstress (off, or η_T ≤ 0)
      double inv_n = 1, m = 1; // 1/n(T), m(T)
      double inv_m = 1;        // 1/m(T)
      double strain_power = 0; // a/n(T): η(ε̄, T)^{1/n} = η_T^{1/n} (1 + ε̄/ε_η)^{a/n}
      double dt = 1;           // s
      bool   active() const { return eta_root > 0; }
    };
    Rate at(double T, double dt) const;

    struct Value
    {
      double stress = 0;         // the overstress η^{1/n} ε̄̇^{1/m}, MPa
      double derivative = 0;     // d/dΔε̄ at fixed T (incl. η's ε̄ dependence)
      double log_derivative = 0; // Δε̄ d/dΔε̄ = d/d ln Δε̄ (finite as Δε̄ → 0)
      double temperature_derivative = 0; // ∂/∂T at fixed Δε̄ (only from temperature_derivative())
    };
    /// Overstress at plastic strain @p eps after an increment @p dp over rate.dt.
    Value evaluate(const Rate &rate, double eps, double dp) const;
    /// ∂V/∂T at fixed Δε̄ of the overstress @p stress = evaluate(rate, eps, dp).stress at @p T.
    double temperature_derivative(const Rate &rate, double T, double eps, double dp,
                                  double stress) const;
    /// The increment Δε̄ at which η(@p eps, T)^{1/n} (Δε̄/Δt)^{1/m} equals
    /// @p overstress. With @p eps where η is smallest over the increment and
    /// @p overstress = q_trial − σᵥ(ε̄ₙ), it bounds the root of the return
    /// map from above when σᵥ is nondecreasing.
    double rate_bound(const Rate &rate, double eps, double overstress) const;
    double strain_exponent_value() const { return strain_exponent; }

  private:
    bool           enabled = false;
    TemperatureLaw eta, n, m;
    double         strain_reference = 1, strain_exponent = 0;
  };

  /**
   * The multiplicative rate factor of Johnson & Cook (1983):
   *
   *   σ_y = σ_h(ε̄, T) (1 + C ln(ε̄̇/ε̇₀))  for ε̄̇ > ε̇₀,  σ_h(ε̄, T) below,
   *
   * written as an overstress V = σ_h C ln(ε̄̇/ε̇₀) on the hardening law so
   * that the return map and its consistent tangent are those of eq. (18)
   * with this V (ε̄̇ = Δε̄/Δt over the step).
   */
  struct JohnsonCookRate
  {
    double C = 0, reference_rate = 1; // dimensionless, 1/s
    bool   active() const { return C > 0; }
    /// V, dV/dΔε̄ (with σ_h's slope) and Δε̄ dV/dΔε̄ at hardening value @p y.
    PerzynaLaw::Value evaluate(double stress, double slope, double dp, double dt) const
    {
      PerzynaLaw::Value v;
      const double      rate = dp / dt;
      if (!(rate > reference_rate))
        return v;
      const double L   = std::log(rate / reference_rate);
      v.stress         = stress * C * L;
      v.derivative     = slope * C * L + stress * C / dp;
      v.log_derivative = dp * v.derivative;
      return v;
    }
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
    /// Subsection Elasticity; Hardening (declare_hardening_parameters());
    /// Viscosity (PerzynaLaw). The registered models declare what they read.
    static void declare_elasticity_parameters(dealii::ParameterHandler &prm);

    /// Elasticity; Hardening if `plastic`; Viscosity if `viscous`.
    void parse_parameters(dealii::ParameterHandler &prm,
                          const Scene              &scene,
                          const std::string        &path) override;

    /// A J2Point, or with options.adiabatic a J2AdiabaticPoint (j2_point.h).
    std::unique_ptr<MaterialPoint> create_point(const PointOptions &options = {}) const override;
    PointBlock create_points(std::size_t n, const PointOptions &options = {}) const override;
    /// The hardening law's strength_limit(), then σᵥ(ε̄, T) > 0 (material/strength.cc).
    StrengthLoss strength_lost(double T, double eps) const override;
    /// Not for an elastic body, nor for σᵥ = σ₀ + h ε̄ with σ₀ > 0, h ≥ 0 and
    /// no softening (material/strength.cc).
    bool        may_lose_strength() const override;
    double      bulk_modulus_at(double T) const override { return elastic.bulk_modulus(T); }
    double      shear_modulus_at(double T) const override { return elastic.shear_modulus(T); }
    double      thermal_strain(double T, double dT) const override
    {
      return elastic.thermal_strain(T, dT);
    }
    double      bulk_modulus() const override { return elastic.bulk_modulus(); }
    double      shear_modulus() const override { return elastic.shear_modulus(); }
    double      density() const override { return elastic.density; }
    double      heat_capacity() const override { return elastic.heat_capacity; }
    std::string name() const override
    {
      return !plastic               ? "hypoelastic" :
             johnson_cook           ? "Johnson-Cook" :
             viscosity.active()     ? "Perzyna" :
                                      "J2";
    }

    ElasticLaw                          elastic;
    std::unique_ptr<const HardeningLaw> hardening; // set if plastic
    PerzynaLaw                          viscosity;
    bool plastic = true;  // false: thermo-hypoelastic only
    bool viscous = false; // true: Perzyna overstress (subsection Viscosity)
    bool johnson_cook = false;    // true: the Johnson-Cook model (rate below)
    JohnsonCookRate johnson_cook_rate; // active(): multiplicative rate factor, no Perzyna

    /**
     * What the points read at every update, found once from the parsed laws
     * (create_point(s)): the hardening law as inline numbers where it is
     * linear with linear or no softening.
     */
    struct Kernel
    {
      bool                     inline_yield = false; // yield below, else hardening->evaluate()
      HardeningLaw::LinearForm yield;
      bool                     linear = false; // hardening->is_linear()
      /// The inline law without softening of either parameter (θ = 1):
      /// σᵥ = σ₀ + h ε̄, no branch on the flags at every update.
      bool plain_yield = false;
      /// linear without viscosity or Johnson-Cook rate: the return map in
      /// closed form at every plastic update (one test, not three).
      bool closed_form = false;
      /// Constant moduli and expansion (ElasticLaw::constant()), a plain
      /// yield with h ≥ 0 in closed form: the isothermal update's own
      /// instance reads K, G, β here (the laws' products, the same bits)
      /// and has no branch on the laws.
      bool   simple = false;
      double K = 0, G = 0, beta = 0;
    };
    /// Valid once a point exists (create_point(s) prepares it).
    const Kernel &kernel() const { return kernel_cache; }

  private:
    void                                        prepare_kernel() const;
    mutable std::once_flag                      kernel_once;
    mutable Kernel                              kernel_cache;
    mutable std::once_flag                      strength_limit_once;
    mutable HardeningLaw::StrengthLimit         strength_limit_cache;
  };
} // namespace anvil
