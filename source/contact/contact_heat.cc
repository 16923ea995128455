// ContactProblem, thermal side (seed §3.1, eq. 30–34): the characteristic
// area of a slave node, the conductance and frictional power frozen after the
// mechanical phase, the exchange as the thermal problem applies it, and the
// heat accounting of a step.
#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <anvil/contact/contact_problem.h>
#include <anvil/core/gather.h>
#include <anvil/core/instantiate.h>

#include <algorithm>
#include <cmath>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  double ContactProblem<dim>::characteristic_area(const unsigned int node, const Surface &surface,
                                                  const Tensor<1, dim> &normal) const
  {
    const auto &x    = x_last;
    double      area = 0;
    if constexpr (dim == 2)
      {
        // The faces run consistently along the boundary (x₀ → x₁); t ⟂ n is
        // oriented along the node's two faces together, so that a face that
        // folds back (a corner of the slave body) projects negatively and
        // counts zero: A = (max(L₁, 0) + max(L₂, 0))/2.
        Tensor<1, dim> t, sum;
        t[0] = -normal[1];
        t[1] = normal[0];
        for (const auto f : node_faces[node])
          if (surface.has(faces[f]))
            sum += x[faces[f].nodes[1]] - x[faces[f].nodes[0]];
        if (sum * t < 0)
          t *= -1;
        for (const auto f : node_faces[node])
          if (surface.has(faces[f]))
            {
              const auto  &nodes     = faces[f].nodes;
              const double projected = std::max(0., (x[nodes[1]] - x[nodes[0]]) * t);
              // Axisymmetric: the node's share of the ring the projected
              // segment sweeps, ∫ N 2πr ds = 2π L (2 r_node + r_other)/6, as
              // the tributary area of the penalty (contact_problem.cc), so a
              // uniform penetration gives a uniform pressure (eq. 34). With
              // 2π r_node L/2 the node on the axis had no area and conducted
              // nothing, and the outer node's pressure was low by L/(3R).
              if (axisymmetric)
                area += 2 * numbers::PI * projected *
                        (2 * std::abs(x[node][0]) +
                         std::abs(x[nodes[0] == node ? nodes[1] : nodes[0]][0])) /
                        6;
              else
                area += 0.5 * projected;
            }
      }
    else
      for (const auto f : node_faces[node])
        if (surface.has(faces[f]))
          {
            // A quarter of each facet projected on the master's tangent plane,
            // a facet turned away counting zero.
            const auto          &nodes = faces[f].nodes;
            const Tensor<1, dim> d1 = x[nodes[3]] - x[nodes[0]], d2 = x[nodes[2]] - x[nodes[1]];
            const Tensor<1, dim> facet = 0.5 * cross_product_3d(d1, d2); // along the facet's outward normal
            area += 0.25 * std::max(0., -(facet * normal));              // the master normal faces the slave
          }
    return area;
  }

  template <int dim>
  bool ContactProblem<dim>::has_heat() const
  {
    for (const auto &p : pairs)
      if (p.conductance > 0 || (p.frictional_heating && p.law.mu_dynamic > 0))
        return true;
    return false;
  }

  template <int dim>
  void ContactProblem<dim>::setup_heat(const DoFHandler<dim> &thermal_dofs)
  {
    // Match the temperature dofs to the surface nodes by reference position.
    // Touching bodies have distinct vertices at the same place: the body tells them apart.
    std::map<std::array<double, dim + 1>, unsigned int> by_position;
    for (unsigned int n = 0; n < node_reference.size(); ++n)
      {
        std::array<double, dim + 1> X;
        X[0] = node_body[n];
        for (unsigned int c = 0; c < dim; ++c)
          X[c + 1] = node_reference[n][c];
        by_position[X] = n;
      }
    std::vector<double> local;
    for (const auto &cell : thermal_dofs.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          if (cell->face(f)->at_boundary() && surfaces.count(cell->face(f)->boundary_id()))
            for (unsigned int k = 0; k < GeometryInfo<dim>::vertices_per_face; ++k)
              {
                const unsigned int v = GeometryInfo<dim>::face_to_cell_vertices(f, k);
                local.push_back(cell->vertex_dof_index(v, 0));
                local.push_back(cell->material_id());
                for (unsigned int c = 0; c < dim; ++c)
                  local.push_back(cell->vertex(v)[c]);
              }
    node_thermal_dof.assign(node_reference.size(), numbers::invalid_dof_index);
    heat_couplings.clear();
    heat_couplings_grew = false;
    for (const auto &part : gather_doubles(mpi_communicator, local))
      for (std::size_t i = 0; i + dim + 2 <= part.size(); i += dim + 2)
        {
          std::array<double, dim + 1> X;
          for (unsigned int c = 0; c < dim + 1; ++c)
            X[c] = part[i + 1 + c];
          const auto it = by_position.find(X);
          if (it != by_position.end())
            node_thermal_dof[it->second] = static_cast<types::global_dof_index>(part[i]);
        }
    const IndexSet &owned = thermal_dofs.locally_owned_dofs();
    node_thermal_owned.resize(node_reference.size());
    for (unsigned int n = 0; n < node_reference.size(); ++n)
      {
        AssertThrow(node_thermal_dof[n] != numbers::invalid_dof_index,
                    ExcMessage("a contact node has no temperature dof"));
        node_thermal_owned[n] = owned.is_element(node_thermal_dof[n]);
      }
  }

  template <int dim>
  std::vector<double> ContactProblem<dim>::gather_node_values(const Vector &v) const
  {
    std::vector<double> values(node_reference.size(), 0.);
    for (unsigned int n = 0; n < node_reference.size(); ++n)
      if (node_thermal_owned[n])
        values[n] = v(node_thermal_dof[n]);
    Utilities::MPI::sum(values, mpi_communicator, values);
    return values;
  }

  template <int dim>
  void ContactProblem<dim>::prepare_heat(const double dt)
  {
    std::vector<double> local; // packed HeatElements
    for (const auto &slot : slots)
      {
        if (!slot.evaluated)
          continue;
        const Trial       &trial = slot.trial;
        const unsigned int p = slot.pair, pass = slot.pass, n = slot.node;
        const Pair &pair        = pairs[p];
        if (!(trial.normal_force > 0) || !(trial.area > 0))
          continue;
        // Two-pass: each pass carries half the contact force, so the pressure
        // is twice its share and each pass conducts through half the area.
        // Self-contact: one loop over the nodes of both sides of the fold, the
        // same halving (each side's nodes carry half the fold's pressure).
        const double half = pair.penalty_share();
        const double area = characteristic_area(n, slave_side(p, pass), trial.normal);
        if (!(area > 0))
          continue;
        const double pressure = trial.normal_force / (half * area); // eq. 34
        const double h        = pair.conductance > 0 ?
                                  half * pair.conductance * std::pow(pressure / pair.hardness, pair.exponent) :
                                  0.;
        // eq. 31: zero while sticking; none if the pair's Frictional heating
        // is off (the work is dissipated, not heat: seed §4.3, case 2).
        const double power    = pair.frictional_heating ? trial.work / dt : 0.;
        if (h == 0 && power == 0)
          continue;
        local.insert(local.end(), {double(p), double(n), h * area, power,
                                   pass == 0 ? pair.slave_share : 1 - pair.slave_share,
                                   double(pair.tool)});
        const auto &master = trial.face >= 0 ? faces[trial.face].nodes : std::vector<unsigned int>();
        local.push_back(master.size());
        for (unsigned int a = 0; a < 4; ++a)
          {
            local.push_back(a < master.size() ? master[a] : 0);
            local.push_back(a < master.size() ? trial.weights[a] : 0);
          }
      }
    heat_elements.clear();
    for (const auto &part : gather_doubles(mpi_communicator, local))
      for (std::size_t i = 0; i + 15 <= part.size(); i += 15)
        {
          HeatElement e;
          e.pair     = static_cast<unsigned int>(part[i]);
          e.slave    = static_cast<unsigned int>(part[i + 1]);
          e.hA       = part[i + 2];
          e.power    = part[i + 3];
          e.share    = part[i + 4];
          e.tool     = static_cast<int>(part[i + 5]);
          e.n_master = static_cast<unsigned int>(part[i + 6]);
          for (unsigned int a = 0; a < 4; ++a)
            {
              e.master[a] = static_cast<unsigned int>(part[i + 7 + 2 * a]);
              e.weight[a] = part[i + 8 + 2 * a];
            }
          heat_elements.push_back(e);
          // The slave's and the master face's temperatures couple in the heat
          // problem's Newton matrix: its pattern grows by new groups only.
          if (e.tool < 0 && e.n_master > 0)
            {
              std::vector<types::global_dof_index> group{node_thermal_dof[e.slave]};
              for (unsigned int a = 0; a < e.n_master; ++a)
                group.push_back(node_thermal_dof[e.master[a]]);
              std::sort(group.begin(), group.end());
              if (heat_couplings.insert(group).second)
                heat_couplings_grew = true;
            }
        }
  }

  template <int dim>
  HeatExchange ContactProblem<dim>::heat_exchange(
    const std::function<bool(types::global_dof_index)> &is_constrained)
  {
    // Q = hA (T_s − T_m(ξ)) from slave to master (eq. 30); D split by the
    // relative effusivity (eq. 32–33); a tool is a reservoir at T_tool(t).
    auto writable = [this, is_constrained](const unsigned int n) {
      return node_thermal_owned[n] && !is_constrained(node_thermal_dof[n]);
    };
    HeatExchange e;
    // Only a tool's temperature depends on t (the rest is held over the step).
    e.rhs_depends_on_time = !tools.empty();
    e.add_rhs = [this, writable](const double t, const Vector &T, Vector &f) {
      const auto Tn = gather_node_values(T);
      for (const auto &h : heat_elements)
        {
          double Tm = 0;
          if (h.tool >= 0)
            Tm = tools[h.tool]->temperature(t);
          else
            for (unsigned int a = 0; a < h.n_master; ++a)
              Tm += h.weight[a] * Tn[h.master[a]];
          const double Q = h.hA * (Tn[h.slave] - Tm);
          if (writable(h.slave))
            f(node_thermal_dof[h.slave]) += -Q + h.share * h.power;
          for (unsigned int a = 0; a < h.n_master; ++a)
            if (writable(h.master[a]))
              f(node_thermal_dof[h.master[a]]) += h.weight[a] * (Q + (1 - h.share) * h.power);
        }
    };
    e.add_jacobian = [this, writable](const Vector &v, Vector &Jv) {
      const auto vn = gather_node_values(v);
      for (const auto &h : heat_elements)
        {
          double vm = 0;
          for (unsigned int a = 0; a < h.n_master; ++a)
            vm += h.weight[a] * vn[h.master[a]];
          const double dQ = h.hA * (vn[h.slave] - vm);
          if (writable(h.slave))
            Jv(node_thermal_dof[h.slave]) += -dQ;
          for (unsigned int a = 0; a < h.n_master; ++a)
            if (writable(h.master[a]))
              Jv(node_thermal_dof[h.master[a]]) += h.weight[a] * dQ;
        }
    };
    e.add_matrix = [this, is_constrained](const HeatExchange::Adder &add) {
      exchange_tangent(is_constrained, add);
    };
    e.couplings = [this]() {
      heat_couplings_grew = false;
      return std::vector<std::vector<types::global_dof_index>>(heat_couplings.begin(),
                                                               heat_couplings.end());
    };
    e.couplings_changed = [this]() { return heat_couplings_grew; };
    return e;
  }

  template <int dim>
  void ContactProblem<dim>::heat_links(std::vector<std::vector<types::global_dof_index>> &u_columns,
                                       std::vector<std::vector<types::global_dof_index>> &T_rows) const
  {
    for (const auto &[p, pass, n, f] : step_allowed)
      {
        std::vector<types::global_dof_index> u(node_dofs[n].begin(), node_dofs[n].end()), T;
        T.push_back(node_thermal_dof[n]);
        for (const auto m : faces[f].nodes)
          {
            u.insert(u.end(), node_dofs[m].begin(), node_dofs[m].end());
            T.push_back(node_thermal_dof[m]);
          }
        const Surface &slave = slave_side(p, pass);
        for (const auto g : node_faces[n])
          if (slave.has(faces[g]))
            for (const auto m : faces[g].nodes)
              u.insert(u.end(), node_dofs[m].begin(), node_dofs[m].end());
        std::sort(u.begin(), u.end());
        u.erase(std::unique(u.begin(), u.end()), u.end());
        u_columns.push_back(u);
        T_rows.push_back(T);
      }
  }

  template <int dim>
  void ContactProblem<dim>::exchange_tangent(
    const std::function<bool(types::global_dof_index)>                                 &is_constrained,
    const std::function<void(types::global_dof_index, types::global_dof_index, double)> &add) const
  {
    // Q = hA (T_s − Σ w_a T_a) (eq. 30) leaves the slave and enters the master
    // nodes by the weights: ∂f_s/∂T = −∂Q/∂T, ∂f_a/∂T = w_a ∂Q/∂T.
    for (const auto &h : heat_elements)
      {
        std::vector<std::pair<unsigned int, double>> dQ{{h.slave, h.hA}};
        if (h.tool < 0)
          for (unsigned int a = 0; a < h.n_master; ++a)
            dQ.emplace_back(h.master[a], -h.weight[a] * h.hA);
        auto row = [&](const unsigned int n, const double factor) {
          const auto i = node_thermal_dof[n];
          if (node_thermal_owned[n] && !is_constrained(i))
            for (const auto &[m, d] : dQ)
              add(i, node_thermal_dof[m], factor * d);
        };
        row(h.slave, -1.);
        if (h.tool < 0)
          for (unsigned int a = 0; a < h.n_master; ++a)
            row(h.master[a], h.weight[a]);
      }
  }

  template <int dim>
  double ContactProblem<dim>::account_heat(const Vector &T_old, const Vector &T_new, const double dt)
  {
    const auto To = gather_node_values(T_old), Tn = gather_node_values(T_new);
    double     into_bodies = 0;
    heat_flux.clear();
    for (const auto &h : heat_elements)
      {
        auto master_T = [&](const std::vector<double> &T, const double t) {
          if (h.tool >= 0)
            return tools[h.tool]->temperature(t);
          double Tm = 0;
          for (unsigned int a = 0; a < h.n_master; ++a)
            Tm += h.weight[a] * T[h.master[a]];
          return Tm;
        };
        const double Q = 0.5 * h.hA *
                         ((To[h.slave] - master_T(To, t_old)) + (Tn[h.slave] - master_T(Tn, t_new)));
        heat_flux[{h.pair, h.slave}] = Q; // for the fields: W, per node
        auto &totals = pair_totals[h.pair];
        totals.heat_exchanged += Q * dt;
        // Into the bodies: all of D for a deformable master, the slave's share
        // and what the tool conducts in (−Q) for a tool.
        const double friction = (h.tool >= 0 ? h.share : 1.) * h.power * dt;
        totals.friction_heat += friction;
        into_bodies += friction - (h.tool >= 0 ? Q * dt : 0.);
      }
    return into_bodies;
  }

  // The class is instantiated in contact_problem.cc; these are its heat members.
  ANVIL_INSTANTIATE_CLASS(ContactProblem)
} // namespace anvil
