#include <deal.II/base/mpi.h>
#include <deal.II/fe/mapping_q1.h>
#include <deal.II/grid/grid_tools.h>

#include <anvil/core/scene.h>
#include <anvil/postprocess/interface.h>
#include <anvil/postprocess/probe_points.h>

#include <cmath>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  template <int dim>
  std::vector<ProbePoint<dim>> parse_probe_points(const std::string &text, const Scene &scene)
  {
    std::vector<ProbePoint<dim>> probes;
    for (const auto &item : split_outside_parentheses(text, ';'))
      {
        if (item.empty())
          continue;
        const auto               colon = item.find(':');
        ProbePoint<dim>          p;
        std::vector<std::string> coords;
        if (colon != std::string::npos)
          {
            p.name = trim(item.substr(0, colon));
            coords = split_outside_parentheses(item.substr(colon + 1), ',');
          }
        if (p.name.empty() || coords.size() != dim)
          scene.fail("Output/Probes", "item '" + item + "': expected 'name: " +
                                        (dim == 2 ? "x, y'" : "x, y, z'") + " in mm");
        for (unsigned int d = 0; d < dim; ++d)
          try
            {
              std::size_t used = 0;
              p.point[d]       = std::stod(coords[d], &used);
              if (used != coords[d].size())
                throw std::invalid_argument("");
            }
          catch (...)
            {
              scene.fail("Output/Probes", "item '" + item + "': '" + coords[d] + "' is not a number");
            }
        for (unsigned int d = 0; d < dim; ++d)
          if (!std::isfinite(p.point[d]))
            scene.fail("Output/Probes", "item '" + item + "': '" + coords[d] +
                                          "' is not a finite number");
        for (const auto &other : probes)
          if (other.name == p.name)
            scene.fail("Output/Probes", "names the probe '" + p.name +
                                          "' twice: expected distinct names (they name the "
                                          "columns of probes.csv)");
        probes.push_back(p);
      }
    return probes;
  }

  /// probes.csv: displacement, stress (cell average), equivalent plastic
  /// strain and temperature at the scene's named points, per step.
  template <int dim>
  class Probes : public Postprocessor<dim>
  {
  public:
    static void declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Probes", "", Patterns::Anything(),
                        "Named points of the reference configuration, mm: "
                        "'name: x, y[, z]; name2: ...'. Their displacement and stress are "
                        "written to probes.csv.");
    }
    void parse_parameters(ParameterHandler &prm, Scene &scene, const SceneContents<dim> &) override
    {
      probes = parse_probe_points<dim>(prm.get({"Output"}, "Probes"), scene);
    }
    bool applies(const SceneContents<dim> &) const override { return !probes.empty(); }

    // A probe outside every body would report zeros for the whole run.
    void check(const SimulationState<dim> &s) override
    {
      const MappingQ1<dim> mapping;
      for (const auto &p : probes)
        {
          unsigned int found = 0;
          try
            {
              const auto c =
                GridTools::find_active_cell_around_point(mapping, static_cast<const Triangulation<dim> &>(s.triangulation), p.point);
              found = c.first.state() == IteratorState::valid && !c.first->is_artificial();
            }
          catch (...)
            {
              // not in this process's part of the mesh
            }
          if (Utilities::MPI::sum(found, s.communicator) == 0)
            {
              std::ostringstream at;
              at << p.point;
              s.scene.fail("Output/Probes", "puts the probe '" + p.name + "' at (" + at.str() +
                                              "), outside the mesh: expected a point of a body "
                                              "(reference configuration, mm)");
            }
        }
    }

    void start(const SimulationState<dim> &s, const bool append) override
    {
      std::vector<std::string> columns = {"step", "time [s]"};
      for (const auto &p : probes)
        {
          if (s.physics.mechanics())
            {
              for (unsigned int d = 0; d < dim; ++d)
                columns.push_back(p.name + "_u" + "xyz"[d] + " [mm]");
              for (const auto *c : {"xx", "yy", "zz", "xy", "yz", "xz"})
                columns.push_back(p.name + "_stress_" + c + " [MPa]");
              columns.push_back(p.name + "_equivalent_plastic_strain [-]");
            }
          if (s.physics.heat())
            columns.push_back(p.name + "_temperature [K]");
        }
      csv.open(s.output_directory + "/probes.csv", columns, s.is_root(), append, s.time);
    }

    void accepted(const SimulationState<dim> &s, const StepReport<dim> *) override
    {
      std::vector<double> row = {double(s.step), s.time};
      for (const auto &p : probes)
        {
          if (const auto *m = s.physics.mechanics())
            {
              Tensor<1, dim>        u;
              SymmetricTensor<2, 3> t;
              double                eqps = 0;
              m->probe(p.point, u, t, eqps);
              for (unsigned int d = 0; d < dim; ++d)
                row.push_back(u[d]);
              row.insert(row.end(), {t[0][0], t[1][1], t[2][2], t[0][1], t[1][2], t[0][2], eqps});
            }
          if (const auto *h = s.physics.heat())
            row.push_back(h->temperature_at(p.point));
        }
      csv.add_row(row);
    }

  private:
    std::vector<ProbePoint<dim>> probes;
    CsvHistory                   csv;
  };

  ANVIL_REGISTER_POSTPROCESSOR(Probes, "probes",
                               "probes.csv: displacement (mm), stress (MPa), equivalent plastic "
                               "strain and temperature (K) at the named points.")

#define INSTANTIATE(dim)                                                                           \
  template std::vector<ProbePoint<dim>> parse_probe_points<dim>(const std::string &, const Scene &);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
