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
      Tensor<1, dim> sum, count;
      for (const auto &[g, c] : m.owned_boundary_dofs(id))
        {
          sum[c] += m.displacement()(g);
          count[c] += 1;
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
