// ContactProblem, its parameters: contact pairs and rigid tools from the scene
// (Contact/Pairs, Contact/Tools), checked against the mesh before any work.
#include <deal.II/base/bounding_box.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>
#include <deal.II/numerics/rtree.h>

#include <anvil/contact/contact_problem.h>
#include <anvil/core/input_error.h>
#include <anvil/core/instantiate.h>
#include <anvil/core/scene.h>
#include <anvil/geometry/geometry.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numeric>
#include <set>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    /// A comma-separated list of boundary names, each checked, as sorted ids.
    template <int dim>
    std::vector<types::boundary_id> boundary_list(const std::string &text, const std::string &parameter,
                                                  const Scene &scene, const Geometry<dim> &geometry,
                                                  const bool or_tool = false)
    {
      const std::string boundaries = "(" + geometry.list_boundary_names() + ")";
      if (text.empty())
        scene.fail(parameter, or_tool ? "is empty: expected boundaries " + boundaries +
                                          " or a tool of Contact/Tools" :
                                        "is empty: expected the name of a boundary, or a "
                                        "comma-separated list " + boundaries);
      const auto names = Utilities::split_string_list(text, ',');
      std::vector<types::boundary_id> ids;
      for (const auto &name : names)
        {
          if (geometry.boundary_names().count(name) == 0)
            {
              if (names.size() == 1)
                scene.fail(parameter, "= '" + name + "' is " +
                                        (or_tool ? "neither a boundary " + boundaries +
                                                     " nor a tool of Contact/Tools" :
                                                   "not a boundary of the mesh " + boundaries));
              scene.fail(parameter, "= '" + text + "': '" + name + "' is not a boundary of the mesh " +
                                      boundaries);
            }
          ids.push_back(geometry.boundary_id(name, scene.where(parameter)));
        }
      std::sort(ids.begin(), ids.end());
      if (std::adjacent_find(ids.begin(), ids.end()) != ids.end())
        scene.fail(parameter, "= '" + text + "' names a boundary twice");
      return ids;
    }
  } // namespace

  template <int dim>
  void ContactProblem<dim>::declare_parameters(ParameterHandler               &prm,
                                               const std::vector<std::string> &pair_names,
                                               const std::vector<std::string> &tool_names)
  {
    prm.enter_subsection("Contact");
    prm.declare_entry("Maximum penetration", "0", Patterns::Double(0),
                      "A converged step whose largest penetration exceeds this (mm) is cut back "
                      "and reported; 0: half the shortest edge of the contact surfaces.");
    prm.declare_entry("Frictional heating", "true", Patterns::Bool(),
                      "false: no pair's frictional power heats the surfaces (each pair's "
                      "Thermal/Frictional heating, for all at once: the seed's tube, case 2).");
    prm.declare_entry("Pattern look-ahead", "10", Patterns::Double(0),
                      "Steps (of the last step's sliding) whose master faces the matrix pattern "
                      "takes in when a slave meets a face outside it, so that it holds for "
                      "several steps; 0: only the step's candidates (a new pattern, KLU analysis "
                      "and pivoting at almost every step of a slide). Changes no answer.");
    prm.declare_entry("Self-contact pattern margin", "-1", Patterns::Double(-1),
                      "Self-contact: the matrix pattern also takes the faces of the surface that a "
                      "node comes within this distance of (in largest face lengths, beyond the "
                      "step's search margin of 1.5) over the look-ahead, moving relative to each "
                      "face as in the last step: a fold closing onto the skin (0.5: the tube's "
                      "crush builds 18 patterns instead of 181, but its factorisations fill the "
                      "wider pattern: more work in all, doc/contact.md). -1: off, self pairs look "
                      "ahead as other pairs. Changes no answer.");
    for (const auto &name : pair_names)
      {
        prm.enter_subsection(name);
        prm.declare_entry("Slave", "", Patterns::Anything(),
                          "The boundaries whose nodes are the slaves (comma-separated boundary "
                          "names).");
        prm.declare_entry("Master", "", Patterns::Anything(),
                          "The boundaries whose faces are the masters (comma-separated; the same "
                          "list as Slave: self-contact, e.g. a folding skin), or the name of a "
                          "rigid tool in Contact/Tools.");
        prm.declare_entry("Two-pass", "automatic", Patterns::Selection("automatic|true|false"),
                          "true: both surfaces act as slave and master (the seed's two-pass "
                          "approach), each pass with half the penalties; false: one pass, Slave "
                          "nodes on Master faces; automatic: two passes between two boundaries, "
                          "one against a tool. Self-contact: every node is a slave of the faces "
                          "across the fold, so one loop is both passes; true/automatic halve the "
                          "penalties as between bodies, false keeps them whole (twice as stiff).");
        prm.declare_entry("Penalty normal", "0", Patterns::Double(0),
                          "c_N of t_N = c_N <-g_N> (eq. 27): N/mm per node, or N/mm^3 per unit "
                          "area (Penalty per = area). Must be > 0.");
        prm.declare_entry("Penalty tangent", "0", Patterns::Double(0),
                          "c_T of the elastic slip (eq. 28), same units as Penalty normal; "
                          "0: frictionless.");
        prm.declare_entry("Free end taper", "0.05", Patterns::Double(0),
                          "2D: beyond a free end of the master surface (a vertex no other master "
                          "face shares, e.g. a skin's corner) its end segment still carries a "
                          "slave node, the force tapered smoothly to zero over this many lengths "
                          "of that segment, so that a node resting at the end does not flip in "
                          "and out of contact (doc/contact.md, 'Free ends'). 0: a sharp end. 3D "
                          "facet edges are sharp whatever this is.");
        prm.declare_entry("Penalty per", "node", Patterns::Selection("node|area"),
                          "node: the penalties are nodal stiffnesses (the seed's choice); area: "
                          "per unit area, scaled by each slave node's tributary area at the start "
                          "of the step (mesh independent).");
        prm.declare_entry("Friction coefficient", "0", Patterns::Double(0),
                          "Static Coulomb coefficient mu_s (eq. 29): sticking while "
                          "|t_T| <= mu_s t_N.");
        prm.declare_entry("Dynamic friction coefficient", "-1", Patterns::Double(-1),
                          "mu_d <= mu_s, the force while sliding is mu_d t_N; -1: equal to the "
                          "static one.");
        prm.enter_subsection("Thermal");
        prm.declare_entry("Conductance", "0", Patterns::Double(0),
                          "h0 of h = h0 (p/H)^e (eq. 34), mW/(mm^2 K); 0: no heat exchange.");
        prm.declare_entry("Hardness", "1000", Patterns::Double(0),
                          "Vickers hardness H of eq. 34, MPa.");
        prm.declare_entry("Exponent", "1", Patterns::Double(0), "e of eq. 34.");
        prm.declare_entry("Relative effusivity", "0.5", Patterns::Double(0, 1),
                          "Share of the frictional heat that goes to the slave side (eq. 31-33), "
                          "0 to 1.");
        prm.declare_entry("Frictional heating", "true", Patterns::Bool(),
                          "true: the frictional power D = t_T . slip / dt heats the surfaces "
                          "(eq. 31-33); false: it is dissipated without heating them (the seed's "
                          "tube, case 2), the conduction across the contact stays.");
        prm.leave_subsection();
        prm.leave_subsection();
      }
    for (const auto &name : tool_names)
      {
        prm.enter_subsection(name);
        RigidTool<dim>::declare_parameters(prm);
        prm.leave_subsection();
      }
    prm.leave_subsection();
  }

  template <int dim>
  void ContactProblem<dim>::parse_parameters(ParameterHandler &prm, const Scene &scene,
                                             const Geometry<dim> &geometry)
  {
    pairs.clear();
    tools.clear();
    prm.enter_subsection("Contact");
    penetration_limit = prm.get_double("Maximum penetration");
    look_ahead_steps  = prm.get_double("Pattern look-ahead");
    self_margin_faces = prm.get_double("Self-contact pattern margin");
    const bool frictional_heating = prm.get_bool("Frictional heating");
    for (const auto &name : scene.contact_tool_names())
      {
        prm.enter_subsection(name);
        tools.push_back(std::make_unique<RigidTool<dim>>());
        tools.back()->parse_parameters(prm, scene, "Contact/" + name);
        tools.back()->name = name;
        prm.leave_subsection();
      }
    for (const auto &name : scene.contact_pair_names())
      {
        const std::string path = "Contact/" + name + "/";
        prm.enter_subsection(name);
        Pair p;
        p.name        = name;
        p.slave_name  = trim(prm.get("Slave"));
        p.master_name = trim(prm.get("Master"));
        p.slaves      = boundary_list(p.slave_name, path + "Slave", scene, geometry);
        for (unsigned int k = 0; k < tools.size(); ++k)
          if (tools[k]->name == p.master_name)
            p.tool = k;
        if (p.tool >= 0 && geometry.boundary_names().count(p.master_name))
          scene.fail(path + "Master", "= '" + p.master_name +
                                        "' names both a tool and a boundary: rename the tool");
        if (p.tool < 0)
          {
            p.masters = boundary_list(p.master_name, path + "Master", scene, geometry, true);
            // Self-contact: the same boundaries on both sides. Partly shared
            // lists would count the shared part twice (once per pass).
            p.self = p.slaves == p.masters;
            std::vector<types::boundary_id> shared;
            std::set_intersection(p.slaves.begin(), p.slaves.end(), p.masters.begin(),
                                  p.masters.end(), std::back_inserter(shared));
            if (!p.self && !shared.empty())
              scene.fail(path + "Master", "= '" + p.master_name + "' shares boundaries with Slave = '" +
                                            p.slave_name + "': expected the same list (self-contact) "
                                            "or boundaries disjoint from the Slave's");
          }
        const std::string passes = prm.get("Two-pass");
        p.two_pass = passes == "true" || (passes == "automatic" && p.tool < 0);
        if (p.two_pass && p.tool >= 0)
          scene.fail(path + "Two-pass", "is true but the Master is a rigid tool (a tool has no nodes)");
        p.per_area                = prm.get("Penalty per") == "area";
        p.end_taper               = prm.get_double("Free end taper");
        p.law.penalty_normal      = prm.get_double("Penalty normal");
        p.law.penalty_tangent     = prm.get_double("Penalty tangent");
        p.law.mu_static           = prm.get_double("Friction coefficient");
        const double mu_d         = prm.get_double("Dynamic friction coefficient");
        p.law.mu_dynamic          = mu_d < 0 ? p.law.mu_static : mu_d;
        if (!(p.law.penalty_normal > 0))
          scene.fail(path + "Penalty normal", "must be > 0 (N/mm per node, N/mm^3 per area)");
        if (p.law.mu_static > 0 && !(p.law.penalty_tangent > 0))
          scene.fail(path + "Penalty tangent",
                     "must be > 0 when there is friction (Friction coefficient > 0)");
        if (p.law.mu_dynamic > p.law.mu_static)
          scene.fail(path + "Dynamic friction coefficient",
                     "must not exceed the static Friction coefficient");
        prm.enter_subsection("Thermal");
        p.conductance = prm.get_double("Conductance");
        p.hardness    = prm.get_double("Hardness");
        p.exponent    = prm.get_double("Exponent");
        p.slave_share = prm.get_double("Relative effusivity");
        p.frictional_heating = frictional_heating && prm.get_bool("Frictional heating");
        prm.leave_subsection();
        if (!(p.hardness > 0))
          scene.fail(path + "Thermal/Hardness", "must be > 0 MPa");
        prm.leave_subsection();
        pairs.push_back(p);
      }
    prm.leave_subsection();
    pair_totals.assign(pairs.size(), PairTotals());
  }

  ANVIL_INSTANTIATE_CLASS(ContactProblem)
} // namespace anvil
