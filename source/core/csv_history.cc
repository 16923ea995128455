#include <anvil/core/csv_history.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <sstream>

namespace anvil
{
  namespace
  {
    // Keeps the header and the rows up to @p keep_until in its "time" column:
    // a run killed after its last checkpoint wrote rows the restart writes
    // again, and a history must not hold a time twice or go back in time.
    void truncate_rows(const std::string &filename, const double keep_until)
    {
      std::vector<std::string> lines;
      {
        std::ifstream in(filename);
        for (std::string line; std::getline(in, line);)
          lines.push_back(line);
      }
      if (lines.empty())
        return;
      std::size_t        time_column = 0, k = 0;
      std::istringstream header(lines[0]);
      bool               found = false;
      for (std::string name; std::getline(header, name, ','); ++k)
        if (name == "time" || name.rfind("time [", 0) == 0)
          {
            time_column = k;
            found       = true;
          }
      if (!found)
        return;
      std::ofstream out(filename, std::ios::trunc);
      out << lines[0] << '\n';
      const double limit = keep_until + 1e-12 * std::max(1., std::abs(keep_until));
      for (std::size_t i = 1; i < lines.size(); ++i)
        {
          std::istringstream row(lines[i]);
          std::string        cell;
          for (std::size_t c = 0; c <= time_column && std::getline(row, cell, ','); ++c)
            ;
          char  *end  = nullptr;
          double time = std::strtod(cell.c_str(), &end);
          if (end != cell.c_str() && time <= limit)
            out << lines[i] << '\n';
        }
    }
  } // namespace

  void CsvHistory::open(const std::string &filename, const std::vector<std::string> &columns,
                        const bool write, const bool append, const double keep_until)
  {
    n_columns = columns.size();
    if (!write)
      return;
    // Continue a history (restart) only if there is one: a restart into
    // another directory starts its files with their header.
    if (append && std::ifstream(filename).good())
      {
        truncate_rows(filename, keep_until);
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
    // Each value as printf's %.12g, which is what the stream wrote with
    // setprecision(12) (the same characters: std::to_chars' general format
    // at a given precision is defined as printf's), without the stream's
    // locale and facet calls per number (~1 500 instructions each); the row
    // goes out in one write.
    char        buffer[32];
    std::string row;
    row.reserve(values.size() * 20 + 1);
    for (std::size_t i = 0; i < values.size(); ++i)
      {
        if (i)
          row += ',';
        const auto end = std::to_chars(buffer, buffer + sizeof(buffer), values[i],
                                       std::chars_format::general, 12).ptr;
        row.append(buffer, end);
      }
    row += '\n';
    file.write(row.data(), static_cast<std::streamsize>(row.size()));
    file << std::flush;
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
