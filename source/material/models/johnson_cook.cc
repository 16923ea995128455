#include <anvil/core/scene.h>
#include <anvil/material/j2_plasticity.h>
#include <anvil/material/number_format.h>

#include <algorithm>
#include <cmath>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /**
     * The flow stress of Johnson & Cook (1983) at ε̄ and T, without the rate
     * factor: σ_h = (A + B ε̄ⁿ)(1 − T*ᵐ), T* = (T − T_tr)/(T_m − T_tr)
     * clamped to [0, 1]. As with the hardening law johnson-cook, the slope
     * at ε̄ = 0 (infinite for n < 1) is reported at ε̄ = 1e-12.
     */
    class JohnsonCookFlow : public HardeningLaw
    {
    public:
      JohnsonCookFlow() { thermal = ThermalSofteningRegistry::instance().create("none"); }
      void parse_parameters(ParameterHandler &, const Scene &, const std::string &) override {}

      Value evaluate(const double eps, const double T) const override
      {
        const double s = (T - T_transition) / (T_melt - T_transition);
        double       theta = 1, dtheta = 0;
        if (s >= 1)
          theta = 0;
        else if (s > 0)
          {
            theta  = 1 - std::pow(s, m);
            dtheta = -m * std::pow(s, m - 1) / (T_melt - T_transition);
          }
        const double e    = std::max(eps, 0.);
        const double base = A + B * std::pow(e, n);
        Value        v;
        v.stress                 = base * theta;
        v.slope                  = B * n * std::pow(std::max(e, 1e-12), n - 1) * theta;
        v.temperature_derivative = base * dtheta;
        return v;
      }
      bool is_nondecreasing(double) const override { return true; } // B >= 0, θ >= 0
      // θ = 0 from T* = 1 on: no strength at and above the melting temperature.
      StrengthLimit strength_limit() const override
      {
        return {T_melt, melt_location, "T_m = " + short_number(T_melt)};
      }

      double      A = 0, B = 0, n = 1, m = 1, T_melt = 1356, T_transition = 293;
      std::string melt_location;
    };

    /// Johnson-Cook thermo-viscoplasticity: J2 with σ_y = σ_h(ε̄, T)(1 + C ln(ε̄̇/ε̇₀)).
    class JohnsonCook : public J2Model
    {
    public:
      JohnsonCook() { johnson_cook = true; }

      static void declare_parameters(ParameterHandler &prm)
      {
        declare_elasticity_parameters(prm);
        prm.enter_subsection("Johnson-Cook");
        prm.declare_entry("A", "90", Patterns::Double(),
                          "Yield stress at zero plastic strain, reference rate and the transition "
                          "temperature, MPa (> 0).");
        prm.declare_entry("B", "292", Patterns::Double(), "Strain hardening coefficient, MPa (>= 0).");
        prm.declare_entry("n", "0.31", Patterns::Double(), "Strain hardening exponent (> 0).");
        prm.declare_entry("C", "0.025", Patterns::Double(),
                          "Strain-rate coefficient (>= 0; 0: rate independent).");
        prm.declare_entry("Reference strain rate", "1", Patterns::Double(),
                          "eps_dot_0 in 1/s (> 0); below it the rate factor is 1.");
        prm.declare_entry("m", "1.09", Patterns::Double(), "Thermal softening exponent (> 0).");
        prm.declare_entry("Melting temperature", "1356", Patterns::Double(), "T_m in K.");
        prm.declare_entry("Transition temperature", "293", Patterns::Double(),
                          "T_tr in K (< T_m): no softening below it.");
        prm.leave_subsection();
      }

      void parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path) override
      {
        plastic = true;
        prm.enter_subsection("Elasticity");
        elastic.parse_parameters(prm, scene, path + "/Elasticity");
        prm.leave_subsection();
        const std::string p    = path + "/Johnson-Cook";
        auto              flow = std::make_unique<JohnsonCookFlow>();
        prm.enter_subsection("Johnson-Cook");
        flow->A                   = prm.get_double("A");
        flow->B                   = prm.get_double("B");
        flow->n                   = prm.get_double("n");
        johnson_cook_rate.C       = prm.get_double("C");
        johnson_cook_rate.reference_rate = prm.get_double("Reference strain rate");
        flow->m                   = prm.get_double("m");
        flow->T_melt              = prm.get_double("Melting temperature");
        flow->T_transition        = prm.get_double("Transition temperature");
        prm.leave_subsection();
        const auto require = [&](const bool ok, const std::string &entry, const double value,
                                 const std::string &expected) {
          if (!ok)
            scene.fail(p + "/" + entry, "= " + short_number(value) + ": expected " + expected);
        };
        require(flow->A > 0, "A", flow->A, "A > 0 MPa");
        require(flow->B >= 0, "B", flow->B, "B >= 0 MPa");
        require(flow->n > 0, "n", flow->n, "n > 0");
        require(johnson_cook_rate.C >= 0, "C", johnson_cook_rate.C, "C >= 0");
        require(johnson_cook_rate.reference_rate > 0, "Reference strain rate",
                johnson_cook_rate.reference_rate, "a rate > 0 1/s");
        require(flow->m > 0, "m", flow->m, "m > 0");
        require(flow->T_transition > 0, "Transition temperature", flow->T_transition,
                "an absolute temperature > 0 K");
        require(flow->T_melt > flow->T_transition, "Melting temperature", flow->T_melt,
                "T_m > Transition temperature (" + short_number(flow->T_transition) + " K)");
        flow->location      = scene.where(p + "/A") + ": '" + p + "'";
        flow->melt_location = scene.where(p + "/Melting temperature") + ": '" + p + "/Melting temperature'";
        hardening      = std::move(flow);
      }
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_MATERIAL_MODEL(anvil::JohnsonCook, "Johnson-Cook",
                              "von Mises thermo-viscoplasticity with the Johnson-Cook flow stress "
                              "(A + B eps^n)(1 + C ln(eps_dot/eps_dot_0))(1 - T*^m), T* = (T - "
                              "T_tr)/(T_m - T_tr) in [0, 1], the rate factor multiplicative (1 "
                              "below eps_dot_0): Elasticity, Johnson-Cook")
