#include <deal.II/base/utilities.h>

#include <anvil/core/scene.h>
#include <anvil/material/laws.h>

#include <algorithm>
#include <cmath>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    // "x1 : y1, x2 : y2, ..." -> two vectors; x strictly increasing.
    void parse_table(const std::string   &text,
                     const Scene         &scene,
                     const std::string   &path,
                     std::vector<double> &x,
                     std::vector<double> &y)
    {
      x.clear();
      y.clear();
      for (const auto &pair : split_outside_parentheses(text, ','))
        {
          const auto colon = pair.find(':');
          try
            {
              if (colon == std::string::npos)
                throw std::invalid_argument("");
              std::size_t  a = 0, b = 0;
              const auto   xs = trim(pair.substr(0, colon)), ys = trim(pair.substr(colon + 1));
              const double xv = std::stod(xs, &a), yv = std::stod(ys, &b);
              if (a != xs.size() || b != ys.size())
                throw std::invalid_argument("");
              x.push_back(xv);
              y.push_back(yv);
            }
          catch (...)
            {
              scene.fail(path, "entry '" + pair + "': expected 'x : y' pairs of numbers");
            }
        }
      if (x.size() < 2)
        scene.fail(path, "needs at least two 'x : y' pairs");
      for (unsigned int i = 1; i < x.size(); ++i)
        if (!(x[i] > x[i - 1]))
          scene.fail(path, "is not increasing in its first column (" + Utilities::to_string(x[i - 1]) +
                             " then " + Utilities::to_string(x[i]) + ")");
    }

    // Piecewise linear interpolation; outside: constant (extrapolate=false) or last slope.
    std::pair<double, double> interpolate(const std::vector<double> &x,
                                          const std::vector<double> &y,
                                          const double               v,
                                          const bool                 extrapolate)
    {
      if (v <= x.front() && !extrapolate)
        return {y.front(), 0};
      if (v >= x.back() && !extrapolate)
        return {y.back(), 0};
      std::size_t i = std::upper_bound(x.begin(), x.end(), v) - x.begin();
      i             = std::min<std::size_t>(std::max<std::size_t>(i, 1), x.size() - 1);
      const double slope = (y[i] - y[i - 1]) / (x[i] - x[i - 1]);
      return {y[i - 1] + slope * (v - x[i - 1]), slope};
    }
  } // namespace

  // ---------------------------------------------------------------- TemperatureLaw

  void TemperatureLaw::declare_parameters(ParameterHandler  &prm,
                                          const std::string &default_value,
                                          const std::string &unit_help)
  {
    prm.declare_entry("Model", "constant", Patterns::Selection("constant|linear|table"),
                      "How this property depends on temperature: constant, linear "
                      "p0 (1 - omega (T - T_ref)) or table.");
    prm.declare_entry("Value", default_value, Patterns::Double(), "p0, " + unit_help + ".");
    prm.declare_entry("Softening", "0", Patterns::Double(),
                      "omega of the linear model, 1/K.");
    prm.declare_entry("Table", "", Patterns::Anything(),
                      "Table model: 'T1 : p1, T2 : p2, ...' with T in K increasing and p in " +
                        unit_help + "; constant outside the table.");
  }

  void TemperatureLaw::parse_parameters(ParameterHandler  &prm,
                                        const Scene       &scene,
                                        const std::string &path,
                                        const double       reference_temperature)
  {
    const std::string m = prm.get("Model");
    kind  = m == "constant" ? Kind::constant : m == "linear" ? Kind::linear : Kind::table;
    p0    = prm.get_double("Value");
    omega = prm.get_double("Softening");
    T_ref = reference_temperature;
    if (kind == Kind::table)
      parse_table(prm.get("Table"), scene, path + "/Table", T_table, p_table);
  }

  double TemperatureLaw::general_value(const double T) const
  {
    switch (kind)
      {
        case Kind::constant:
          return p0;
        case Kind::linear:
          return p0 * (1 - omega * (T - T_ref));
        default:
          return interpolate(T_table, p_table, T, false).first;
      }
  }

  double TemperatureLaw::general_derivative(const double T) const
  {
    switch (kind)
      {
        case Kind::constant:
          return 0;
        case Kind::linear:
          return -p0 * omega;
        default:
          return interpolate(T_table, p_table, T, false).second;
      }
  }

  // ---------------------------------------------------------------- ThermalSoftening

  void ThermalSoftening::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Thermal softening");
    prm.declare_entry("Model", "none", Patterns::Selection("none|linear|johnson-cook|table"),
                      "Factor theta(T) on the softened yield parameters: none (1), linear "
                      "1 - omega (T - T_ref) (seed eq. 35), johnson-cook 1 - ((T - T_ref)/(T_melt - "
                      "T_ref))^m, or table.");
    prm.declare_entry("Reference temperature", "293", Patterns::Double(0),
                      "T_ref in K: the temperature at which the yield parameters are given.");
    prm.declare_entry("Softening coefficient", "0", Patterns::Double(),
                      "omega of the linear model, 1/K (e.g. 2e-3).");
    prm.declare_entry("Melting temperature", "1800", Patterns::Double(0),
                      "T_melt of the Johnson-Cook model, K.");
    prm.declare_entry("Exponent", "1", Patterns::Double(0), "m of the Johnson-Cook model.");
    prm.declare_entry("Table", "", Patterns::Anything(),
                      "Table model: 'T1 : theta1, T2 : theta2, ...' (K, dimensionless).");
    prm.leave_subsection();
  }

  void ThermalSoftening::parse_parameters(ParameterHandler  &prm,
                                          const Scene       &scene,
                                          const std::string &path)
  {
    prm.enter_subsection("Thermal softening");
    model    = prm.get("Model");
    T_ref    = prm.get_double("Reference temperature");
    omega    = prm.get_double("Softening coefficient");
    T_melt   = prm.get_double("Melting temperature");
    exponent = prm.get_double("Exponent");
    const std::string table = prm.get("Table");
    prm.leave_subsection();
    kind = model == "linear"       ? Kind::linear :
           model == "johnson-cook" ? Kind::johnson_cook :
           model == "table"        ? Kind::table :
                                     Kind::none;
    const std::string p = path + "/Thermal softening";
    if (model == "johnson-cook" && !(T_melt > T_ref))
      scene.fail(p + "/Melting temperature", "must exceed the Reference temperature");
    if (model == "johnson-cook" && !(exponent > 0))
      scene.fail(p + "/Exponent", "must be > 0");
    if (model == "table")
      parse_table(table, scene, p + "/Table", T_table, f_table);
  }

  double ThermalSoftening::factor(const double T) const
  {
    switch (kind)
      {
        case Kind::linear:
          return 1 - omega * (T - T_ref);
        case Kind::johnson_cook:
          {
            const double s = std::clamp((T - T_ref) / (T_melt - T_ref), 0., 1.);
            return 1 - std::pow(s, exponent);
          }
        case Kind::table:
          return interpolate(T_table, f_table, T, false).first;
        default:
          return 1;
      }
  }

  double ThermalSoftening::derivative(const double T) const
  {
    switch (kind)
      {
        case Kind::linear:
          return -omega;
        case Kind::johnson_cook:
          {
            const double s = (T - T_ref) / (T_melt - T_ref);
            if (s <= 0 || s >= 1)
              return 0;
            return -exponent * std::pow(s, exponent - 1) / (T_melt - T_ref);
          }
        case Kind::table:
          return interpolate(T_table, f_table, T, false).second;
        default:
          return 0;
      }
  }

  // ---------------------------------------------------------------- HardeningLaw

  void HardeningLaw::declare_parameters(ParameterHandler &prm)
  {
    prm.enter_subsection("Hardening");
    prm.declare_entry("Model", "linear", Patterns::Selection("linear|swift|voce|saturation|table"),
                      "Yield stress sigma_v(eps, T): linear s0 + h eps; swift K (eps0 + eps)^n; "
                      "voce s0 + (s_inf - s0)(1 - exp(-delta eps)); saturation (Simo-Miehe) "
                      "s0 + h eps + (s_inf - s0)(1 - exp(-delta eps)); table.");
    prm.declare_entry("Initial yield stress", "0", Patterns::Double(),
                      "s0 in MPa (linear, voce, saturation); > 0.");
    prm.declare_entry("Hardening modulus", "0", Patterns::Double(),
                      "h in MPa (linear, saturation): slope of yield stress against plastic strain.");
    prm.declare_entry("Saturation stress", "0", Patterns::Double(),
                      "s_inf in MPa (voce, saturation).");
    prm.declare_entry("Saturation exponent", "0", Patterns::Double(0),
                      "delta, dimensionless (voce, saturation).");
    prm.declare_entry("Strength coefficient", "0", Patterns::Double(0), "K in MPa (swift).");
    prm.declare_entry("Reference strain", "0.002", Patterns::Double(0),
                      "eps0, dimensionless (swift), > 0.");
    prm.declare_entry("Hardening exponent", "0.2", Patterns::Double(0),
                      "n, dimensionless (swift).");
    prm.declare_entry("Table", "", Patterns::Anything(),
                      "Table model: 'eps1 : s1, eps2 : s2, ...' (dimensionless : MPa), eps from 0 "
                      "increasing; extrapolated with the last slope.");
    prm.declare_entry("Softened parameters", "all",
                      Patterns::MultipleSelection("all|none|initial yield stress|hardening modulus|"
                                                  "saturation stress|strength coefficient"),
                      "Which parameters the thermal softening factor multiplies (all: the whole "
                      "yield stress).");
    ThermalSoftening::declare_parameters(prm);
    prm.leave_subsection();
  }

  void HardeningLaw::parse_parameters(ParameterHandler  &prm,
                                      const Scene       &scene,
                                      const std::string &path)
  {
    const std::string p = path + "/Hardening";
    prm.enter_subsection("Hardening");
    model     = prm.get("Model");
    kind      = model == "linear"     ? Kind::linear :
                model == "swift"      ? Kind::swift :
                model == "voce"       ? Kind::voce :
                model == "saturation" ? Kind::saturation :
                                        Kind::table;
    sigma0    = prm.get_double("Initial yield stress");
    h         = prm.get_double("Hardening modulus");
    sigma_inf = prm.get_double("Saturation stress");
    delta     = prm.get_double("Saturation exponent");
    K         = prm.get_double("Strength coefficient");
    eps0      = prm.get_double("Reference strain");
    n         = prm.get_double("Hardening exponent");
    const auto softened = Utilities::split_string_list(prm.get("Softened parameters"));
    auto has = [&](const std::string &s) {
      return std::find(softened.begin(), softened.end(), s) != softened.end() ||
             std::find(softened.begin(), softened.end(), "all") != softened.end();
    };
    soft_sigma0    = has("initial yield stress");
    soft_h         = has("hardening modulus");
    soft_sigma_inf = has("saturation stress");
    soft_K         = has("strength coefficient");
    if (model == "table")
      parse_table(prm.get("Table"), scene, p + "/Table", eps_table, sigma_table);
    thermal.parse_parameters(prm, scene, p);
    prm.leave_subsection();

    if ((model == "linear" || model == "voce" || model == "saturation") && !(sigma0 > 0))
      scene.fail(p + "/Initial yield stress", "must be > 0 MPa for the " + model + " model");
    if ((model == "voce" || model == "saturation") && !(sigma_inf >= sigma0))
      scene.fail(p + "/Saturation stress", "must be >= Initial yield stress");
    if (model == "swift" && !(K > 0 && eps0 > 0))
      scene.fail(p + "/Strength coefficient", "and 'Reference strain' must be > 0 for swift");
    if (model == "table" && (eps_table.front() != 0 || !(sigma_table.front() > 0)))
      scene.fail(p + "/Table", "must start at plastic strain 0 with a yield stress > 0");
    table_nondecreasing = true;
    for (unsigned int i = 1; i < sigma_table.size(); ++i)
      table_nondecreasing = table_nondecreasing && sigma_table[i] >= sigma_table[i - 1];
  }

  bool HardeningLaw::is_nondecreasing(const double T) const
  {
    const double theta = thermal.factor(T);
    auto         f     = [&](bool soft) { return soft ? theta : 1.; };
    switch (kind)
      {
        case Kind::linear:
          return f(soft_h) * h >= 0;
        case Kind::swift: // slope K n (ε₀ + ε̄)^{n-1}, n ≥ 0
          return f(soft_K) * K >= 0;
        case Kind::voce: // slope (σ∞ − σ₀) δ e^{−δ ε̄}, δ ≥ 0
          return f(soft_sigma_inf) * sigma_inf - f(soft_sigma0) * sigma0 >= 0;
        case Kind::saturation:
          return f(soft_h) * h >= 0 && f(soft_sigma_inf) * sigma_inf - f(soft_sigma0) * sigma0 >= 0;
        default:
          return theta >= 0 && table_nondecreasing;
      }
  }

  HardeningLaw::Value HardeningLaw::evaluate(const double eps, const double T) const
  {
    const double theta  = thermal.factor(T);
    const double dtheta = thermal.derivative(T);
    // Each parameter a scaled by f = theta (if softened) or 1.
    auto f  = [&](bool soft) { return soft ? theta : 1.; };
    auto df = [&](bool soft) { return soft ? dtheta : 0.; };
    Value v;
    if (kind == Kind::linear)
      {
        v.stress                 = f(soft_sigma0) * sigma0 + f(soft_h) * h * eps;
        v.slope                  = f(soft_h) * h;
        v.temperature_derivative = df(soft_sigma0) * sigma0 + df(soft_h) * h * eps;
      }
    else if (kind == Kind::swift)
      {
        const double base        = std::pow(eps0 + eps, n);
        v.stress                 = f(soft_K) * K * base;
        v.slope                  = f(soft_K) * K * n * base / (eps0 + eps);
        v.temperature_derivative = df(soft_K) * K * base;
      }
    else if (kind == Kind::voce || kind == Kind::saturation)
      {
        const double e = 1 - std::exp(-delta * eps);
        const double lin = kind == Kind::saturation ? h : 0;
        v.stress = f(soft_sigma0) * sigma0 + f(soft_h) * lin * eps +
                   (f(soft_sigma_inf) * sigma_inf - f(soft_sigma0) * sigma0) * e;
        v.slope = f(soft_h) * lin +
                  (f(soft_sigma_inf) * sigma_inf - f(soft_sigma0) * sigma0) * delta * (1 - e);
        v.temperature_derivative = df(soft_sigma0) * sigma0 + df(soft_h) * lin * eps +
                                   (df(soft_sigma_inf) * sigma_inf - df(soft_sigma0) * sigma0) * e;
      }
    else
      {
        const auto [s, slope]    = interpolate(eps_table, sigma_table, eps, true);
        v.stress                 = theta * s;
        v.slope                  = theta * slope;
        v.temperature_derivative = dtheta * s;
      }
    return v;
  }
} // namespace anvil
