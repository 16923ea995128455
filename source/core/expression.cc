#include <anvil/core/expression.h>
#include <anvil/core/instantiate.h>
#include <anvil/core/scene.h>

#include <iostream>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  std::shared_ptr<FunctionParser<dim>> parse_expression(const std::string &expression,
                                                        const std::string &variables,
                                                        const bool         time_dependent,
                                                        const Scene       &scene,
                                                        const std::string &path,
                                                        const std::string &what)
  {
    auto f = std::make_shared<FunctionParser<dim>>(1);
    // deal.II prints muparser's diagnosis to std::cerr before it throws:
    // capture it for our one-line message.
    std::ostringstream diagnosis;
    std::streambuf    *cerr_buffer = std::cerr.rdbuf(diagnosis.rdbuf());
    bool               ok          = true;
    try
      {
        f->initialize(variables, expression, {{"pi", numbers::PI}}, time_dependent);
        f->value(Point<dim>()); // muparser reports unknown names on first evaluation
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
