#include <anvil/postprocess/interface.h>

namespace anvil
{
  /**
   * energy.csv and the energy and heat-balance sections of summary.json:
   * the mechanical audit's two balances (doc/energy_audit.md): the work of
   * loads, supports and contact against kinetic energy and stress work
   * (balance_error; in dynamics with generalized-α's algorithmic dissipation,
   * its own column), and the stress work against elastic energy, plastic,
   * thermal, hypoelastic-volume and F-bar work (stress_balance_error); and, for a heat equation
   * integrated in time (a steady one: steady_heat.cc), the heat audit (content, its change,
   * heat through boundaries, sources, plastic, thermoelastic and contact
   * heat, and the balance error — computed from independent sums, so it is
   * not zero by construction).
   */
  template <int dim>
  class Energy : public Postprocessor<dim>
  {
  public:
    void start(const SimulationState<dim> &s, const bool append) override
    {
      // Works in N mm, heat in mJ (the same unit; per mm of depth in plane strain).
      std::vector<std::string> columns = {"step", "time [s]"};
      if (s.physics.mechanics())
        columns.insert(columns.end(),
                       {"external_work [N mm]", "internal_work [N mm]", "kinetic_energy [N mm]",
                        "plastic_work [N mm]", "elastic_energy [N mm]", "stress_work [N mm]",
                        "balance_error [-]", "contact_work [N mm]", "flow_plastic_work [N mm]",
                        "thermal_work [N mm]", "hypoelastic_volume_work [N mm]",
                        "f_bar_work [N mm]", "stress_balance_error [-]"});
      // Only a dynamic scene has a scheme that dissipates (generalized-α, ρ∞ < 1).
      if (s.physics.mechanics() && s.physics.mechanics()->is_dynamic())
        columns.emplace_back("algorithmic_dissipation [N mm]");
      if (s.physics.transient_heat())
        columns.insert(columns.end(),
                       {"heat_content [mJ]", "heat_content_change [mJ]", "boundary_heat_in [mJ]",
                        "source_heat [mJ]", "plastic_heat [mJ]", "thermoelastic_heat [mJ]",
                        "contact_heat [mJ]", "heat_balance_error [mJ]"});
      csv.open(s.output_directory + "/energy.csv", columns, s.is_root(), append, s.time);
    }

    void accepted(const SimulationState<dim> &s, const StepReport<dim> *) override
    {
      std::vector<double> row = {double(s.step), s.time};
      if (const auto *m = s.physics.mechanics())
        {
          const auto &e = m->energy();
          row.insert(row.end(), {e.external_work, e.internal_work, e.kinetic, e.plastic_work,
                                 e.elastic_energy, e.stress_work, e.balance_error(),
                                 e.contact_work, e.flow_plastic_work, e.thermal_work,
                                 e.hypoelastic_volume_work,
                                 e.f_bar_work, e.stress_balance_error()});
          if (m->is_dynamic())
            row.push_back(e.algorithmic_dissipation);
        }
      if (s.physics.transient_heat())
        {
          const auto b = s.physics.heat_balance();
          row.insert(row.end(), {b.content, b.change, b.boundary, b.source, b.plastic,
                                 b.thermoelastic, b.contact, b.error});
        }
      csv.add_row(row);
    }

    void add_to_summary(const SimulationState<dim> &s, Summary &summary) const override
    {
      if (const auto *m = s.physics.mechanics())
        {
          const auto &e = m->energy();
          summary.set("energy", "external_work", e.external_work);
          summary.set("energy", "internal_work", e.internal_work);
          summary.set("energy", "kinetic_energy", e.kinetic);
          summary.set("energy", "initial_kinetic_energy", e.initial_kinetic);
          summary.set("energy", "plastic_work", e.plastic_work);
          summary.set("energy", "elastic_energy", e.elastic_energy);
          summary.set("energy", "stress_work", e.stress_work);
          summary.set("energy", "balance_error", e.balance_error());
          summary.set("energy", "contact_work", e.contact_work);
          summary.set("energy", "flow_plastic_work", e.flow_plastic_work);
          summary.set("energy", "thermal_work", e.thermal_work);
          summary.set("energy", "hypoelastic_volume_work", e.hypoelastic_volume_work);
          summary.set("energy", "f_bar_work", e.f_bar_work);
          summary.set("energy", "stress_balance_error", e.stress_balance_error());
          if (m->is_dynamic())
            summary.set("energy", "algorithmic_dissipation", e.algorithmic_dissipation);
        }
      if (s.physics.transient_heat())
        {
          const auto b = s.physics.heat_balance();
          summary.set("heat", "heat_content", b.content);
          summary.set("heat", "heat_content_change", b.change);
          summary.set("heat", "boundary_heat_in", b.boundary);
          summary.set("heat", "source_heat", b.source);
          summary.set("heat", "plastic_heat", b.plastic);
          summary.set("heat", "thermoelastic_heat", b.thermoelastic);
          summary.set("heat", "contact_heat", b.contact);
          summary.set("heat", "balance_error", b.error);
        }
    }

  private:
    CsvHistory csv;
  };

  ANVIL_REGISTER_POSTPROCESSOR(Energy, "energy",
                               "energy.csv: work, kinetic, plastic and elastic energy and the "
                               "two balances of the energy audit (N mm); with heat, the heat "
                               "balance (mJ).")
} // namespace anvil
