#pragma once

#include <deal.II/base/parameter_handler.h>

#include <anvil/material/hardening/interface.h>
#include <anvil/material/softening/interface.h>

#include <memory>
#include <string>
#include <vector>

namespace anvil
{
  class Scene;

  /**
   * A scalar property as a function of temperature: constant, linear
   * p(T) = p₀ (1 − ω (T − T_ref)) (the form of eq. 35), or a table of (T, p)
   * pairs interpolated linearly and held constant outside.
   *
   *   set Model          = constant | linear | table
   *   set Value          = p₀ (units of the property)
   *   set Softening      = ω, 1/K (linear)
   *   set Table          = T1 : p1, T2 : p2, ... (table; T increasing, K)
   */
  class TemperatureLaw
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm,
                                   const std::string        &default_value,
                                   const std::string        &unit_help);
    void        parse_parameters(dealii::ParameterHandler &prm,
                                 const Scene              &scene,
                                 const std::string        &path,
                                 double                    reference_temperature);

    /// p(T) and dp/dT. The constant case is inline: these run several times
    /// per material point update.
    double value(double T) const { return kind == Kind::constant ? p0 : general_value(T); }
    double derivative(double T) const { return kind == Kind::constant ? 0. : general_derivative(T); }
    bool   is_constant() const { return kind == Kind::constant; }
    double reference() const { return p0; }

  private:
    double general_value(double T) const;
    double general_derivative(double T) const;

    enum class Kind
    {
      constant,
      linear,
      table
    } kind = Kind::constant;
    double              p0 = 0, omega = 0, T_ref = 293;
    std::vector<double> T_table, p_table;
  };

  // The hardening and thermal-softening laws are registries of their own:
  // <anvil/material/hardening/interface.h>, <anvil/material/softening/interface.h>.
} // namespace anvil
