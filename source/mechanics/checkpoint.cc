// Checkpoint and restart of MechanicalProblem: vectors and material point
// states through data attached to the triangulation's cells, so a run can
// resume on any number of processes.
#include <deal.II/distributed/solution_transfer.h>


#include <anvil/core/instantiate.h>
#include <anvil/mechanics/mechanical_problem.h>

#include <algorithm>
#include <cstring>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    template <int dim>
    bool is_p4est(const parallel::DistributedTriangulationBase<dim> &triangulation)
    {
      return dynamic_cast<const parallel::distributed::Triangulation<dim> *>(&triangulation) != nullptr;
    }

    // A block's mask bit: no per-point temperatures follow the states (a
    // scene without a temperature field keeps none, point_setup.cc). Set,
    // not cleared, for their absence: format 4 as written before carries
    // them always, and reads the same.
    constexpr unsigned int no_point_temperatures = 1u << 30;
  } // namespace

  template <int dim>
  std::vector<TrilinosWrappers::MPI::Vector *> MechanicalProblem<dim>::checkpoint_targets()
  {
    return {&owned_old_solution, &velocity_old,       &acceleration_old,  &previous_increment,
            &internal_force_old, &external_force_old, &reaction_force_old, &static_residual_old,
            &contact_force_old};
  }

  template <int dim>
  void MechanicalProblem<dim>::prepare_checkpoint()
  {
    // One block per owned cell (checkpoint format 4):
    //   the mask of the vectors of checkpoint_targets() saved (those not zero
    //   everywhere: a quasi-static scene's velocity, acceleration and contact
    //   force are not), the number c of the cell's dofs it carries and their
    //   positions in the cell, the carried values of each saved vector, then
    //   per point (size, state) and the points' temperatures at the end of
    //   their last step (scenes with a temperature field; without, the
    //   mask's no_point_temperatures bit).
    // Each owned dof is carried by one cell of its owner (the first in active
    // order), not by every cell around it: format 3 saved each vertex's values
    // eight times (3D Q1), 9 × 24 doubles a cell, most of the checkpoint, and
    // deal.II holds the blocks twice while it saves (the cells' pieces and the
    // process's buffer): that was the run's memory peak on the 3D plastic
    // block (doc/memory.md, session 21). The values are read from the owned
    // vectors in place, without ghosted copies.
    const auto targets = checkpoint_targets();
    checkpoint_transfer.reset();
    checkpoint_vectors.clear();
    unsigned int mask = material_temperature_old.empty() ? no_point_temperatures : 0;
    for (unsigned int i = 0; i < targets.size(); ++i)
      if (targets[i]->size() > 0 && targets[i]->linfty_norm() > 0)
        mask |= 1u << i;
    struct Carried
    {
      std::vector<unsigned int>              start; // per active cell index, into positions
      std::vector<unsigned short>            positions;
      std::vector<types::global_dof_index>   dofs;
      std::vector<double>                    block;
    };
    auto carried = std::make_shared<Carried>();
    {
      std::vector<bool> taken(locally_owned_dofs.n_elements(), false);
      std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
      carried->start.assign(triangulation.n_active_cells() + 1, 0);
      for (const auto &cell : dof_handler.active_cell_iterators())
        {
          const unsigned int index = cell->active_cell_index();
          if (cell->is_locally_owned())
            {
              cell->get_dof_indices(dofs);
              for (unsigned int j = 0; j < dofs.size(); ++j)
                if (locally_owned_dofs.is_element(dofs[j]))
                  {
                    const auto k = locally_owned_dofs.index_within_set(dofs[j]);
                    if (!taken[k])
                      {
                        taken[k] = true;
                        carried->positions.push_back(j);
                      }
                  }
            }
          carried->start[index + 1] = carried->positions.size();
        }
    }
    const unsigned int n_q = quadrature.size(), n_dofs = fe.n_dofs_per_cell();
    carried->dofs.resize(n_dofs);
    const auto pack = [this, carried, targets, mask, n_q](const auto &tria_cell) -> const std::vector<double> & {
      const typename DoFHandler<dim>::active_cell_iterator cell(&triangulation, tria_cell->level(),
                                                                tria_cell->index(), &dof_handler);
      Carried           &c     = *carried;
      const unsigned int index = cell->active_cell_index();
      cell->get_dof_indices(c.dofs);
      c.block.clear();
      c.block.push_back(mask);
      c.block.push_back(c.start[index + 1] - c.start[index]);
      for (unsigned int k = c.start[index]; k < c.start[index + 1]; ++k)
        c.block.push_back(c.positions[k]);
      for (unsigned int i = 0; i < targets.size(); ++i)
        if (mask & (1u << i))
          {
            const Epetra_BlockMap &map    = targets[i]->trilinos_vector().Map();
            const double *const    values = targets[i]->trilinos_vector()[0];
            for (unsigned int k = c.start[index]; k < c.start[index + 1]; ++k)
              c.block.push_back(
                values[map.LID(static_cast<TrilinosWrappers::types::int_type>(c.dofs[c.positions[k]]))]);
          }
      for (unsigned int q = 0; q < n_q; ++q)
        {
          const auto state = points(cell, q)->save_state();
          c.block.push_back(state.size());
          c.block.insert(c.block.end(), state.begin(), state.end());
        }
      if (!(mask & no_point_temperatures))
        for (unsigned int q = 0; q < n_q; ++q)
          c.block.push_back(material_temperature_old(cell, q));
      return c.block;
    };
    // A fully distributed triangulation (Geometry/Partition = per body) saves
    // only fixed-size data (deal.II 9.4): every cell's block is padded to the
    // longest one, which its sizes make self-describing on reading.
    auto &tria  = const_cast<parallel::DistributedTriangulationBase<dim> &>(triangulation);
    const bool fixed = !is_p4est(triangulation);
    std::size_t longest = 0;
    if (fixed)
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->is_locally_owned())
          longest = std::max(longest, pack(cell).size());
    const std::size_t padded = fixed ? Utilities::MPI::max(longest, mpi_communicator) : 0;
    checkpoint_handle = tria.register_data_attach(
      [pack, padded](const typename Triangulation<dim>::cell_iterator &cell,
                     const typename Triangulation<dim>::CellStatus) {
        const std::vector<double> &block = pack(cell);
        std::vector<char>          bytes(std::max(block.size(), padded) * sizeof(double), 0);
        std::memcpy(bytes.data(), block.data(), block.size() * sizeof(double));
        return bytes;
      },
      /*returns_variable_size_data=*/!fixed);
  }

  template <int dim>
  void MechanicalProblem<dim>::load_checkpoint()
  {
    const auto         targets = checkpoint_targets();
    const unsigned int n_q = quadrature.size(), n_dofs = fe.n_dofs_per_cell();
    auto              &tria = const_cast<parallel::DistributedTriangulationBase<dim> &>(triangulation);
    // Attached data sets are identified by the order of registration: ours
    // is the first (the heat's follows), so registering again yields its handle.
    const unsigned int handle = tria.register_data_attach(
      [](const typename Triangulation<dim>::cell_iterator &,
         const typename Triangulation<dim>::CellStatus) { return std::vector<char>(); },
      /*returns_variable_size_data=*/is_p4est(triangulation));
    std::vector<types::global_dof_index> dofs(n_dofs);
    // A carried dof whose owner is now another process (restart on another
    // partition): sent to it by the vector's compress(insert) below.
    std::vector<std::vector<types::global_dof_index>> remote_dofs(targets.size());
    std::vector<std::vector<double>>                  remote_values(targets.size());
    unsigned int                                      mask = 0;
    tria.notify_ready_to_unpack(
      handle,
      [&, n_q](const typename Triangulation<dim>::cell_iterator &cell,
               const typename Triangulation<dim>::CellStatus,
               const boost::iterator_range<std::vector<char>::const_iterator> &bytes) {
        std::vector<double> data(std::distance(bytes.begin(), bytes.end()) / sizeof(double));
        std::memcpy(data.data(), &*bytes.begin(), data.size() * sizeof(double));
        AssertThrow(data.size() >= 2, ExcMessage("checkpoint: a cell's block is short"));
        typename DoFHandler<dim>::active_cell_iterator(&triangulation, cell->level(), cell->index(), &dof_handler)
          ->get_dof_indices(dofs);
        mask                       = static_cast<unsigned int>(data[0]);
        const std::size_t n_carried = static_cast<std::size_t>(data[1]);
        std::size_t       k         = 2 + n_carried;
        AssertThrow(data.size() >= k, ExcMessage("checkpoint: a cell's block is short"));
        for (unsigned int i = 0; i < targets.size(); ++i)
          if (mask & (1u << i))
            {
              const Epetra_BlockMap &map    = targets[i]->trilinos_vector().Map();
              double *const          values = targets[i]->trilinos_vector()[0];
              for (std::size_t c = 0; c < n_carried; ++c, ++k)
                {
                  const auto dof = dofs.at(static_cast<unsigned int>(data[2 + c]));
                  const int  lid = map.LID(static_cast<TrilinosWrappers::types::int_type>(dof));
                  if (lid >= 0)
                    values[lid] = data.at(k);
                  else
                    {
                      remote_dofs[i].push_back(dof);
                      remote_values[i].push_back(data.at(k));
                    }
                }
            }
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const std::size_t   size = static_cast<std::size_t>(data.at(k++));
            AssertThrow(k + size <= data.size(), ExcMessage("checkpoint: a cell's block is short"));
            std::vector<double> state(data.begin() + k, data.begin() + k + size);
            k += size;
            points(cell, q)->load_state(state);
          }
        // Format 4 as session 21 wrote it carries them in every scene: read
        // where this scene keeps them (its coupling is the checkpoint's).
        if (!(mask & no_point_temperatures) && !material_temperature.empty())
          for (unsigned int q = 0; q < n_q; ++q)
            material_temperature_old(cell, q) = material_temperature(cell, q) = data.at(k++);
      });
    // A process without cells has read no mask.
    mask = Utilities::MPI::max(mask, mpi_communicator);
    AssertThrow(!(mask & no_point_temperatures) || material_temperature.empty(),
                ExcMessage("checkpoint: the points' temperatures were not saved, but this scene "
                           "has a temperature field"));
    for (unsigned int i = 0; i < targets.size(); ++i)
      if (mask & (1u << i))
        {
          targets[i]->set(remote_dofs[i], remote_values[i]);
          targets[i]->compress(VectorOperation::insert);
        }
      else if (targets[i]->size() > 0)
        *targets[i] = 0;

    owned_solution           = owned_old_solution;
    solution                 = owned_solution;
    old_solution             = owned_solution;
    if (parameters.dynamic)
      {
        velocity_old_ghosted     = velocity_old;
        velocity_ghosted         = velocity_old;
        acceleration_old_ghosted = acceleration_old;
      }
  }

  template <int dim>
  NamedValues MechanicalProblem<dim>::checkpoint_scalars() const
  {
    const Energy &e = energy_audit;
    return {{"external_work", e.external_work},
            {"internal_work", e.internal_work},
            {"contact_work", e.contact_work},
            {"stress_work", e.stress_work},
            {"kinetic_energy", e.kinetic},
            {"initial_kinetic_energy", e.initial_kinetic},
            {"plastic_work", e.plastic_work},
            {"flow_plastic_work", e.flow_plastic_work},
            {"elastic_energy", e.elastic_energy},
            {"initial_elastic_energy", e.initial_elastic_energy},
            {"thermal_work", e.thermal_work},
            {"hypoelastic_volume_work", e.hypoelastic_volume_work},
            {"f_bar_work", e.f_bar_work},
            {"algorithmic_dissipation", e.algorithmic_dissipation},
            {"previous_time_step", previous_time_step}};
  }

  template <int dim>
  void MechanicalProblem<dim>::restore_scalars(const NamedValues &v)
  {
    Energy &e          = energy_audit;
    e.external_work    = named_value(v, "external_work");
    e.internal_work    = named_value(v, "internal_work");
    e.stress_work      = named_value(v, "stress_work");
    e.kinetic          = named_value(v, "kinetic_energy");
    e.initial_kinetic  = named_value(v, "initial_kinetic_energy");
    e.plastic_work     = named_value(v, "plastic_work");
    e.elastic_energy   = named_value(v, "elastic_energy");
    e.contact_work     = named_value(v, "contact_work");
    e.flow_plastic_work       = named_value(v, "flow_plastic_work");
    e.initial_elastic_energy  = named_value(v, "initial_elastic_energy");
    e.thermal_work            = named_value(v, "thermal_work");
    e.hypoelastic_volume_work = named_value(v, "hypoelastic_volume_work");
    e.f_bar_work              = named_value(v, "f_bar_work");
    e.algorithmic_dissipation = named_value(v, "algorithmic_dissipation");
    previous_time_step = named_value(v, "previous_time_step");
  }

  ANVIL_INSTANTIATE_CLASS(MechanicalProblem)
} // namespace anvil
