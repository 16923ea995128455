#include <deal.II/base/utilities.h>

#include <anvil/core/scene.h>
#include <anvil/material/laws.h>
#include <anvil/material/table.h>

#include <algorithm>
#include <cmath>

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

} // namespace anvil
