#pragma once

#include <deal.II/base/parameter_handler.h>

#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  class Scene;

  /**
   * A scalar property as a function of temperature: constant, linear
   * p(T) = p₀ (1 − ω (T − T_ref)) (the form of eq. 35), or a table of (T, p)
   * pairs interpolated linearly and held constant outside.
   *
   *   set Model          = constant | linear | table
   *   set Value          = p₀ (units of the property)
   *   set Softening      = ω, 1/K (linear)
   *   set Table          = T1 : p1, T2 : p2, ... (table; T increasing, K)
   */
  class TemperatureLaw
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm,
                                   const std::string        &default_value,
                                   const std::string        &unit_help);
    void        parse_parameters(dealii::ParameterHandler &prm,
                                 const Scene              &scene,
                                 const std::string        &path,
                                 double                    reference_temperature);

    /// p(T) and dp/dT. The constant case is inline: these run several times
    /// per material point update.
    double value(double T) const { return kind == Kind::constant ? p0 : general_value(T); }
    double derivative(double T) const { return kind == Kind::constant ? 0. : general_derivative(T); }
    bool   is_constant() const { return kind == Kind::constant; }
    double reference() const { return p0; }

  private:
    double general_value(double T) const;
    double general_derivative(double T) const;

    enum class Kind
    {
      constant,
      linear,
      table
    } kind = Kind::constant;
    double              p0 = 0, omega = 0, T_ref = 293;
    std::vector<double> T_table, p_table;
  };

  /**
   * Thermal softening θ(T) ≥ 0 multiplying the yield parameters that the
   * hardening law says are softened (seed eq. 35 and its generalisations):
   *   none:         θ = 1
   *   linear:       θ = 1 − ω (T − T_ref)                    (eq. 35)
   *   johnson-cook: θ = 1 − T*^m, T* = (T − T_ref)/(T_melt − T_ref), clamped to [0, 1]
   *   table:        θ from (T, θ) pairs
   */
  class ThermalSoftening
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm,
                                 const Scene              &scene,
                                 const std::string        &path);
    double factor(double T) const;
    double derivative(double T) const;
    double reference_temperature() const { return T_ref; }

  private:
    std::string model = "none";
    /// `model` as an enum, set at parse time: factor() and derivative() run
    /// several times per material point update.
    enum class Kind
    {
      none,
      linear,
      johnson_cook,
      table
    } kind = Kind::none;
    double              omega = 0, T_ref = 293, T_melt = 1800, exponent = 1;
    std::vector<double> T_table, f_table;
  };

  /**
   * The yield stress σᵥ(ε̄ᵖ, T) of isotropic hardening (seed eq. 15–16) as a
   * small strategy: its value and derivatives in ε̄ᵖ and T. Parameters named in
   * "Softened parameters" are multiplied by the thermal softening factor θ(T).
   *
   *   linear:     σ₀ + h ε̄
   *   swift:      K (ε₀ + ε̄)ⁿ                                (power law)
   *   voce:       σ₀ + (σ∞ − σ₀)(1 − e^{−δ ε̄})
   *   saturation: σ₀ + h ε̄ + (σ∞ − σ₀)(1 − e^{−δ ε̄})          (Simo & Miehe 1992)
   *   table:      (ε̄, σ) pairs, linear in between, extrapolated with the last slope
   */
  class HardeningLaw
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm,
                                 const Scene              &scene,
                                 const std::string        &path);

    struct Value
    {
      double stress = 0, slope = 0, temperature_derivative = 0;
    };
    /// σᵥ, ∂σᵥ/∂ε̄ and ∂σᵥ/∂T at (ε̄, T).
    Value  evaluate(double eps, double T) const;
    double initial_yield_stress(double T) const { return evaluate(0, T).stress; }
    /// σᵥ is linear in ε̄ (the linear model): σᵥ(ε̄ₙ + Δε̄) = σᵥ(ε̄ₙ) + slope Δε̄,
    /// so the rate-independent return has a closed form.
    bool is_linear() const { return kind == Kind::linear; }
    /// σᵥ(·, T) is nondecreasing in ε̄ ≥ 0 at temperature @p T: then σᵥ stays
    /// positive over a plastic increment once it is positive at its start.
    bool is_nondecreasing(double T) const;
    const ThermalSoftening &softening() const { return thermal; }

  private:
    std::string model = "linear";
    /// `model` as an enum, set at parse time (evaluate() is on the hot path).
    enum class Kind
    {
      linear,
      swift,
      voce,
      saturation,
      table
    } kind = Kind::linear;
    double              sigma0 = 0, h = 0, sigma_inf = 0, delta = 0, K = 0, eps0 = 0, n = 1;
    bool                soft_sigma0 = true, soft_h = true, soft_sigma_inf = true, soft_K = true;
    std::vector<double> eps_table, sigma_table;
    bool                table_nondecreasing = true;
    ThermalSoftening    thermal;
  };
} // namespace anvil
