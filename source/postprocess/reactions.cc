#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe.h>

#include <anvil/postprocess/interface.h>

namespace anvil
{
  using namespace dealii;

  /**
   * reactions.csv: per named boundary, its displacement (the mean of its
   * nodes' displacements, mm) beside the force its support exerts on the body
   * (N; per mm of depth in plane strain) — a force-displacement curve with no
   * post-processing.
   */
  template <int dim>
  class Reactions : public Postprocessor<dim>
  {
  public:
    bool applies(const SceneContents<dim> &c) const override { return c.mechanics; }

    void start(const SimulationState<dim> &s, const bool append) override
    {
      std::vector<std::string> columns = {"step", "time [s]"};
      for (const auto &[name, id] : s.geometry.boundary_names())
        {
          for (unsigned int d = 0; d < dim; ++d)
            columns.push_back(name + "_u" + "xyz"[d] + " [mm]");
          for (unsigned int d = 0; d < dim; ++d)
            columns.push_back(name + "_F" + "xyz"[d] + " [N]");
        }
      csv.open(s.output_directory + "/reactions.csv", columns, s.is_root(), append, s.time);
    }

    void accepted(const SimulationState<dim> &s, const StepReport<dim> *) override
    {
      std::vector<double> row = {double(s.step), s.time};
      for (const auto &[name, id] : s.geometry.boundary_names())
        {
          const auto u = mean_displacement(*s.physics.mechanics(), id, s.communicator);
          const auto f = s.physics.mechanics()->reaction(id);
          for (unsigned int d = 0; d < dim; ++d)
            row.push_back(u[d]);
          for (unsigned int d = 0; d < dim; ++d)
            row.push_back(f[d]);
        }
      csv.add_row(row);
    }

  private:
    CsvHistory csv;

    // The mean over the boundary's nodes (each counted once, by its owner),
    // per component: exact for a face moved rigidly, the face's average
    // motion otherwise.
    static Tensor<1, dim> mean_displacement(const MechanicalProblem<dim> &m,
                                            const types::boundary_id id, const MPI_Comm comm)
    {
      const auto    &dofs   = m.get_dof_handler();
      const auto    &fe     = dofs.get_fe();
      const IndexSet owned  = dofs.locally_owned_dofs();
      const IndexSet on_boundary = DoFTools::extract_boundary_dofs(dofs, ComponentMask(), {id});
      Tensor<1, dim> sum, count;
      std::vector<types::global_dof_index> cell_dofs(fe.n_dofs_per_cell());
      std::vector<bool>                    seen(owned.n_elements(), false);
      for (const auto &cell : dofs.active_cell_iterators())
        if (cell->is_locally_owned() || cell->is_ghost())
          {
            cell->get_dof_indices(cell_dofs);
            for (unsigned int i = 0; i < cell_dofs.size(); ++i)
              {
                const auto g = cell_dofs[i];
                if (!owned.is_element(g) || !on_boundary.is_element(g) ||
                    seen[owned.index_within_set(g)])
                  continue;
                seen[owned.index_within_set(g)] = true;
                const unsigned int c = fe.system_to_component_index(i).first;
                sum[c] += m.displacement()(g);
                count[c] += 1;
              }
          }
      sum   = Utilities::MPI::sum(sum, comm);
      count = Utilities::MPI::sum(count, comm);
      Tensor<1, dim> mean;
      for (unsigned int d = 0; d < dim; ++d)
        mean[d] = count[d] > 0 ? sum[d] / count[d] : 0.;
      return mean;
    }
  };

  ANVIL_REGISTER_POSTPROCESSOR(Reactions, "reactions",
                               "reactions.csv: mean displacement (mm) and reaction force (N) of "
                               "every named boundary, per step.")
} // namespace anvil
