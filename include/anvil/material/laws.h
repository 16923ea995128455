#pragma once

#include <deal.II/base/function_parser.h>
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
   * A scalar property as a function of temperature (every parameter the seed
   * lets depend on T: moduli, eq. 10; eta, n, m, eq. 14 and 18; sigma_0 and h,
   * eq. 15-16; beta, eq. 19): constant, linear p(T) = p0 (1 - omega (T - T_ref))
   * (the form of eq. 35), a table of (T, p) pairs interpolated piecewise
   * linearly, or a muparser expression in T.
   *
   *   set Model          = constant | linear | table | expression
   *   set Value          = p0 (units of the property)
   *   set Softening      = omega, 1/K (linear)
   *   set Table          = T1 : p1, T2 : p2, ... (table; T increasing, K)
   *   set Expression     = a formula in T (expression)
   *   set Range          = T_min, T_max (expression; optional, K)
   *   set Out of range   = refuse | clamp: a temperature outside the table's
   *                        [T1, Tlast] (or the expression's Range) stops the
   *                        update naming the parameter, or holds the end value
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
    /// per material point update. A refused temperature throws
    /// MaterialPointError naming the parameter.
    double value(double T) const { return kind == Kind::constant ? p0 : general_value(T); }
    double derivative(double T) const { return kind == Kind::constant ? 0. : general_derivative(T); }
    bool   is_constant() const { return kind == Kind::constant; }
    /// p0 (constant, linear), p(T_ref) (table, expression).
    double reference() const { return kind == Kind::constant || kind == Kind::linear ? p0 : value_at_reference; }

    /**
     * Refuses (Scene::fail naming the entry) a law that is not > @p bound
     * (@p strict) or >= @p bound where it can be checked exactly: the value
     * (constant), p0 at T_ref (linear), every tabulated value (table: the
     * extrema of a piecewise linear function are at its nodes), p(T_ref) and,
     * with a Range, 201 samples over it (expression).
     * @p what names the property in the message ("eta", "m", ...).
     */
    void require_above(const Scene &scene, double bound, bool strict, const std::string &what) const;

    /// The lowest temperature above T_ref where a linear law p0 (1 − ω (T − T_ref))
    /// with p0 > 0 reaches 0, T_ref + 1/ω (ω > 0); +inf for the others (a table
    /// that require_above() passed stays positive; an expression is not analysed).
    double      vanishing_temperature() const;
    std::string vanishing_formula() const;

  private:
    double general_value(double T) const;
    double general_derivative(double T) const;
    [[noreturn]] void out_of_range(double T) const;

    enum class Kind
    {
      constant,
      linear,
      table,
      expression
    } kind = Kind::constant;
    double              p0 = 0, omega = 0, T_ref = 293, value_at_reference = 0;
    double              T_min = -1, T_max = -1; // range of a table or expression (T_min < 0: none)
    bool                refuse_outside = true;
    std::vector<double> T_table, p_table;
    std::shared_ptr<dealii::FunctionParser<1>> formula;
    std::string         path; // for messages only
  };

  // The hardening and thermal-softening laws are registries of their own:
  // <anvil/material/hardening/interface.h>, <anvil/material/softening/interface.h>.
} // namespace anvil
