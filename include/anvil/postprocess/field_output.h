#pragma once

#include <deal.II/base/parameter_handler.h>

#include <anvil/postprocess/interface.h>

#include <string>
#include <utility>
#include <vector>

namespace anvil
{
  /**
   * What the field outputs (solution.pvd, contact.pvd) share: when to write
   * (Output/Field interval) and the .pvd record of the files written so far,
   * carried through checkpoints.
   */
  class FieldSchedule
  {
  public:
    static void declare_parameters(dealii::ParameterHandler &prm);
    void        parse_parameters(dealii::ParameterHandler &prm);

    /// Every Field interval steps, and always at t = 0 and at the end.
    template <int dim>
    bool due(const SimulationState<dim> &s) const
    {
      return s.step == 0 || s.last_step || (interval > 0 && s.step % interval == 0);
    }

    /// Adds a record (replacing one at the same time: a final write after a
    /// failure) and rewrites @p pvd on rank 0.
    void record(double time, const std::string &file, const std::string &pvd, bool root);

    /// Output/VTU encoding = raw: arrays appended raw (vtu_writer.h), else deal.II's zlib.
    bool raw_vtu() const { return raw; }
    /// Output/Field interval > 0: writes come on schedule through the run
    /// (else only at t = 0 and at the end).
    bool periodic() const { return interval > 0; }

    void save(const std::string &key, std::map<std::string, std::string> &entries) const;
    void load(const std::string &key, const std::map<std::string, std::string> &entries);

  private:
    unsigned int                                interval = 1;
    bool                                        raw      = true;
    std::vector<std::pair<double, std::string>> records;
  };

  /**
   * An output of fields on the schedule: written at t = 0, every Field
   * interval steps, at the end and, after an unrecoverable failure, with the
   * last converged state; its .pvd record (named @p key) goes through
   * checkpoints. A concrete output implements write().
   */
  template <int dim>
  class ScheduledFieldOutput : public Postprocessor<dim>
  {
  public:
    explicit ScheduledFieldOutput(const std::string &key)
      : key(key)
    {}
    void parse_parameters(dealii::ParameterHandler &prm, Scene &, const SceneContents<dim> &) override
    {
      schedule.parse_parameters(prm);
    }
    void accepted(const SimulationState<dim> &s, const StepReport<dim> *) override
    {
      if (schedule.due(s))
        write(s);
    }
    void finish(const SimulationState<dim> &s, const bool failed) override
    {
      if (failed)
        write(s);
    }
    void save(std::map<std::string, std::string> &entries) const override
    {
      schedule.save(key, entries);
    }
    void load(const std::map<std::string, std::string> &entries) override
    {
      schedule.load(key, entries);
    }

  protected:
    virtual void write(const SimulationState<dim> &s) = 0;
    FieldSchedule schedule;

  private:
    const std::string key;
  };
} // namespace anvil
