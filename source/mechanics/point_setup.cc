// The material points of the mechanics and the per-point data beside them:
// a block per body from its law (MaterialModel::create_points), the table of
// pointers into the blocks in cell order (PointData), and the heat's
// per-point doubles where a coupling reads them.
#include <anvil/core/input_error.h>
#include <anvil/core/instantiate.h>
#include <anvil/mechanics/element_formulation.h>
#include <anvil/mechanics/mechanical_problem.h>

#include <limits>
#include <map>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  void MechanicalProblem<dim>::setup_quadrature_point_data()
  {
    const unsigned int n_q = quadrature.size();
    points.reinit(triangulation, n_q, nullptr);
    point_blocks.clear();
    // The heat equation's sources and the points' own temperatures only
    // where something reads them (keep_heat_sources(), a temperature field):
    // 4 doubles a point, 74 B/DoF of the 3D plastic block's 3.75 KB
    // (doc/memory.md, session 22). Ẇirr stays: the audit's heat plastic work
    // reads it at commit in every scene.
    heat_sources          = PointData<double>();
    thermoelastic_sources = PointData<double>();
    if (heat_sources_kept)
      {
        heat_sources.reinit(triangulation, n_q, 0.);
        thermoelastic_sources.reinit(triangulation, n_q, 0.);
      }
    plastic_work_rates.reinit(triangulation, n_q, 0.);
    if (parameters.dynamic)
      node_masses.reinit(triangulation, formulation->n_nodes * formulation->n_nodes,
                         std::numeric_limits<double>::quiet_NaN());
    // The step-start table (F_n and F-bar's root per point, u_n per cell)
    // spares an update F_n's gradient and root: in 2D 3.5 % of the tube's
    // instructions for ~190 B/DoF; in 3D 0.7 % of the plastic block's for
    // 240 B/DoF (6 % of its peak, doc/memory.md session 21), so 3D forms
    // them at each update (the same operations: the same bits) and keeps
    // no table (material_point_update.cc reads an empty one as none).
    if (dim == 2)
      step_start.reinit(triangulation, fe.n_dofs_per_cell(), n_q);
    else
      step_start = MechanicsAssembly::StepStart();
    material_temperature = material_temperature_old = PointData<double>();
    if (temperature_field)
      {
        material_temperature.reinit(triangulation, n_q, parameters.temperature);
        material_temperature_old = material_temperature;
      }
    make_points(point_options);
  }

  template <int dim>
  void MechanicalProblem<dim>::set_temperature_field(const TemperatureField &field, const bool adiabatic)
  {
    temperature_field = field;
    adiabatic_split   = adiabatic;
    if (temperature_field && material_temperature.empty() && !points.empty())
      {
        material_temperature.reinit(triangulation, quadrature.size(), parameters.temperature);
        material_temperature_old = material_temperature;
      }
    if (adiabatic != point_options.adiabatic)
      make_points({adiabatic});
  }

  template <int dim>
  void MechanicalProblem<dim>::set_initial_point_temperatures(const std::vector<double> &T)
  {
    material_temperature.raw()     = T;
    material_temperature_old.raw() = T;
  }

  template <int dim>
  void MechanicalProblem<dim>::keep_heat_sources()
  {
    heat_sources_kept = true;
    if (heat_sources.empty() && !points.empty())
      {
        heat_sources.reinit(triangulation, quadrature.size(), 0.);
        thermoelastic_sources.reinit(triangulation, quadrature.size(), 0.);
      }
  }

  template <int dim>
  unsigned int MechanicalProblem<dim>::n_point_doubles() const
  {
    unsigned int n = 0;
    for (const auto *d : {&heat_sources, &thermoelastic_sources, &plastic_work_rates, &material_temperature,
                          &material_temperature_old})
      n += d->empty() ? 0 : 1;
    return n;
  }

  template <int dim>
  void MechanicalProblem<dim>::make_points(const PointOptions &options)
  {
    // One block of points per body (MaterialModel::create_points), handed
    // out in cell order.
    const unsigned int                        n_q = quadrature.size();
    std::map<types::material_id, std::size_t> count;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          if (materials.find(cell->material_id()) == materials.end())
            throw InputError("internal: no material for body id " +
                             std::to_string(cell->material_id()));
          count[cell->material_id()] += n_q;
        }
    std::map<types::material_id, PointBlock> made;
    for (const auto &[id, n] : count)
      made[id] = materials.find(id)->second->create_points(n, options);
    std::map<types::material_id, std::size_t> next;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->is_locally_owned())
        {
          std::size_t &k = next[cell->material_id()];
          for (unsigned int q = 0; q < n_q; ++q)
            {
              MaterialPoint *&point = points(cell, q);
              MaterialPoint  *fresh = made[cell->material_id()].points[k++];
              // The committed state of the point replaced (points made again
              // for other options, set_temperature_field()), unless it is
              // still the state of a new point (no stress, no plastic
              // strain: before the first step, where the coupling scheme
              // connects the temperatures): no save_state() vector per point.
              if (point && (point->committed_stress().norm() != 0 || point->stress().norm() != 0 ||
                            point->committed_equivalent_plastic_strain() != 0))
                fresh->load_state(point->save_state());
              point = fresh;
            }
        }
    point_blocks.clear(); // (the replaced points, after their state was read)
    for (auto &[id, block] : made)
      point_blocks.push_back(std::move(block.owner));
    point_options = options;
  }

#define INSTANTIATE(dim)                                                          \
  template void MechanicalProblem<dim>::setup_quadrature_point_data();           \
  template void MechanicalProblem<dim>::make_points(const PointOptions &);                 \
  template void MechanicalProblem<dim>::set_temperature_field(const MechanicalProblem<dim>::TemperatureField &, bool); \
  template void MechanicalProblem<dim>::set_initial_point_temperatures(const std::vector<double> &); \
  template void MechanicalProblem<dim>::keep_heat_sources();                            \
  template unsigned int MechanicalProblem<dim>::n_point_doubles() const;
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
