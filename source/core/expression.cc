#include <anvil/core/expression.h>
#include <anvil/core/instantiate.h>
#include <anvil/core/scene.h>

#include <anvil/core/input_error.h>

#include <deal.II/base/mpi.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    std::mutex  non_finite_mutex;
    std::string first_non_finite; // guarded by non_finite_mutex

    /// A formula that checks what it gives: a load, temperature or motion
    /// that is NaN or infinite is the scene's error, not a step to cut back.
    /// It is recorded, not thrown: the value may come from an assembly thread
    /// (deal.II aborts on exceptions there) or from one process only.
    template <int dim>
    class CheckedFunctionParser : public FunctionParser<dim>
    {
    public:
      CheckedFunctionParser(const std::string &location, const std::string &variables,
                            const std::string &expression)
        : FunctionParser<dim>(1)
        , location(location)
        , variables(Utilities::split_string_list(variables))
        , expression(expression)
      {}

      double value(const Point<dim> &p, const unsigned int component = 0) const override
      {
        const double v = FunctionParser<dim>::value(p, component);
        if (!std::isfinite(v))
          {
            std::ostringstream at;
            at << std::setprecision(6);
            for (unsigned int d = 0; d < variables.size(); ++d)
              at << (d ? ", " : "") << variables[d] << " = "
                 << (d < dim ? p[d] : this->get_time());
            record_input_error(location + " = '" + expression + "' evaluates to " +
                              (std::isnan(v) ? "NaN" : v > 0 ? "+inf" : "-inf") + " at " +
                              at.str() + ": expected a finite value wherever and whenever "
                              "the run evaluates it");
          }
        return v;
      }

    private:
      const std::string              location;
      const std::vector<std::string> variables;
      const std::string              expression;
    };
  } // namespace

  void record_input_error(const std::string &message)
  {
    std::lock_guard<std::mutex> lock(non_finite_mutex);
    if (first_non_finite.empty())
      first_non_finite = message;
  }

  void throw_recorded_input_error(const MPI_Comm comm)
  {
    std::string mine;
    {
      std::lock_guard<std::mutex> lock(non_finite_mutex);
      mine = first_non_finite;
    }
    // Collective: every process throws the first process's message. Called
    // twice a step: a one-int reduction first (the string gather serialises
    // through boost, ~200 000 instructions a call, for a message that is
    // almost always empty everywhere).
    if (Utilities::MPI::max(int(!mine.empty()), comm) == 0)
      return;
    for (const auto &message : Utilities::MPI::all_gather(comm, mine))
      if (!message.empty())
        throw InputError(message);
  }

  template <int dim>
  std::shared_ptr<FunctionParser<dim>> parse_expression(const std::string &expression,
                                                        const std::string &variables,
                                                        const bool         time_dependent,
                                                        const Scene       &scene,
                                                        const std::string &path,
                                                        const std::string &what)
  {
    auto f = std::make_shared<CheckedFunctionParser<dim>>(scene.where(path) + ": '" + path + "'",
                                                          variables, expression);
    // deal.II prints muparser's diagnosis to std::cerr before it throws:
    // capture it for our one-line message.
    std::ostringstream diagnosis;
    std::streambuf    *cerr_buffer = std::cerr.rdbuf(diagnosis.rdbuf());
    bool               ok          = true;
    try
      {
        f->initialize(variables, expression, {{"pi", numbers::PI}}, time_dependent);
        // muparser reports unknown names on first evaluation (unchecked: a
        // formula may be undefined at the origin and never evaluated there)
        f->FunctionParser<dim>::value(Point<dim>());
      }
    catch (...)
      {
        ok = false;
      }
    std::cerr.rdbuf(cerr_buffer);
    if (!ok)
      {
        std::string       reason;
        const std::string text = diagnosis.str();
        const auto        m    = text.find("Message:");
        if (m != std::string::npos)
          reason = trim(text.substr(m + 8, text.find('\n', m) - m - 8));
        scene.fail(path, "has an invalid expression '" + expression + "'" +
                           (what.empty() ? "" : " for " + what) +
                           (reason.empty() ? "" : " (" + reason + ")") +
                           ": expected a muparser formula in " + variables +
                           " (e.g. 0.5*t or if(t<1, t, 1), constant pi)");
      }
    return f;
  }

  template <int dim>
  std::shared_ptr<FunctionParser<dim>> parse_expression(const std::string &expression,
                                                        const Scene       &scene,
                                                        const std::string &path)
  {
    return parse_expression<dim>(expression, dim == 2 ? "x,y,t" : "x,y,z,t", true, scene, path, "");
  }

  template std::shared_ptr<FunctionParser<1>> parse_expression<1>(const std::string &, const std::string &, bool, const Scene &, const std::string &, const std::string &);
#define INSTANTIATE(dim)                                                                           \
  template std::shared_ptr<FunctionParser<dim>> parse_expression<dim>(                            \
    const std::string &, const std::string &, bool, const Scene &, const std::string &,           \
    const std::string &);                                                                         \
  template std::shared_ptr<FunctionParser<dim>> parse_expression<dim>(                            \
    const std::string &, const Scene &, const std::string &);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
