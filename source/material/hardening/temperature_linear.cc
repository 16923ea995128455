#include <anvil/core/scene.h>
#include <anvil/material/hardening/interface.h>
#include <anvil/material/laws.h>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /**
     * σᵥ = σ₀(T) + h(T) ε̄ (seed eq. 15–16 with linear isotropic hardening)
     * where the initial yield stress and the hardening modulus are each a
     * TemperatureLaw of their own (constant, linear, table, expression), as
     * the seed lets every parameter depend on T. A thermal softening θ(T), if
     * chosen, multiplies the parameters `Softened parameters` lists on top.
     */
    class TemperatureLinearHardening : public HardeningLaw
    {
    public:
      static void declare_parameters(ParameterHandler &prm)
      {
        prm.enter_subsection("Yield stress of T");
        TemperatureLaw::declare_parameters(prm, "0", "initial yield stress sigma_0(T) in MPa, > 0");
        prm.leave_subsection();
        prm.enter_subsection("Hardening modulus of T");
        TemperatureLaw::declare_parameters(prm, "0", "hardening modulus h(T) in MPa");
        prm.leave_subsection();
      }

      void parse_parameters(ParameterHandler &prm, const Scene &scene, const std::string &path) override
      {
        const double T_ref = softening().reference_temperature();
        prm.enter_subsection("Yield stress of T");
        sigma0.parse_parameters(prm, scene, path + "/Yield stress of T", T_ref);
        prm.leave_subsection();
        prm.enter_subsection("Hardening modulus of T");
        h.parse_parameters(prm, scene, path + "/Hardening modulus of T", T_ref);
        prm.leave_subsection();
        // σ₀ ≤ 0 anywhere in the table's range would remove all strength.
        sigma0.require_above(scene, 0, true, "the initial yield stress");
        const std::string entry = path + "/Yield stress of T/Softening";
        sigma0_location         = scene.where(entry) + ": '" + entry + "'";
        soft_sigma0 = softened("initial yield stress");
        soft_h      = softened("hardening modulus");
      }

      Value evaluate(const double eps, const double T) const override
      {
        const double theta = thermal->factor(T), dtheta = thermal->derivative(T);
        const double s0 = sigma0.value(T), ds0 = sigma0.derivative(T);
        const double hT = h.value(T), dh = h.derivative(T);
        const double a = scale(soft_sigma0, theta), b = scale(soft_h, theta);
        Value        v;
        v.stress                 = a * s0 + b * hT * eps;
        v.slope                  = b * hT;
        v.temperature_derivative = scale_derivative(soft_sigma0, dtheta) * s0 + a * ds0 +
                                   (scale_derivative(soft_h, dtheta) * hT + b * dh) * eps;
        return v;
      }

      bool is_linear() const override { return true; }

      // The softening's limit, or where σ₀(T) itself reaches 0, whichever is first.
      StrengthLimit strength_limit() const override
      {
        StrengthLimit limit = softening_limit(soft_sigma0);
        if (const double T0 = sigma0.vanishing_temperature(); T0 < limit.temperature)
          limit = {T0, sigma0_location, sigma0.vanishing_formula()};
        return limit;
      }
      bool is_nondecreasing(const double T) const override
      {
        return scale(soft_h, thermal->factor(T)) * h.value(T) >= 0;
      }

    private:
      TemperatureLaw sigma0, h;
      bool           soft_sigma0 = false, soft_h = false;
      std::string    sigma0_location;
    };
  } // namespace
} // namespace anvil

ANVIL_REGISTER_HARDENING_LAW(anvil::TemperatureLinearHardening, "temperature linear",
                             "s0(T) + h(T) eps, each a function of T (subsections 'Yield stress of "
                             "T', 'Hardening modulus of T': constant, linear, table or expression)")
