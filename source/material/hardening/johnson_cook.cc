#include <anvil/core/scene.h>
#include <anvil/material/hardening/interface.h>

#include <algorithm>
#include <cmath>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /**
     * σᵥ = A + B ε̄ⁿ, the strain part of Johnson & Cook (1983) (Ludwik's
     * law). With n < 1 the slope B n ε̄ⁿ⁻¹ is infinite at ε̄ = 0; it is
     * reported at ε̄ = 1e-12 there, where it only starts the return map
     * (the root is then at ε̄ > 0, where the slope is exact).
     */
    class JohnsonCookHardening : public HardeningLaw
    {
    public:
      static void declare_parameters(ParameterHandler &prm)
      {
        declare_common_entry(prm, "Initial yield stress");
        declare_common_entry(prm, "Strength coefficient");
        declare_common_entry(prm, "Hardening exponent");
      }

      void parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path) override
      {
        A      = prm.get_double("Initial yield stress");
        B      = prm.get_double("Strength coefficient");
        n      = prm.get_double("Hardening exponent");
        soft_A = softened("initial yield stress");
        soft_B = softened("strength coefficient");
        if (!(A > 0))
          scene.fail(path + "/Initial yield stress",
                     "= " + std::to_string(A) + ": expected A > 0 MPa for johnson-cook");
        if (!(n > 0))
          scene.fail(path + "/Hardening exponent",
                     "= " + std::to_string(n) + ": expected n > 0 for johnson-cook");
      }

      Value evaluate(const double eps, const double T) const override
      {
        const double theta = thermal->factor(T), dtheta = thermal->derivative(T);
        const double e     = std::max(eps, 0.);
        const double power = std::pow(e, n);
        const double slope = n * std::pow(std::max(e, 1e-12), n - 1);
        Value        v;
        v.stress = scale(soft_A, theta) * A + scale(soft_B, theta) * B * power;
        v.slope  = scale(soft_B, theta) * B * slope;
        v.temperature_derivative =
          scale_derivative(soft_A, dtheta) * A + scale_derivative(soft_B, dtheta) * B * power;
        return v;
      }

      StrengthLimit strength_limit() const override { return softening_limit(soft_A); }

      bool is_nondecreasing(const double T) const override
      {
        return scale(soft_B, thermal->factor(T)) * B >= 0;
      }

    private:
      double A = 0, B = 0, n = 1;
      bool   soft_A = true, soft_B = true;
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_HARDENING_LAW(anvil::JohnsonCookHardening, "johnson-cook",
                             "A + B eps^n, the strain part of Johnson-Cook (Initial yield "
                             "stress A, Strength coefficient B, Hardening exponent n; with "
                             "Thermal softening johnson-cook for its temperature part)")
