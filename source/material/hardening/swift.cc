#include <anvil/core/scene.h>
#include <anvil/material/hardening/interface.h>

#include <cmath>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// σᵥ = K (ε₀ + ε̄)ⁿ, the power law of Swift (1952).
    class SwiftHardening : public HardeningLaw
    {
    public:
      static void declare_parameters(ParameterHandler &prm)
      {
        declare_common_entry(prm, "Strength coefficient");
        declare_common_entry(prm, "Reference strain");
        declare_common_entry(prm, "Hardening exponent");
      }

      void parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path) override
      {
        K      = prm.get_double("Strength coefficient");
        eps0   = prm.get_double("Reference strain");
        n      = prm.get_double("Hardening exponent");
        soft_K = softened("strength coefficient");
        if (!(K > 0 && eps0 > 0))
          scene.fail(path + "/Strength coefficient", "and 'Reference strain' must be > 0 for swift");
      }

      Value evaluate(const double eps, const double T) const override
      {
        const double theta = thermal->factor(T), dtheta = thermal->derivative(T);
        const double base  = std::pow(eps0 + eps, n);
        Value        v;
        v.stress                 = scale(soft_K, theta) * K * base;
        v.slope                  = scale(soft_K, theta) * K * n * base / (eps0 + eps);
        v.temperature_derivative = scale_derivative(soft_K, dtheta) * K * base;
        return v;
      }

      StrengthLimit strength_limit() const override { return softening_limit(soft_K); }

      // Slope K n (ε₀ + ε̄)^{n−1} with n ≥ 0.
      bool is_nondecreasing(const double T) const override
      {
        return scale(soft_K, thermal->factor(T)) * K >= 0;
      }

    private:
      double K = 0, eps0 = 0, n = 1;
      bool   soft_K = true;
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_HARDENING_LAW(anvil::SwiftHardening, "swift",
                             "K (eps0 + eps)^n (Strength coefficient K, Reference strain eps0, "
                             "Hardening exponent n)")
