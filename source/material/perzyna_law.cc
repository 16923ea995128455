#include <anvil/core/scene.h>
#include <anvil/material/j2_plasticity.h>

#include <cmath>
#include <string>

namespace anvil
{
  using namespace dealii;

  // ---------------------------------------------------------------- PerzynaLaw

  void PerzynaLaw::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Viscosity");
    prm.enter_subsection("Eta");
    TemperatureLaw::declare_parameters(prm, "0", "viscosity eta(T) in MPa^n s^(n/m), >= 0");
    prm.leave_subsection();
    prm.enter_subsection("n");
    TemperatureLaw::declare_parameters(prm, "1", "exponent n(T) on eta (seed eq. 14), > 0");
    prm.leave_subsection();
    prm.enter_subsection("m");
    TemperatureLaw::declare_parameters(prm, "1", "rate sensitivity m(T) (seed eq. 14), > 0");
    prm.leave_subsection();
    prm.declare_entry("Strain reference", "1", Patterns::Double(0),
                      "eps_eta in eta(eps, T) = eta(T) (1 + eps/eps_eta)^a, dimensionless, > 0.");
    prm.declare_entry("Strain exponent", "0", Patterns::Double(),
                      "a in eta(eps, T) = eta(T) (1 + eps/eps_eta)^a, dimensionless (0: no "
                      "dependence on plastic strain).");
    prm.leave_subsection();
  }

  void PerzynaLaw::parse_parameters(ParameterHandler  &prm,
                                    const Scene       &scene,
                                    const std::string &path,
                                    const double       T_ref)
  {
    const std::string p = path + "/Viscosity";
    prm.enter_subsection("Viscosity");
    prm.enter_subsection("Eta");
    eta.parse_parameters(prm, scene, p + "/Eta", T_ref);
    prm.leave_subsection();
    prm.enter_subsection("n");
    n.parse_parameters(prm, scene, p + "/n", T_ref);
    prm.leave_subsection();
    prm.enter_subsection("m");
    m.parse_parameters(prm, scene, p + "/m", T_ref);
    prm.leave_subsection();
    strain_reference = prm.get_double("Strain reference");
    strain_exponent  = prm.get_double("Strain exponent");
    prm.leave_subsection();
    enabled = true;
    // Every tabulated (or sampled) value, not only the reference: eq. (14)
    // needs eta >= 0 and n, m > 0 at every temperature the run may reach.
    eta.require_above(scene, 0, false, "eta");
    n.require_above(scene, 0, true, "n");
    m.require_above(scene, 0, true, "m");
    if (!(strain_reference > 0))
      scene.fail(p + "/Strain reference", "must be > 0");
  }

  PerzynaLaw::Rate PerzynaLaw::at(const double T, const double dt) const
  {
    Rate r;
    r.dt = dt;
    if (!enabled)
      return r;
    const double eta_T = eta.value(T);
    if (!(eta_T > 0))
      return r; // η_T ≤ 0: no overstress, rate-independent J2
    const double nT = n.value(T), mT = m.value(T);
    r.inv_n        = 1 / nT;
    r.m            = mT;
    r.inv_m        = 1 / mT;
    r.eta_root     = nT == 1 ? eta_T : std::pow(eta_T, r.inv_n);
    r.strain_power = strain_exponent * r.inv_n;
    return r;
  }

  PerzynaLaw::Value PerzynaLaw::evaluate(const Rate &r, const double eps, const double dp) const
  {
    Value v;
    if (!r.active() || !(dp > 0))
      {
        // The derivative at dp = 0 is infinite for m > 1; callers keep dp > 0.
        return v;
      }
    // η(ε̄, T)^{1/n} = η_T^{1/n} (1 + ε̄/ε_η)^{a/n} and its logarithmic derivative in ε̄.
    double c = r.eta_root, dlnc = 0;
    if (strain_exponent != 0)
      {
        c *= std::pow(1 + eps / strain_reference, r.strain_power);
        dlnc = r.strain_power / (strain_reference + eps);
      }
    const double rate = dp / r.dt;
    v.stress          = c * (r.inv_m == 1 ? rate : std::pow(rate, r.inv_m));
    // d/dΔε̄: the rate term and η's dependence on ε̄ = ε̄_n + Δε̄.
    v.log_derivative = v.stress * (r.inv_m + dp * dlnc);
    v.derivative     = v.stress * (r.inv_m / dp + dlnc);
    return v;
  }

  double PerzynaLaw::temperature_derivative(const Rate  &r,
                                            const double T,
                                            const double eps,
                                            const double dp,
                                            const double stress) const
  {
    if (!r.active() || !(dp > 0))
      return 0;
    // ∂/∂T of ln V = (1/n) ln η − (1/m) ... with n(T), m(T), η(T).
    const double eta_T = eta.value(T);
    double       dlnV  = eta.derivative(T) / eta_T * r.inv_n;
    if (const double dn = n.derivative(T); dn != 0)
      dlnV -= dn * r.inv_n * r.inv_n *
              std::log(eta_T * std::pow(1 + eps / strain_reference, strain_exponent));
    if (const double dm = m.derivative(T); dm != 0)
      dlnV -= dm * r.inv_m * r.inv_m * std::log(dp / r.dt);
    return stress * dlnV;
  }

  double PerzynaLaw::rate_bound(const Rate &r, const double eps, const double overstress) const
  {
    double c = r.eta_root;
    if (strain_exponent != 0)
      c *= std::pow(1 + eps / strain_reference, r.strain_power);
    const double x = overstress / c;
    return r.dt * (r.m == 1 ? x : std::pow(x, r.m));
  }
} // namespace anvil
