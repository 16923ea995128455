#include <deal.II/base/mpi.h>

#include <anvil/core/gather.h>
#include <anvil/postprocess/field_output.h>
#include <anvil/postprocess/vtu_writer.h>

#include <fstream>
#include <iomanip>

namespace anvil
{
  using namespace dealii;

  /**
   * contact.pvd and fields/contact_*.vtu: the slave nodes of every pair as a
   * point cloud with contact pressure, gap, slip, status, frictional power,
   * conductance, heat flux and pair index, written with the solution fields.
   */
  template <int dim>
  class ContactFields : public ScheduledFieldOutput<dim>
  {
  public:
    ContactFields()
      : ScheduledFieldOutput<dim>("contact.pvd")
    {}
    bool applies(const SceneContents<dim> &c) const override { return !c.contact->empty(); }

  private:
    static constexpr unsigned int n_fields = 8;

    void write(const SimulationState<dim> &s) override
    {
      std::vector<double> local;
      for (const auto &o : s.physics.contact_problem().node_outputs())
        {
          for (unsigned int d = 0; d < 3; ++d)
            local.push_back(d < dim ? o.position[d] : 0.);
          local.insert(local.end(), {o.pressure, o.gap, o.slip, double(o.status),
                                     o.friction_power, o.conductance, o.heat_flux, double(o.pair)});
        }
      const std::string name = "contact_" + Utilities::int_to_string(s.step, 5) + ".vtu";
      const auto parts = gather_doubles(s.communicator, local); // no packing; none on one process
      if (s.is_root())
        {
          std::vector<double> all;
          for (const auto &part : parts)
            all.insert(all.end(), part.begin(), part.end());
          write_vtu(s.output_directory + "/fields/" + name, all, this->schedule.raw_vtu());
        }
      this->schedule.record(s.time, "fields/" + name, s.output_directory + "/contact.pvd", s.is_root());
    }

    static void write_vtu(const std::string &filename, const std::vector<double> &all,
                          const bool raw)
    {
      const unsigned int width = 3 + n_fields, n = all.size() / width;
      const char *names[n_fields] = {"contact_pressure", "gap", "slip", "status",
                                     "frictional_power", "conductance", "contact_heat_flux",
                                     "pair"};
      if (raw)
        {
          // Float64 like the ascii file's 10 digits (a gap of 1e-6 mm matters).
          BasicVtuPiece<double> piece;
          piece.point_data.resize(n_fields);
          for (unsigned int f = 0; f < n_fields; ++f)
            piece.point_data[f].name = names[f];
          for (unsigned int i = 0; i < n; ++i)
            {
              piece.points.insert(piece.points.end(), &all[i * width], &all[i * width + 3]);
              for (unsigned int f = 0; f < n_fields; ++f)
                piece.point_data[f].values.push_back(all[i * width + 3 + f]);
              piece.connectivity.push_back(static_cast<std::int32_t>(i));
              piece.offsets.push_back(static_cast<std::int32_t>(i + 1));
              piece.types.push_back(1); // VTK_VERTEX
            }
          write_vtu_raw(piece, filename);
          return;
        }
      std::ofstream vtu(filename);
      vtu << std::setprecision(10)
          << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n"
          << "<UnstructuredGrid><Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n
          << "\">\n"
          << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
      for (unsigned int i = 0; i < n; ++i)
        vtu << all[i * width] << ' ' << all[i * width + 1] << ' ' << all[i * width + 2] << '\n';
      vtu << "</DataArray></Points>\n<Cells>\n"
          << "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
      for (unsigned int i = 0; i < n; ++i)
        vtu << i << ' ';
      vtu << "\n</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
      for (unsigned int i = 0; i < n; ++i)
        vtu << i + 1 << ' ';
      vtu << "\n</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
      for (unsigned int i = 0; i < n; ++i)
        vtu << "1 "; // VTK_VERTEX
      vtu << "\n</DataArray>\n</Cells>\n<PointData>\n";
      for (unsigned int f = 0; f < n_fields; ++f)
        {
          vtu << "<DataArray type=\"Float64\" Name=\"" << names[f] << "\" format=\"ascii\">\n";
          for (unsigned int i = 0; i < n; ++i)
            vtu << all[i * width + 3 + f] << ' ';
          vtu << "\n</DataArray>\n";
        }
      vtu << "</PointData>\n</Piece></UnstructuredGrid>\n</VTKFile>\n";
    }

  };

  ANVIL_REGISTER_POSTPROCESSOR(ContactFields, "contact fields",
                               "contact.pvd: slave nodes with contact pressure (MPa), gap, slip "
                               "(mm), status, frictional power (mW), conductance, heat flux.")
} // namespace anvil
