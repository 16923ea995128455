#include <deal.II/base/mpi.h>

#include <cctype>

#include <anvil/core/scene.h>
#include <anvil/postprocess/interface.h>
#include <anvil/postprocess/probe_points.h>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    // "f(a, b)" -> ("f", {"a", "b"}); empty name if malformed.
    std::pair<std::string, std::vector<std::string>> parse_call(const std::string &text)
    {
      const auto open  = text.find('(');
      const auto close = text.rfind(')');
      if (open == std::string::npos || close == std::string::npos || close < open)
        return {"", {}};
      return {trim(text.substr(0, open)),
              split_outside_parentheses(text.substr(open + 1, close - open - 1), ',')};
    }

    // "probe(top, uy) - probe(bottom, uy) + 2" -> {(+1, "probe(top, uy)"),
    // (-1, "probe(bottom, uy)"), (+1, "2")}: split at the signs outside
    // parentheses that are not a number's exponent (1e-3).
    std::vector<std::pair<double, std::string>> split_sum(const std::string &text)
    {
      std::vector<std::pair<double, std::string>> terms;
      std::string                                 current;
      double                                      sign  = 1;
      int                                         depth = 0;
      for (std::size_t k = 0; k < text.size(); ++k)
        {
          const char c = text[k];
          depth += c == '(' ? 1 : c == ')' ? -1 : 0;
          const bool exponent = k >= 2 && (text[k - 1] == 'e' || text[k - 1] == 'E') &&
                                std::isdigit(static_cast<unsigned char>(text[k - 2])) &&
                                trim(current).find('(') == std::string::npos;
          if (depth == 0 && (c == '+' || c == '-') && !exponent)
            {
              if (!trim(current).empty())
                terms.emplace_back(sign, trim(current));
              else if (!terms.empty() || sign < 0)
                return {}; // two signs in a row
              sign    = c == '-' ? -1 : 1;
              current.clear();
              continue;
            }
          current += c;
        }
      if (trim(current).empty())
        return {};
      terms.emplace_back(sign, trim(current));
      return terms;
    }

    bool parse_number(const std::string &text, double &value)
    {
      try
        {
          std::size_t used = 0;
          value            = std::stod(text, &used);
          return used == text.size();
        }
      catch (...)
        {
          return false;
        }
    }

    // Units of the fields a quantity can read (mm, N, s, K; MPa).
    std::string unit_of_field(const std::string &field)
    {
      if (field.rfind("stress_", 0) == 0 || field == "von_mises" || field == "pressure")
        return "MPa";
      if (field == "temperature")
        return "K";
      if (field.size() == 2 && field[0] == 'u')
        return "mm";
      return "-";
    }
  } // namespace

  /**
   * The scene's named results (Output/Quantities of interest), evaluated at
   * the end of the run into summary.json: what tests, studies and plots read.
   */
  template <int dim>
  class Quantities : public Postprocessor<dim>
  {
  public:
    static void declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry(
        "Quantities of interest", "", Patterns::Anything(),
        "Named results written to summary.json at the end: 'name: expr; ...' with "
        "expr one of reaction(boundary, x|y|z) [N], probe(name, ux|uy|uz|<field>), "
        "max(<field>), min(<field>), mean(<field>[, body]), contact(pair, "
        "x|y|z|normal|tangential|friction_work|active_nodes|sliding_nodes|"
        "max_penetration) [N, N mm, mm], or a sum of these and numbers "
        "(e.g. 'dT: mean(temperature, upper) - 300', 'gap: probe(top, uy) - probe(bottom, "
        "uy)'); <field> is stress_xx..stress_zz, von_mises, pressure [MPa], J, "
        "equivalent_plastic_strain, temperature [K] (heat scenes). max and min of the "
        "temperature of a heat equation run over its nodal values (the extremes of the Q1 "
        "field); of the mechanical fields over the quadrature points (the material points "
        "themselves, not the cell averages of the VTU, which lie inside their range); of a "
        "prescribed temperature over cell averages. mean is the volume mean of cell "
        "averages. Each result is "
        "printed and written to summary.json with its unit (summary.json: units).");
    }

    void parse_parameters(ParameterHandler &prm, Scene &scene, const SceneContents<dim> &c) override;
    bool applies(const SceneContents<dim> &) const override { return !expressions.empty(); }
    void finish(const SimulationState<dim> &s, bool failed) override;
    void add_to_summary(const SimulationState<dim> &, Summary &summary) const override
    {
      for (const auto &[name, value] : values)
        summary.set("quantities_of_interest", name, value);
      // Beside, not inside: readers of quantities_of_interest keep their numbers.
      for (const auto &e : expressions)
        summary.set("units", e.name, e.unit);
      for (const auto &[name, note] : extrema)
        summary.set("quantities_of_interest_extrema", name, note);
    }
    std::vector<std::pair<std::string, std::string>> notes() const override { return extrema; }
    std::vector<std::pair<std::string, std::string>> units() const override
    {
      std::vector<std::pair<std::string, std::string>> u;
      for (const auto &e : expressions)
        u.emplace_back(e.name, e.unit);
      return u;
    }
    std::vector<std::pair<std::string, double>> results() const override { return values; }

  private:
    struct Quantity
    {
      std::string                name, kind, target, field;
      types::boundary_id         boundary  = 0;
      int                        body      = -1;
      unsigned int               component = 0;
      std::string                unit;
    };
    /// name: a sum of calls and numbers, with the unit its calls share.
    struct Expression
    {
      std::string                                 name, unit;
      std::vector<std::pair<double, Quantity>>    calls;
      double                                      constant = 0;
    };
    Quantity   parse_one(const std::string &item, const std::string &call, const Scene &scene,
                         const SceneContents<dim> &c, const std::vector<std::string> &fields) const;
    Expression parse_expression(const std::string &item, const Scene &scene,
                                const SceneContents<dim> &c,
                                const std::vector<std::string> &fields) const;
    double   evaluate(const Quantity &q, const SimulationState<dim> &s,
                      const typename MechanicalProblem<dim>::CellFields &fields) const;

    std::vector<ProbePoint<dim>>                probes;
    std::vector<Expression>                     expressions;
    std::vector<std::pair<std::string, double>> values;
    std::vector<std::pair<std::string, std::string>> extrema; // name -> what its max/min run over
  };

  template <int dim>
  void Quantities<dim>::parse_parameters(ParameterHandler &prm, Scene &scene,
                                         const SceneContents<dim> &c)
  {
    probes = parse_probe_points<dim>(prm.get({"Output"}, "Probes"), scene);
    std::vector<std::string> fields;
    if (c.mechanics)
      fields = {"stress_xx", "stress_xy", "stress_xz", "stress_yy", "stress_yz",
                "stress_zz", "von_mises", "pressure",  "J",         "equivalent_plastic_strain"};
    if (c.temperature)
      fields.push_back("temperature");
    for (const auto &item :
         split_outside_parentheses(prm.get({"Output"}, "Quantities of interest"), ';'))
      if (!item.empty())
        expressions.push_back(parse_expression(item, scene, c, fields));
  }

  template <int dim>
  typename Quantities<dim>::Quantity
  Quantities<dim>::parse_one(const std::string &item, const std::string &call, const Scene &scene,
                             const SceneContents<dim> &c, const std::vector<std::string> &fields) const
  {
    const std::string qpath = "Output/Quantities of interest";
    auto              is_field = [&](const std::string &f) {
      return std::find(fields.begin(), fields.end(), f) != fields.end();
    };
    std::string known_fields;
    for (const auto &f : fields)
      known_fields += (known_fields.empty() ? "" : ", ") + f;
    Quantity q;
    const auto [f, args] = parse_call(call);
    if (!f.empty() && trim(call.substr(call.rfind(')') + 1)).size() > 0)
      scene.fail(qpath, "item '" + item + "': '" + call + "': expected '+' or '-' after ')'");
    q.kind = f;
    auto component_of    = [&](const std::string &comp) -> unsigned int {
      for (unsigned int d = 0; d < dim; ++d)
        if (comp == std::string(1, "xyz"[d]))
          return d;
      scene.fail(qpath, "item '" + item + "': component '" + comp + "' should be x, y" +
                          (dim == 3 ? " or z" : ""));
    };
    if (f == "reaction" && args.size() == 2 && !c.mechanics)
      scene.fail(qpath, "item '" + item + "': a reaction needs the mechanics, and "
                                          "Physics/Coupling is 'thermal only'");
    if (f == "reaction" && args.size() == 2)
      {
        q.target    = args[0];
        q.boundary  = c.geometry->boundary_id(args[0], scene.where(qpath));
        q.component = component_of(args[1]);
        q.unit      = "N";
      }
    else if (f == "probe" && args.size() == 2)
      {
        q.target = args[0];
        q.field  = args[1];
        if (std::none_of(probes.begin(), probes.end(),
                         [&](const ProbePoint<dim> &p) { return p.name == args[0]; }))
          scene.fail(qpath, "item '" + item + "': no probe named '" + args[0] +
                              "' in Output/Probes");
        if (!is_field(q.field) && !(c.mechanics && q.field.size() == 2 && q.field[0] == 'u'))
          scene.fail(qpath, "item '" + item + "': unknown field '" + q.field +
                              "' for this scene (expected " +
                              (c.mechanics ? std::string(dim == 3 ? "ux, uy, uz, " : "ux, uy, ") :
                                             "") +
                              "one of: " + known_fields + ")");
        if (q.field == "temperature" && !c.heat)
          scene.fail(qpath, "item '" + item + "': a probe's temperature needs the heat equation "
                                              "(use mean(temperature) for a prescribed one)");
        if (q.field[0] == 'u' && q.field.size() == 2)
          q.component = component_of(q.field.substr(1));
        q.unit = unit_of_field(q.field);
      }
    else if (f == "contact" && args.size() == 2)
      {
        q.target          = args[0];
        q.field           = args[1];
        const auto &pairs = c.contact->get_pairs();
        if (std::none_of(pairs.begin(), pairs.end(), [&](const auto &p) { return p.name == args[0]; }))
          scene.fail(qpath, "item '" + item + "': no contact pair named '" + args[0] +
                              "' in Contact/Pairs");
        const std::vector<std::string> known = {"x", "y", "z", "normal", "tangential",
                                                "friction_work", "active_nodes",
                                                "sliding_nodes", "max_penetration"};
        if (std::find(known.begin(), known.end(), args[1]) == known.end() ||
            (args[1] == "z" && dim == 2))
          scene.fail(qpath, "item '" + item + "': expected contact(pair, x|y" +
                              (dim == 3 ? "|z" : "") +
                              "|normal|tangential|friction_work|active_nodes|sliding_nodes|"
                              "max_penetration)");
        q.unit = args[1] == "friction_work" ? "N mm" :
                 args[1] == "max_penetration" ? "mm" :
                 args[1].find("nodes") != std::string::npos ? "" : "N";
      }
    else if ((f == "max" || f == "min") && args.size() == 1 && is_field(args[0]))
      {
        q.field = args[0];
        q.unit  = unit_of_field(q.field);
      }
    else if (f == "mean" && (args.size() == 1 || args.size() == 2) && is_field(args[0]))
      {
        q.field = args[0];
        if (args.size() == 2)
          q.body = c.geometry->body_id(args[1], scene.where(qpath));
        q.unit = unit_of_field(q.field);
      }
    else
      scene.fail(qpath, "item '" + item + "': expected reaction(boundary, x), "
                          "probe(name, field), max(field), min(field) or mean(field[, body]) "
                          "with a field of this scene (" + known_fields + "), or a sum of "
                          "them and numbers");
    return q;
  }

  template <int dim>
  typename Quantities<dim>::Expression
  Quantities<dim>::parse_expression(const std::string &item, const Scene &scene,
                                    const SceneContents<dim> &c,
                                    const std::vector<std::string> &fields) const
  {
    const std::string qpath = "Output/Quantities of interest";
    const auto        colon = item.find(':');
    if (colon == std::string::npos || trim(item.substr(0, colon)).empty())
      scene.fail(qpath, "item '" + item + "': expected 'name: expression'");
    Expression e;
    e.name           = trim(item.substr(0, colon));
    const auto terms = split_sum(item.substr(colon + 1));
    if (terms.empty())
      scene.fail(qpath, "item '" + item + "': expected a call such as max(von_mises), or a sum "
                                          "'a + b - 300' of calls and numbers");
    std::vector<std::string> units;
    for (const auto &[sign, text] : terms)
      {
        double number = 0;
        if (text.find('(') == std::string::npos && parse_number(text, number))
          e.constant += sign * number;
        else
          {
            e.calls.emplace_back(sign, parse_one(item, text, scene, c, fields));
            units.push_back(e.calls.back().second.unit);
          }
      }
    if (e.calls.empty())
      scene.fail(qpath, "item '" + item + "': a number alone is not a result; expected a call");
    // A sum of quantities of different units has none; say so rather than guess.
    e.unit = units.front();
    for (const auto &u : units)
      if (u != e.unit)
        scene.fail(qpath, "item '" + item + "': adds '" + e.unit + "' and '" + u +
                            "': the terms of a sum must have the same unit");
    return e;
  }

  template <int dim>
  void Quantities<dim>::finish(const SimulationState<dim> &s, const bool failed)
  {
    // After a failure the state is the last converged one, not the scene's end:
    // its quantities would be mistaken for results.
    values.clear();
    extrema.clear();
    if (failed)
      return;
    typename MechanicalProblem<dim>::CellFields fields;
    if (s.physics.mechanics())
      fields = s.physics.mechanics()->cell_fields();
    if (s.physics.has_temperature())
      {
        fields.names.push_back("temperature");
        fields.values.push_back(s.physics.cell_temperature());
      }
    for (const auto &e : expressions)
      {
        double      value = e.constant;
        std::string note;
        for (const auto &[sign, q] : e.calls)
          {
            value += sign * evaluate(q, s, fields);
            // Say what each extremum runs over (they differ by field and scene).
            if (q.kind == "max" || q.kind == "min")
              {
                const std::string over =
                  q.field == "temperature" ?
                    (s.physics.heat() ? "nodal values" : "cell averages") :
                    "quadrature points";
                note += (note.empty() ? "" : "; ") + q.kind + "(" + q.field + ") over " + over;
              }
          }
        values.emplace_back(e.name, value);
        if (!note.empty())
          extrema.emplace_back(e.name, note);
      }
  }

  template <int dim>
  double Quantities<dim>::evaluate(const Quantity &q, const SimulationState<dim> &s,
                                   const typename MechanicalProblem<dim>::CellFields &fields) const
  {
    const auto *mechanical = s.physics.mechanics();
    if (q.kind == "reaction")
      return mechanical->reaction(q.boundary)[q.component];
    if (q.kind == "contact")
      {
        const auto &contact = s.physics.contact_problem();
        const auto &pairs   = contact.get_pairs();
        const auto  k = std::find_if(pairs.begin(), pairs.end(),
                                    [&](const auto &p) { return p.name == q.target; }) -
                       pairs.begin();
        const auto &c = contact.totals()[k];
        if (q.field.size() == 1)
          return c.force[q.field[0] - 'x'];
        if (q.field == "normal")
          return c.normal;
        if (q.field == "tangential")
          return c.tangential;
        if (q.field == "friction_work")
          return c.friction_work;
        if (q.field == "active_nodes")
          return c.active;
        if (q.field == "sliding_nodes")
          return c.sliding;
        return c.max_penetration;
      }
    if (q.kind == "probe")
      {
        const auto &p = *std::find_if(probes.begin(), probes.end(),
                                      [&](const ProbePoint<dim> &p) { return p.name == q.target; });
        Tensor<1, dim>        u;
        SymmetricTensor<2, 3> t;
        double                eqps = 0;
        if (mechanical)
          mechanical->probe(p.point, u, t, eqps);
        if (q.field == "temperature")
          return s.physics.heat()->temperature_at(p.point);
        if (q.field[0] == 'u' && q.field.size() == 2)
          return u[q.component];
        if (q.field == "equivalent_plastic_strain")
          return eqps;
        // The probe's cell average; evaluated from the stress tensor.
        const auto dev = deviator(t);
        if (q.field == "von_mises")
          return std::sqrt(1.5 * (dev * dev));
        if (q.field == "pressure")
          return -trace(t) / 3;
        return t[q.field[7] - 'x'][q.field[8] - 'x'];
      }
    if ((q.kind == "max" || q.kind == "min") && q.field == "temperature" && s.physics.heat())
      {
        // Nodal values: the extremes of the Q1 temperature field itself (a
        // cell average lies below the hottest node of its cell).
        const auto &h       = *s.physics.heat();
        double      extreme = q.kind == "max" ? -1e300 : 1e300;
        for (const auto i : h.get_dof_handler().locally_owned_dofs())
          extreme = q.kind == "max" ? std::max(extreme, double(h.temperature()(i))) :
                                      std::min(extreme, double(h.temperature()(i)));
        return q.kind == "max" ? Utilities::MPI::max(extreme, s.communicator) :
                                 Utilities::MPI::min(extreme, s.communicator);
      }
    const auto index = std::find(fields.names.begin(), fields.names.end(), q.field) -
                       fields.names.begin();
    // max and min over the quadrature points where the mechanics has them
    // (a cell average lies inside its points' range); mean over cell averages.
    const bool  at_points = q.kind != "mean" && std::size_t(index) < fields.max_values.size();
    const auto &v         = !at_points ? fields.values[index] :
                            q.kind == "max" ? fields.max_values[index] : fields.min_values[index];
    double      sum = 0, volume = 0, extreme = q.kind == "max" ? -1e300 : 1e300;
    for (const auto &cell : s.triangulation.active_cell_iterators())
      if (cell->is_locally_owned() && (q.body < 0 || cell->material_id() == types::material_id(q.body)))
        {
          const double x = v[cell->active_cell_index()];
          sum += x * cell->measure();
          volume += cell->measure();
          extreme = q.kind == "max" ? std::max(extreme, x) : std::min(extreme, x);
        }
    if (q.kind == "mean")
      return Utilities::MPI::sum(sum, s.communicator) / Utilities::MPI::sum(volume, s.communicator);
    if (q.kind == "max")
      return Utilities::MPI::max(extreme, s.communicator);
    return Utilities::MPI::min(extreme, s.communicator);
  }

  ANVIL_REGISTER_POSTPROCESSOR(Quantities, "quantities of interest",
                               "summary.json: the scene's named results (Output/Quantities of "
                               "interest), evaluated at the end of the run.")
} // namespace anvil
