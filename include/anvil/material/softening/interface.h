#pragma once

#include <deal.II/base/parameter_handler.h>

#include <anvil/core/registry.h>

#include <limits>
#include <memory>
#include <string>

namespace anvil
{
  class Scene;

  /**
   * Thermal softening θ(T) ≥ 0: the factor on the yield parameters that a
   * hardening law softens (seed eq. 35 and its generalisations). One file per
   * law under source/material/softening/, registered with
   * ANVIL_REGISTER_THERMAL_SOFTENING; `Hardening/Thermal softening/Model`
   * chooses one by name.
   *
   * The entries of `subsection Thermal softening` are flat: `Model` and
   * `Reference temperature` (every law) are declared here, each law declares
   * the entries it reads (a static declare_parameters(), called with the
   * subsection entered; entries of the same name must be declared identically).
   */
  class ThermalSoftening
  {
  public:
    virtual ~ThermalSoftening() = default;

    /// The law's own entries (none by default).
    static void declare_parameters(dealii::ParameterHandler &) {}
    /// Reads the law's own entries, subsection entered; @p path names it in errors.
    virtual void parse_parameters(dealii::ParameterHandler &prm,
                                  const Scene              &scene,
                                  const std::string        &path);

    /// θ(T) and dθ/dT (several calls per material point update: keep them cheap).
    virtual double factor(double T) const     = 0;
    virtual double derivative(double T) const = 0;

    /// T_ref in K: where the yield parameters are given (θ = 1 for the built-in laws).
    double reference_temperature() const { return T_ref; }

    /// θ = 1 (@p constant) or θ = 1 − @p omega (T − T_ref) exactly as factor()
    /// computes it: HardeningLaw::LinearForm (false: neither).
    virtual bool linear_form(bool & /*constant*/, double & /*omega*/) const { return false; }

    /**
     * The lowest temperature above T_ref where θ reaches 0, K (+inf if it
     * never does): T_ref + 1/ω (linear, ω > 0), T_melt (johnson-cook), the
     * first crossing of a table. A softened yield stress has no strength
     * there: a converged state that reaches it ends the run (issue 17).
     */
    virtual double vanishing_temperature() const { return std::numeric_limits<double>::infinity(); }
    /// How vanishing_temperature() follows from the entries, for messages
    /// (e.g. "T_ref + 1/omega = 293 + 1/0.002").
    virtual std::string vanishing_formula() const { return ""; }
    /// "file:line: '<path>/Thermal softening/<entry>'": the entry that sets
    /// vanishing_temperature() (vanishing_entry()), for messages.
    std::string vanishing_location;

  protected:
    /// The entry of `subsection Thermal softening` that sets vanishing_temperature().
    virtual std::string vanishing_entry() const { return "Model"; }

    double T_ref = 293;

    friend std::unique_ptr<ThermalSoftening> create_thermal_softening(dealii::ParameterHandler &,
                                                                      const Scene &,
                                                                      const std::string &);
  };

  using ThermalSofteningRegistry = Registry<ThermalSoftening>;

  /// `subsection Thermal softening` (in the current subsection): Model from
  /// the registry, Reference temperature, every registered law's entries.
  void declare_thermal_softening_parameters(dealii::ParameterHandler &prm);

  /// The law `Thermal softening/Model` names, parsed; @p path is the path of
  /// the enclosing subsection (e.g. "Bodies/bar/Material/Hardening").
  std::unique_ptr<ThermalSoftening> create_thermal_softening(dealii::ParameterHandler &prm,
                                                             const Scene              &scene,
                                                             const std::string        &path);
} // namespace anvil

/**
 * Registers thermal-softening law @p classname (default constructible, with a
 * static declare_parameters(ParameterHandler &) for its own entries) under
 * @p name with @p documentation (one sentence with its formula; it becomes
 * the help of `Thermal softening/Model`). At namespace scope of one .cc file.
 */
#define ANVIL_REGISTER_THERMAL_SOFTENING(classname, name, documentation)                         \
  namespace                                                                                      \
  {                                                                                              \
    const bool ANVIL_REGISTRY_UNIQUE(anvil_thermal_softening_) =                                 \
      ::anvil::ThermalSofteningRegistry::instance().add(                                         \
        name, documentation,                                                                     \
        []() -> std::unique_ptr<::anvil::ThermalSoftening> {                                     \
          return std::make_unique<classname>();                                                  \
        },                                                                                       \
        [](dealii::ParameterHandler &prm) { classname::declare_parameters(prm); });              \
  }
