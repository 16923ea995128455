#include <deal.II/numerics/data_out.h>

#include <anvil/postprocess/field_output.h>

namespace anvil
{
  using namespace dealii;

  /**
   * solution.pvd and fields/solution_*.pvtu: displacement (and velocity in
   * dynamics), temperature, the cell fields of the mechanics (stress,
   * von Mises, pressure, J, equivalent plastic strain), body and rank — what
   * a user opens in ParaView.
   */
  template <int dim>
  class Fields : public ScheduledFieldOutput<dim>
  {
  public:
    Fields()
      : ScheduledFieldOutput<dim>("fields.pvd")
    {}
    static void declare_parameters(ParameterHandler &prm) { FieldSchedule::declare_parameters(prm); }

  private:
    void write(const SimulationState<dim> &s) override
    {
      const auto  *mechanical = s.physics.mechanics();
      const auto  *thermal    = s.physics.heat();
      DataOut<dim> data_out;
      Vector<double> prescribed_temperature;
      if (mechanical)
        {
          data_out.attach_dof_handler(mechanical->get_dof_handler());
          std::vector<DataComponentInterpretation::DataComponentInterpretation> interpretation(
            dim, DataComponentInterpretation::component_is_part_of_vector);
          data_out.add_data_vector(mechanical->displacement(),
                                   std::vector<std::string>(dim, "displacement"),
                                   DataOut<dim>::type_dof_data, interpretation);
          if (mechanical->is_dynamic())
            data_out.add_data_vector(mechanical->velocity(),
                                     std::vector<std::string>(dim, "velocity"),
                                     DataOut<dim>::type_dof_data, interpretation);
          if (thermal)
            data_out.add_data_vector(thermal->get_dof_handler(), thermal->temperature(),
                                     "temperature");
          else if (s.physics.has_temperature())
            {
              prescribed_temperature = s.physics.cell_temperature();
              data_out.add_data_vector(prescribed_temperature, "temperature",
                                       DataOut<dim>::type_cell_data);
            }
          cell_fields = mechanical->cell_fields();
          for (unsigned int i = 0; i < cell_fields.names.size(); ++i)
            data_out.add_data_vector(cell_fields.values[i], cell_fields.names[i],
                                     DataOut<dim>::type_cell_data);
        }
      else
        {
          data_out.attach_dof_handler(thermal->get_dof_handler());
          data_out.add_data_vector(thermal->temperature(), "temperature");
        }
      Vector<float> rank(s.triangulation.n_active_cells());
      rank = Utilities::MPI::this_mpi_process(s.communicator);
      data_out.add_data_vector(rank, "rank", DataOut<dim>::type_cell_data);
      data_out.build_patches(mechanical ? mechanical->get_mapping() : thermal->get_mapping());
      // best_compression costs several seconds per write at 10⁵ cells.
      DataOutBase::VtkFlags flags;
      flags.compression_level = DataOutBase::VtkFlags::best_speed;
      data_out.set_flags(flags);
      const std::string name = data_out.write_vtu_with_pvtu_record(
        s.output_directory + "/fields/", "solution", s.step, s.communicator, 5);
      this->schedule.record(s.time, "fields/" + name, s.output_directory + "/solution.pvd", s.is_root());
    }

    typename MechanicalProblem<dim>::CellFields cell_fields; // alive while data_out writes
  };

  ANVIL_REGISTER_POSTPROCESSOR(Fields, "fields",
                               "solution.pvd: displacement, velocity, temperature, Cauchy "
                               "stress, von Mises, pressure, J, equivalent plastic strain, body, "
                               "rank (VTU, every Field interval steps).")
} // namespace anvil
