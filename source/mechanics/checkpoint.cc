// Checkpoint and restart of MechanicalProblem: vectors and material point
// states through data attached to the triangulation's cells, so a run can
// resume on any number of processes.
#include <deal.II/distributed/solution_transfer.h>

#include <Epetra_Import.h>

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
    // Ghosted copies of the vectors (a cell's dofs may be another process's),
    // one layout and one import for all of them (deal.II's operator= from an
    // owned vector builds an Epetra_Import per copy: ~9 M instructions each on
    // two processes of the contact strip).
    const auto targets = checkpoint_targets();
    checkpoint_transfer.reset();
    checkpoint_vectors.assign(1, TrilinosWrappers::MPI::Vector(locally_owned_dofs, locally_relevant_dofs,
                                                               mpi_communicator));
    checkpoint_vectors.resize(targets.size(), checkpoint_vectors[0]);
    const Epetra_BlockMap &source = targets[0]->trilinos_vector().Map();
    const Epetra_Import    import(checkpoint_vectors[0].trilinos_vector().Map(), source);
    for (unsigned int i = 0; i < targets.size(); ++i)
      if (targets[i]->trilinos_vector().Map().SameAs(source))
        {
          const int ierr =
            checkpoint_vectors[i].trilinos_vector().Import(targets[i]->trilinos_vector(), import, Insert);
          AssertThrow(ierr == 0, ExcMessage("prepare_checkpoint: Epetra import failed"));
        }
      else
        checkpoint_vectors[i] = *targets[i];

    // One block per owned cell (checkpoint format 3): the cell's dof values
    // of each vector in checkpoint_targets() order, per point (size, state),
    // the points' temperatures at the end of their last step (heat scenes).
    // Each state saved once; deal.II's SolutionTransfer packed nine vectors
    // of dealii::Vector through boost per cell (~18 k instructions a cell:
    // 569 M on one process of the contact strip). Packed when deal.II asks
    // for the cell, into the bytes it keeps: a whole-process buffer packed
    // first was the run's memory peak on the 3D plastic block with the
    // geometric preconditioner (doc/memory.md, session 20).
    struct Packer
    {
      std::vector<TrilinosWrappers::MPI::Vector> vectors;
      std::vector<types::global_dof_index>       dofs;
      std::vector<int>                           lids;
      std::vector<double>                        block;
    };
    auto packer     = std::make_shared<Packer>();
    packer->vectors = std::move(checkpoint_vectors);
    checkpoint_vectors.clear(); // held by the packer until the save: not through the run
    const unsigned int n_q = quadrature.size(), n_dofs = fe.n_dofs_per_cell();
    packer->dofs.resize(n_dofs);
    packer->lids.resize(n_dofs);
    const auto pack = [this, packer, n_q, n_dofs](const auto &tria_cell) -> const std::vector<double> & {
      const typename DoFHandler<dim>::active_cell_iterator cell(&triangulation, tria_cell->level(),
                                                                tria_cell->index(), &dof_handler);
      Packer                &p       = *packer;
      const Epetra_BlockMap &ghosted = p.vectors[0].trilinos_vector().Map();
      cell->get_dof_indices(p.dofs);
      for (unsigned int j = 0; j < n_dofs; ++j)
        p.lids[j] = ghosted.LID(static_cast<TrilinosWrappers::types::int_type>(p.dofs[j]));
      p.block.clear();
      for (const auto &v : p.vectors)
        {
          const double *const values = v.trilinos_vector()[0];
          for (unsigned int j = 0; j < n_dofs; ++j)
            p.block.push_back(values[p.lids[j]]);
        }
      for (unsigned int q = 0; q < n_q; ++q)
        {
          const auto state = points(cell, q)->save_state();
          p.block.push_back(state.size());
          p.block.insert(p.block.end(), state.begin(), state.end());
        }
      for (unsigned int q = 0; q < n_q; ++q)
        p.block.push_back(material_temperature_old(cell, q));
      return p.block;
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
    tria.notify_ready_to_unpack(
      handle,
      [&, n_q, n_dofs](const typename Triangulation<dim>::cell_iterator &cell,
                       const typename Triangulation<dim>::CellStatus,
                       const boost::iterator_range<std::vector<char>::const_iterator> &bytes) {
        std::vector<double> data(std::distance(bytes.begin(), bytes.end()) / sizeof(double));
        std::memcpy(data.data(), &*bytes.begin(), data.size() * sizeof(double));
        AssertThrow(data.size() >= targets.size() * n_dofs, ExcMessage("checkpoint: a cell's block is short"));
        // The owned dofs of the owned cells: every owned dof is on one of them.
        typename DoFHandler<dim>::active_cell_iterator(&triangulation, cell->level(), cell->index(), &dof_handler)
          ->get_dof_indices(dofs);
        std::size_t k = 0;
        for (auto *v : targets)
          {
            const Epetra_BlockMap &map    = v->trilinos_vector().Map();
            double *const          values = v->trilinos_vector()[0];
            for (unsigned int j = 0; j < n_dofs; ++j, ++k)
              {
                const int lid = map.LID(static_cast<TrilinosWrappers::types::int_type>(dofs[j]));
                if (lid >= 0)
                  values[lid] = data[k];
              }
          }
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const std::size_t   size = static_cast<std::size_t>(data.at(k++));
            std::vector<double> state(data.begin() + k, data.begin() + k + size);
            k += size;
            points(cell, q)->load_state(state);
          }
        for (unsigned int q = 0; q < n_q; ++q)
          material_temperature_old(cell, q) = material_temperature(cell, q) = data.at(k++);
      });

    owned_solution           = owned_old_solution;
    solution                 = owned_solution;
    old_solution             = owned_solution;
    velocity_old_ghosted     = velocity_old;
    velocity_ghosted         = velocity_old;
    acceleration_old_ghosted = acceleration_old;
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
