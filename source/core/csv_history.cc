#include <anvil/core/csv_history.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace anvil
{
  void CsvHistory::open(const std::string &filename, const std::vector<std::string> &columns,
                        const bool write, const bool append)
  {
    n_columns = columns.size();
    if (!write)
      return;
    // Continue a history (restart) only if there is one: a restart into
    // another directory starts its files with their header.
    if (append && std::ifstream(filename).good())
      {
        file.open(filename, std::ios::app);
        return;
      }
    file.open(filename);
    for (std::size_t i = 0; i < columns.size(); ++i)
      file << (i ? "," : "") << columns[i];
    file << '\n' << std::flush;
  }

  void CsvHistory::add_row(const std::vector<double> &values)
  {
    if (!file.is_open())
      return;
    file << std::setprecision(12);
    for (std::size_t i = 0; i < values.size(); ++i)
      file << (i ? "," : "") << values[i];
    file << '\n' << std::flush;
  }

  std::string Summary::quote(const std::string &text)
  {
    std::string out = "\"";
    for (const char c : text)
      {
        if (c == '"' || c == '\\')
          out += '\\';
        if (c == '\n')
          {
            out += "\\n";
            continue;
          }
        out += c;
      }
    return out + "\"";
  }

  std::string Summary::number(const double value)
  {
    if (!std::isfinite(value))
      return "null";
    std::ostringstream s;
    s << std::setprecision(15) << value;
    return s.str();
  }

  void Summary::put(const std::string &object, const std::string &key, const std::string &raw)
  {
    if (object.empty())
      {
        for (auto &v : values)
          if (v.first == key)
            {
              v.second = raw;
              return;
            }
        values.emplace_back(key, raw);
        return;
      }
    for (auto &o : objects)
      if (o.first == object)
        {
          for (auto &v : o.second)
            if (v.first == key)
              {
                v.second = raw;
                return;
              }
          o.second.emplace_back(key, raw);
          return;
        }
    objects.push_back({object, {{key, raw}}});
  }

  void Summary::set(const std::string &key, const double value) { put("", key, number(value)); }
  void Summary::set(const std::string &key, const std::string &value) { put("", key, quote(value)); }
  void Summary::set(const std::string &o, const std::string &key, const double value)
  {
    put(o, key, number(value));
  }
  void Summary::set(const std::string &o, const std::string &key, const std::string &value)
  {
    put(o, key, quote(value));
  }

  void Summary::write(const std::string &filename) const
  {
    std::ofstream out(filename);
    out << "{\n";
    bool first = true;
    for (const auto &[k, v] : values)
      {
        out << (first ? "" : ",\n") << "  " << quote(k) << ": " << v;
        first = false;
      }
    for (const auto &[name, entries] : objects)
      {
        out << (first ? "" : ",\n") << "  " << quote(name) << ": {";
        first = false;
        bool first_entry = true;
        for (const auto &[k, v] : entries)
          {
            out << (first_entry ? "\n" : ",\n") << "    " << quote(k) << ": " << v;
            first_entry = false;
          }
        out << "\n  }";
      }
    out << "\n}\n";
  }
} // namespace anvil
