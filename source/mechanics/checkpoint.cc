// Checkpoint and restart of MechanicalProblem: vectors through deal.II's
// SolutionTransfer, material point states through data attached to the
// triangulation's cells, so a run can resume on any number of processes.
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
    // SolutionTransfer wants ghosted inputs.
    // One ghosted layout and one import for all of them (deal.II's operator=
    // from an owned vector builds an Epetra_Import per copy: ~9 M
    // instructions each on two processes of the contact strip).
    const auto targets = checkpoint_targets();
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
    std::vector<const TrilinosWrappers::MPI::Vector *> inputs;
    for (const auto &v : checkpoint_vectors)
      inputs.push_back(&v);
    checkpoint_transfer =
      std::make_unique<parallel::distributed::SolutionTransfer<dim, TrilinosWrappers::MPI::Vector>>(
        dof_handler);
    checkpoint_transfer->prepare_for_serialization(inputs);

    // Material points: per cell, n_q blocks of (size, values).
    const unsigned int n_q = quadrature.size();
    auto &tria = const_cast<parallel::DistributedTriangulationBase<dim> &>(triangulation);
    // A fully distributed triangulation (Geometry/Partition = per body) saves
    // only fixed-size data (deal.II 9.4): every cell's block is padded to the
    // largest one, which its sizes make self-describing on reading.
    const bool         fixed = !is_p4est(triangulation);
    std::size_t        padded = 0;
    if (fixed)
      {
        for (const auto &cell : triangulation.active_cell_iterators())
          if (cell->is_locally_owned())
            {
              std::size_t n = 2 * n_q;
              for (unsigned int q = 0; q < n_q; ++q)
                n += points(cell, q)->save_state().size();
              padded = std::max(padded, n);
            }
        padded = Utilities::MPI::max(padded, mpi_communicator);
      }
    checkpoint_handle = tria.register_data_attach(
      [this, n_q, padded](const typename Triangulation<dim>::cell_iterator &cell,
                          const typename Triangulation<dim>::CellStatus) {
        std::vector<double> data;
        for (unsigned int q = 0; q < n_q; ++q)
          {
            const auto state = points(cell, q)->save_state();
            data.push_back(state.size());
            data.insert(data.end(), state.begin(), state.end());
          }
        // The temperature each point ended its last step at (heat scenes).
        for (unsigned int q = 0; q < n_q; ++q)
          data.push_back(material_temperature_old(cell, q));
        data.resize(std::max(data.size(), padded), 0.);
        std::vector<char> bytes(data.size() * sizeof(double));
        std::memcpy(bytes.data(), data.data(), bytes.size());
        return bytes;
      },
      /*returns_variable_size_data=*/!fixed);
  }

  template <int dim>
  void MechanicalProblem<dim>::load_checkpoint()
  {
    const auto targets = checkpoint_targets();
    std::vector<TrilinosWrappers::MPI::Vector *> outputs(targets.begin(), targets.end());
    parallel::distributed::SolutionTransfer<dim, TrilinosWrappers::MPI::Vector> transfer(dof_handler);
    transfer.deserialize(outputs);

    const unsigned int n_q  = quadrature.size();
    auto              &tria = const_cast<parallel::DistributedTriangulationBase<dim> &>(triangulation);
    // Attached data sets are identified by the order of registration: the
    // SolutionTransfer registered first (at save and in deserialize()), ours
    // second, so registering again yields our handle.
    const unsigned int handle = tria.register_data_attach(
      [](const typename Triangulation<dim>::cell_iterator &,
         const typename Triangulation<dim>::CellStatus) { return std::vector<char>(); },
      /*returns_variable_size_data=*/is_p4est(triangulation));
    tria.notify_ready_to_unpack(
      handle,
      [this, n_q](const typename Triangulation<dim>::cell_iterator &cell,
                  const typename Triangulation<dim>::CellStatus,
                  const boost::iterator_range<std::vector<char>::const_iterator> &bytes) {
        std::vector<double> data(std::distance(bytes.begin(), bytes.end()) / sizeof(double));
        std::memcpy(data.data(), &*bytes.begin(), data.size() * sizeof(double));
        std::size_t k = 0;
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
