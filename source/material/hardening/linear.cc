#include <anvil/core/scene.h>
#include <anvil/material/hardening/interface.h>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// σᵥ = σ₀ + h ε̄ (seed eq. 16 with linear isotropic hardening).
    class LinearHardening : public HardeningLaw
    {
    public:
      static void declare_parameters(ParameterHandler &prm)
      {
        declare_common_entry(prm, "Initial yield stress");
        declare_common_entry(prm, "Hardening modulus");
      }

      void parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path) override
      {
        sigma0      = prm.get_double("Initial yield stress");
        h           = prm.get_double("Hardening modulus");
        soft_sigma0 = softened("initial yield stress");
        soft_h      = softened("hardening modulus");
        if (!(sigma0 > 0))
          scene.fail(path + "/Initial yield stress", "must be > 0 MPa for the linear model");
      }

      Value evaluate(const double eps, const double T) const override
      {
        return linear_value(sigma0, h, soft_sigma0, soft_h, thermal->factor(T),
                            thermal->derivative(T), eps);
      }

      bool          is_linear() const override { return true; }
      bool          linear_form(LinearForm &form) const override
      {
        bool constant = false;
        if (!thermal->linear_form(constant, form.omega))
          return false;
        form.theta_linear = !constant;
        form.T_ref        = thermal->reference_temperature();
        form.sigma0       = sigma0;
        form.h            = h;
        form.soft_sigma0  = soft_sigma0;
        form.soft_h       = soft_h;
        return true;
      }
      StrengthLimit strength_limit() const override { return softening_limit(soft_sigma0); }
      bool is_nondecreasing(const double T) const override
      {
        return scale(soft_h, thermal->factor(T)) * h >= 0;
      }

    private:
      double sigma0 = 0, h = 0;
      bool   soft_sigma0 = true, soft_h = true;
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_HARDENING_LAW(anvil::LinearHardening, "linear",
                             "s0 + h eps (Initial yield stress s0, Hardening modulus h)")
