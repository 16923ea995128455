#include <anvil/core/scene.h>
#include <anvil/material/hardening/interface.h>

#include <cmath>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// σᵥ = σ₀ + h ε̄ + (σ∞ − σ₀)(1 − e^{−δ ε̄}) (Simo & Miehe 1992): Voce with a
    /// linear term. Voce (below) is this law with h = 0: adding the zero term is
    /// exact, so it gives Voce's numbers bit for bit.
    class SaturationHardening : public HardeningLaw
    {
    public:
      explicit SaturationHardening(const bool linear_term = true)
        : linear_term(linear_term)
      {}

      static void declare_parameters(ParameterHandler &prm)
      {
        declare_common_entry(prm, "Initial yield stress");
        declare_common_entry(prm, "Hardening modulus");
        declare_common_entry(prm, "Saturation stress");
        declare_common_entry(prm, "Saturation exponent");
      }

      void parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path) override
      {
        sigma0         = prm.get_double("Initial yield stress");
        h              = linear_term ? prm.get_double("Hardening modulus") : 0.;
        sigma_inf      = prm.get_double("Saturation stress");
        delta          = prm.get_double("Saturation exponent");
        soft_sigma0    = softened("initial yield stress");
        soft_h         = softened("hardening modulus");
        soft_sigma_inf = softened("saturation stress");
        if (!(sigma0 > 0))
          scene.fail(path + "/Initial yield stress",
                     std::string("must be > 0 MPa for the ") + (linear_term ? "saturation" : "voce") +
                       " model");
        if (!(sigma_inf >= sigma0))
          scene.fail(path + "/Saturation stress", "must be >= Initial yield stress");
      }

      Value evaluate(const double eps, const double T) const override
      {
        const double theta = thermal->factor(T), dtheta = thermal->derivative(T);
        const double e     = 1 - std::exp(-delta * eps);
        const double s0 = scale(soft_sigma0, theta) * sigma0, s_inf = scale(soft_sigma_inf, theta) * sigma_inf;
        const double ds0 = scale_derivative(soft_sigma0, dtheta) * sigma0;
        Value        v;
        v.stress = s0 + scale(soft_h, theta) * h * eps + (s_inf - s0) * e;
        v.slope  = scale(soft_h, theta) * h + (s_inf - s0) * delta * (1 - e);
        v.temperature_derivative = ds0 + scale_derivative(soft_h, dtheta) * h * eps +
                                   (scale_derivative(soft_sigma_inf, dtheta) * sigma_inf - ds0) * e;
        return v;
      }

      StrengthLimit strength_limit() const override { return softening_limit(soft_sigma0); }

      bool is_nondecreasing(const double T) const override
      {
        const double theta = thermal->factor(T);
        return scale(soft_h, theta) * h >= 0 &&
               scale(soft_sigma_inf, theta) * sigma_inf - scale(soft_sigma0, theta) * sigma0 >= 0;
      }

    private:
      const bool linear_term;
      double     sigma0 = 0, h = 0, sigma_inf = 0, delta = 0;
      bool       soft_sigma0 = true, soft_h = true, soft_sigma_inf = true;
    };

    /// σᵥ = σ₀ + (σ∞ − σ₀)(1 − e^{−δ ε̄}) (Voce 1948).
    class VoceHardening : public SaturationHardening
    {
    public:
      VoceHardening()
        : SaturationHardening(false)
      {}
      static void declare_parameters(ParameterHandler &prm)
      {
        declare_common_entry(prm, "Initial yield stress");
        declare_common_entry(prm, "Saturation stress");
        declare_common_entry(prm, "Saturation exponent");
      }
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_HARDENING_LAW(anvil::SaturationHardening, "saturation",
                             "(Simo-Miehe) s0 + h eps + (s_inf - s0)(1 - exp(-delta eps)) "
                             "(Initial yield stress, Hardening modulus, Saturation stress, Saturation "
                             "exponent)")
ANVIL_REGISTER_HARDENING_LAW(anvil::VoceHardening, "voce",
                             "s0 + (s_inf - s0)(1 - exp(-delta eps)) (Initial yield stress s0, "
                             "Saturation stress s_inf, Saturation exponent delta)")
