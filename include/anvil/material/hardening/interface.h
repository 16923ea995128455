#pragma once

#include <deal.II/base/parameter_handler.h>

#include <anvil/core/registry.h>
#include <anvil/material/softening/interface.h>

#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  class Scene;

  /**
   * The yield stress σᵥ(ε̄ᵖ, T) of isotropic hardening (seed eq. 15–16): its
   * value and derivatives in ε̄ᵖ and T. One file per law under
   * source/material/hardening/, registered by name with
   * ANVIL_REGISTER_HARDENING_LAW; `Hardening/Model` chooses one (a
   * Patterns::Selection of what is registered). A program registers its own
   * law the same way (contrib/steps/step-2).
   *
   * Every law owns the thermal softening θ(T) of `subsection Thermal
   * softening` and the list of `Softened parameters`: a law multiplies the
   * parameters it has under those names by θ (and differentiates θ for
   * ∂σᵥ/∂T), see softened().
   *
   * The entries of `subsection Hardening` are flat and shared: a law declares
   * the entries it reads in a static declare_parameters() (called with the
   * subsection entered). Entries several laws read (Initial yield stress,
   * Hardening modulus, ...) are declared with declare_common_entry() so that
   * every law declares them the same way.
   */
  class HardeningLaw
  {
  public:
    virtual ~HardeningLaw() = default;

    struct Value
    {
      double stress = 0, slope = 0, temperature_derivative = 0;
    };

    /// The law's own entries (none by default).
    static void declare_parameters(dealii::ParameterHandler &) {}

    /**
     * Reads and checks the law's own entries, subsection Hardening entered;
     * @p path (".../Hardening") names it in errors (Scene::fail). softened()
     * and softening() are already set.
     */
    virtual void parse_parameters(dealii::ParameterHandler &prm,
                                  const Scene              &scene,
                                  const std::string        &path) = 0;

    /// σᵥ, ∂σᵥ/∂ε̄ and ∂σᵥ/∂T at (ε̄, T): runs several times per material
    /// point update (no allocation, no string work).
    virtual Value evaluate(double eps, double T) const = 0;

    /// σᵥ is linear in ε̄: σᵥ(ε̄ₙ + Δε̄) = σᵥ(ε̄ₙ) + slope Δε̄, so the
    /// rate-independent return has a closed form.
    virtual bool is_linear() const { return false; }

    /**
     * The linear law σᵥ = θ_σ(T) σ₀ + θ_h(T) h ε̄ (seed eq. 16) with θ = 1 or
     * θ = 1 − ω (T − T_ref) (eq. 35) as plain numbers, so that a material point
     * evaluates it inline: through evaluate() each evaluation is a virtual call
     * and two more for θ, several times per update. evaluate() below is the
     * law's own arithmetic, operation for operation (the same bits).
     */
    struct LinearForm
    {
      double sigma0 = 0, h = 0;
      bool   soft_sigma0 = false, soft_h = false;
      bool   theta_linear = false; // θ = 1 − ω (T − T_ref); else θ = 1
      double omega = 0, T_ref = 0;

      Value evaluate(const double eps, const double T) const
      {
        const double theta = theta_linear ? 1 - omega * (T - T_ref) : 1.;
        const double dtheta = theta_linear ? -omega : 0.;
        return linear_value(sigma0, h, soft_sigma0, soft_h, theta, dtheta, eps);
      }
      bool is_nondecreasing(const double T) const
      {
        return scale(soft_h, theta_linear ? 1 - omega * (T - T_ref) : 1.) * h >= 0;
      }
    };
    /// The law as a LinearForm, if it is one (false by default).
    virtual bool linear_form(LinearForm &) const { return false; }

    /// σᵥ(·, T) is nondecreasing in ε̄ ≥ 0 at temperature @p T: then σᵥ stays
    /// positive over a plastic increment once it is positive at its start.
    /// (false is always safe: the return map then checks its bracket.)
    virtual bool is_nondecreasing(double T) const = 0;

    double initial_yield_stress(double T) const { return evaluate(0, T).stress; }

    /// Where the yield stress vanishes as the temperature rises: σᵥ(0, T) has
    /// no strength for T >= temperature (+inf: never), because of the entry
    /// at `location` ("file:line: '<path>'"), by `formula`.
    struct StrengthLimit
    {
      double      temperature = std::numeric_limits<double>::infinity();
      std::string location, formula;
    };
    /**
     * The built-in laws: the softening's vanishing temperature when θ
     * multiplies the yield stress at zero plastic strain (the initial yield
     * stress or the strength coefficient is softened), +inf otherwise.
     * A law with a temperature dependence of its own overrides it.
     */
    virtual StrengthLimit strength_limit() const;

    /// "file:line: '<path>/Hardening'": where the scene sets the law, for errors.
    std::string location;
    const ThermalSoftening &softening() const { return *thermal; }

    /// Declares one of the entries several laws share ("Initial yield stress",
    /// "Hardening modulus", "Saturation stress", "Saturation exponent",
    /// "Strength coefficient", "Reference strain", "Hardening exponent",
    /// "Table"), always with the same default, pattern and help.
    static void declare_common_entry(dealii::ParameterHandler &prm, const std::string &entry);

  protected:
    /// Whether `Softened parameters` lists @p parameter ("initial yield
    /// stress", "hardening modulus", "saturation stress", "strength
    /// coefficient") or "all". Call from parse_parameters().
    bool softened(const std::string &parameter) const;

    /// θ(T) on a parameter that is softened, 1 on one that is not, and the T-derivatives.
    static double scale(const bool is_softened, const double theta) { return is_softened ? theta : 1.; }
    static double scale_derivative(const bool is_softened, const double dtheta)
    {
      return is_softened ? dtheta : 0.;
    }

    /// σᵥ = θ_σ σ₀ + θ_h h ε̄ (eq. 16; θ_σ, θ_h = θ(T) where softened, eq. 35),
    /// its slope and ∂/∂T from θ and dθ/dT: the linear law, and its LinearForm.
    static Value linear_value(const double sigma0, const double h, const bool soft_sigma0,
                              const bool soft_h, const double theta, const double dtheta,
                              const double eps)
    {
      Value v;
      v.stress                 = scale(soft_sigma0, theta) * sigma0 + scale(soft_h, theta) * h * eps;
      v.slope                  = scale(soft_h, theta) * h;
      v.temperature_derivative = scale_derivative(soft_sigma0, dtheta) * sigma0 +
                                 scale_derivative(soft_h, dtheta) * h * eps;
      return v;
    }

    std::unique_ptr<ThermalSoftening> thermal;

    /// The thermal softening's limit if @p yield_stress_softened, else none.
    StrengthLimit softening_limit(bool yield_stress_softened) const;

  private:
    std::vector<std::string> softened_parameters;

    friend std::unique_ptr<HardeningLaw> create_hardening_law(dealii::ParameterHandler &,
                                                              const Scene &,
                                                              const std::string &);
  };

  using HardeningLawRegistry = Registry<HardeningLaw>;

  /// `subsection Hardening` (in the current subsection): Model from the
  /// registry, Softened parameters, Thermal softening, every law's entries.
  void declare_hardening_parameters(dealii::ParameterHandler &prm);

  /// The law `Hardening/Model` names, with its softening, parsed and checked;
  /// @p path is the enclosing subsection's path (e.g. "Bodies/bar/Material").
  std::unique_ptr<HardeningLaw> create_hardening_law(dealii::ParameterHandler &prm,
                                                     const Scene              &scene,
                                                     const std::string        &path);
} // namespace anvil

/**
 * Registers hardening law @p classname (default constructible, derived from
 * anvil::HardeningLaw, with a static declare_parameters(ParameterHandler &)
 * for its own entries) under @p name with @p documentation (one sentence with
 * its formula and the entries it reads; it becomes part of the help of
 * `Hardening/Model`). At namespace scope of one .cc file, in the library or
 * in a program linked against it.
 */
#define ANVIL_REGISTER_HARDENING_LAW(classname, name, documentation)                              \
  namespace                                                                                      \
  {                                                                                              \
    const bool ANVIL_REGISTRY_UNIQUE(anvil_hardening_law_) =                                     \
      ::anvil::HardeningLawRegistry::instance().add(                                             \
        name, documentation,                                                                     \
        []() -> std::unique_ptr<::anvil::HardeningLaw> { return std::make_unique<classname>(); }, \
        [](dealii::ParameterHandler &prm) { classname::declare_parameters(prm); });              \
  }
