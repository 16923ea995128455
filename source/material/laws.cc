#include <deal.II/base/utilities.h>

#include <anvil/core/expression.h>
#include <anvil/core/scene.h>
#include <anvil/material/material_point.h>
#include <anvil/material/laws.h>
#include <anvil/material/number_format.h>
#include <anvil/material/table.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

namespace anvil
{
  using namespace dealii;

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

  // ---------------------------------------------------------------- TemperatureLaw

  void TemperatureLaw::declare_parameters(ParameterHandler  &prm,
                                          const std::string &default_value,
                                          const std::string &unit_help)
  {
    prm.declare_entry("Model", "constant", Patterns::Selection("constant|linear|table|expression"),
                      "How this property depends on temperature: constant, linear "
                      "p0 (1 - omega (T - T_ref)), table (piecewise linear) or expression in T.");
    prm.declare_entry("Value", default_value, Patterns::Double(), "p0, " + unit_help + ".");
    prm.declare_entry("Softening", "0", Patterns::Double(),
                      "omega of the linear model, 1/K.");
    prm.declare_entry("Table", "", Patterns::Anything(),
                      "Table model: 'T1 : p1, T2 : p2, ...' with T in K strictly increasing (at "
                      "least two pairs) and p in " + unit_help + "; linear in between.");
    prm.declare_entry("Expression", "", Patterns::Anything(),
                      "Expression model: a muparser formula in T (K), e.g. 70000 - 40*(T - 293); "
                      "its derivative is a central difference with a 1e-3 K step.");
    prm.declare_entry("Range", "", Patterns::Anything(),
                      "Expression model, optional: 'T_min, T_max' in K where the formula holds "
                      "(checked at 201 temperatures; outside: Out of range).");
    prm.declare_entry("Out of range", "refuse", Patterns::Selection("refuse|clamp"),
                      "A temperature outside the table (or the expression's Range): refuse stops "
                      "the material update with a message naming this parameter (the step is cut "
                      "back, then the run stops); clamp holds the end value (zero derivative).");
  }

  void TemperatureLaw::parse_parameters(ParameterHandler  &prm,
                                        const Scene       &scene,
                                        const std::string &path_,
                                        const double       reference_temperature)
  {
    const std::string m = prm.get("Model");
    kind  = m == "constant" ? Kind::constant :
            m == "linear"   ? Kind::linear :
            m == "table"    ? Kind::table :
                              Kind::expression;
    p0             = prm.get_double("Value");
    omega          = prm.get_double("Softening");
    T_ref          = reference_temperature;
    path           = path_;
    refuse_outside = prm.get("Out of range") == "refuse";
    T_min = T_max = -1;
    if (kind == Kind::table)
      {
        parse_table(prm.get("Table"), scene, path + "/Table", T_table, p_table);
        T_min = T_table.front(), T_max = T_table.back();
      }
    if (kind == Kind::expression)
      {
        formula = parse_expression<1>(prm.get("Expression"), "T", false, scene,
                                      path + "/Expression", "a property of the temperature T");
        if (const std::string r = trim(prm.get("Range")); !r.empty())
          {
            const auto parts = split_outside_parentheses(r, ',');
            try
              {
                if (parts.size() != 2)
                  throw std::invalid_argument("");
                T_min = std::stod(parts[0]), T_max = std::stod(parts[1]);
              }
            catch (...)
              {
                scene.fail(path + "/Range", "= '" + r + "': expected 'T_min, T_max' in K");
              }
            if (!(T_max > T_min && T_min >= 0))
              scene.fail(path + "/Range", "= '" + r + "': expected 0 <= T_min < T_max");
          }
      }
    if (kind == Kind::table || kind == Kind::expression)
      {
        // p(T_ref) for reference(): clamped, a reference outside the range is not an error.
        const bool keep = refuse_outside;
        refuse_outside  = false;
        value_at_reference = general_value(T_ref);
        refuse_outside     = keep;
      }
  }

  void TemperatureLaw::out_of_range(const double T) const
  {
    throw MaterialPointError("'" + path + "' is given for " + short_number(T_min) +
                             " K <= T <= " + short_number(T_max) +
                             " K and refuses T = " + short_number(T) +
                             " K (Out of range = refuse; extend it or set clamp)");
  }

  double TemperatureLaw::general_value(const double T) const
  {
    if (T_min >= 0 && (T < T_min || T > T_max))
      {
        if (refuse_outside)
          out_of_range(T);
        if (kind == Kind::expression)
          return formula->value(Point<1>(std::clamp(T, T_min, T_max)));
      }
    switch (kind)
      {
        case Kind::constant:
          return p0;
        case Kind::linear:
          return p0 * (1 - omega * (T - T_ref));
        case Kind::expression:
          return formula->value(Point<1>(T));
        default:
          return interpolate(T_table, p_table, T, false).first;
      }
  }

  double TemperatureLaw::general_derivative(const double T) const
  {
    if (T_min >= 0 && (T < T_min || T > T_max))
      {
        if (refuse_outside)
          out_of_range(T);
        return 0; // clamped
      }
    switch (kind)
      {
        case Kind::constant:
          return 0;
        case Kind::linear:
          return -p0 * omega;
        case Kind::expression:
          {
            // Central difference, one-sided at the ends of a Range.
            const double h  = 1e-3;
            const double hi = T_min >= 0 ? std::min(T + h, T_max) : T + h;
            const double lo = T_min >= 0 ? std::max(T - h, T_min) : T - h;
            return (formula->value(Point<1>(hi)) - formula->value(Point<1>(lo))) / (hi - lo);
          }
        default:
          return interpolate(T_table, p_table, T, false).second;
      }
  }

  double TemperatureLaw::vanishing_temperature() const
  {
    if (kind == Kind::linear && p0 > 0 && omega > 0)
      return T_ref + 1 / omega;
    return std::numeric_limits<double>::infinity();
  }

  std::string TemperatureLaw::vanishing_formula() const
  {
    return "T_ref + 1/omega = " + short_number(T_ref) + " + 1/" + short_number(omega);
  }

  void TemperatureLaw::require_above(const Scene       &scene,
                                     const double       bound,
                                     const bool         strict,
                                     const std::string &what) const
  {
    const std::string expected = std::string(strict ? "> " : ">= ") + short_number(bound);
    auto check = [&](const double T, const double p, const std::string &entry, const bool at_T) {
      if (strict ? p > bound : p >= bound)
        return;
      scene.fail(path + "/" + entry,
                 "gives " + what + " = " + short_number(p) +
                   (at_T ? " at T = " + short_number(T) + " K" : "") + ": expected " +
                   what + " " + expected + " at every temperature");
    };
    switch (kind)
      {
        case Kind::constant:
          check(T_ref, p0, "Value", false);
          break;
        case Kind::linear:
          check(T_ref, p0, "Value", false);
          break;
        case Kind::table:
          // Piecewise linear: its extrema are at the nodes.
          for (unsigned int i = 0; i < T_table.size(); ++i)
            check(T_table[i], p_table[i], "Table", true);
          break;
        case Kind::expression:
          check(T_ref, value_at_reference, "Expression", true);
          if (T_min >= 0)
            for (unsigned int i = 0; i <= 200; ++i)
              {
                const double T = T_min + (T_max - T_min) * i / 200.;
                check(T, formula->value(Point<1>(T)), "Expression", true);
              }
          break;
      }
  }

} // namespace anvil
