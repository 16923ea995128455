#include <anvil/postprocess/interface.h>

namespace anvil
{
  /// contact.csv and the contact section of summary.json, per pair: the
  /// force on the Slave body, normal and tangential totals, friction work,
  /// active and sliding nodes, largest penetration, heat exchanged and
  /// friction heat (seed eq. 27–33).
  template <int dim>
  class ContactHistory : public Postprocessor<dim>
  {
  public:
    bool applies(const SceneContents<dim> &c) const override { return !c.contact->empty(); }

    void start(const SimulationState<dim> &s, const bool append) override
    {
      std::vector<std::string> columns = {"step", "time [s]"};
      for (const auto &p : s.physics.contact_problem().get_pairs())
        {
          for (unsigned int d = 0; d < dim; ++d)
            columns.push_back(p.name + "_F" + "xyz"[d] + " [N]");
          for (const auto *c : {"_normal [N]", "_tangential [N]", "_friction_work [N mm]",
                                "_active_nodes", "_sliding_nodes", "_max_penetration [mm]",
                                "_heat_exchanged [mJ]", "_friction_heat [mJ]"})
            columns.push_back(p.name + c);
        }
      csv.open(s.output_directory + "/contact.csv", columns, s.is_root(), append, s.time);
    }

    void accepted(const SimulationState<dim> &s, const StepReport<dim> *) override
    {
      std::vector<double> row = {double(s.step), s.time};
      for (const auto &c : s.physics.contact_problem().totals())
        {
          for (unsigned int d = 0; d < dim; ++d)
            row.push_back(c.force[d]);
          row.insert(row.end(), {c.normal, c.tangential, c.friction_work, double(c.active),
                                 double(c.sliding), c.max_penetration, c.heat_exchanged,
                                 c.friction_heat});
        }
      csv.add_row(row);
    }

    void add_to_summary(const SimulationState<dim> &s, Summary &summary) const override
    {
      const auto &contact = s.physics.contact_problem();
      for (unsigned int k = 0; k < contact.get_pairs().size(); ++k)
        {
          const auto &c    = contact.totals()[k];
          const auto &name = contact.get_pairs()[k].name;
          summary.set("contact", name + "_normal", c.normal);
          summary.set("contact", name + "_tangential", c.tangential);
          summary.set("contact", name + "_friction_work", c.friction_work);
          summary.set("contact", name + "_max_penetration", c.max_penetration);
          summary.set("contact", name + "_heat_exchanged", c.heat_exchanged);
          summary.set("contact", name + "_friction_heat", c.friction_heat);
        }
      // How often the mechanics built its matrix pattern anew for the contact
      // couplings (the first included; doc/contact.md, "Pattern").
      summary.set("contact", "pattern_rebuilds", double(contact.pattern_rebuilds()));
    }

  private:
    CsvHistory csv;
  };

  ANVIL_REGISTER_POSTPROCESSOR(ContactHistory, "contact history",
                               "contact.csv: per pair force (N), normal and tangential totals, "
                               "friction work (N mm), active and sliding nodes, largest "
                               "penetration (mm), heat exchanged and friction heat (mJ).")
} // namespace anvil
