#include <deal.II/base/data_out_base.h>

#include <anvil/core/input_error.h>
#include <anvil/postprocess/field_output.h>

#include <fstream>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  void FieldSchedule::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Field interval", "1", Patterns::Integer(0),
                      "Write VTU fields every this many steps (0: only the first and last).");
    prm.declare_entry("VTU encoding", "raw", Patterns::Selection("raw|zlib"),
                      "How the solution fields' VTU files hold their arrays: raw (appended "
                      "binary, written at memory speed one array at a time, files about 3 times "
                      "larger than zlib's) or zlib (deal.II's compressed base64, smaller files; it "
                      "builds every patch of the write at once: more memory). ParaView "
                      "and VTK read both.");
  }

  void FieldSchedule::parse_parameters(ParameterHandler &prm)
  {
    interval = prm.get_integer({"Output"}, "Field interval");
    raw      = prm.get({"Output"}, "VTU encoding") == "raw";
  }

  void FieldSchedule::record(const double time, const std::string &file, const std::string &pvd,
                             const bool root)
  {
    if (!records.empty() && records.back().first == time)
      records.pop_back();
    records.emplace_back(time, file);
    if (root)
      {
        std::ofstream out(pvd);
        DataOutBase::write_pvd_record(out, records);
      }
  }

  void FieldSchedule::save(const std::string &key, std::map<std::string, std::string> &entries) const
  {
    std::ostringstream out;
    out.precision(17);
    out << records.size();
    for (const auto &[time, name] : records)
      out << ' ' << time << ' ' << name;
    entries[key] = out.str();
  }

  void FieldSchedule::load(const std::string &key, const std::map<std::string, std::string> &entries)
  {
    const auto it = entries.find(key);
    records.clear();
    if (it == entries.end())
      return;
    std::istringstream in(it->second);
    std::size_t        n = 0;
    in >> n;
    if (!in || n > it->second.size())
      throw InputError("the checkpoint entry '" + key + "' is damaged (" + std::to_string(n) +
                       " records in " + std::to_string(it->second.size()) + " characters)");
    records.resize(n);
    for (auto &[time, name] : records)
      in >> time >> name;
    if (!in)
      throw InputError("the checkpoint entry '" + key + "' is truncated");
  }
} // namespace anvil
