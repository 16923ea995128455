#pragma once

#include <fstream>
#include <string>
#include <vector>

namespace anvil
{
  /**
   * A CSV time history (one row per accepted step), written by rank 0 only
   * and flushed after each row so that a run that stops keeps its history.
   */
  class CsvHistory
  {
  public:
    /// @p write is false on every rank but 0; @p append continues an existing
    /// file (a restart) without writing the header again.
    void open(const std::string &filename, const std::vector<std::string> &columns, bool write,
              bool append = false);
    void add_row(const std::vector<double> &values);
    bool is_open() const { return file.is_open(); }

  private:
    std::ofstream file;
    std::size_t   n_columns = 0;
  };

  /**
   * summary.json: a flat, ordered JSON object with nested objects one level
   * deep — what tests, studies and plots read after a run.
   */
  class Summary
  {
  public:
    void set(const std::string &key, double value);
    void set(const std::string &key, const std::string &value);
    void set(const std::string &object, const std::string &key, double value);
    void set(const std::string &object, const std::string &key, const std::string &value);
    void write(const std::string &filename) const;

    static std::string quote(const std::string &text);

  private:
    // (key, raw JSON) per top-level entry; objects hold their own list.
    std::vector<std::pair<std::string, std::string>>                                   values;
    std::vector<std::pair<std::string, std::vector<std::pair<std::string, std::string>>>> objects;
    static std::string number(double value);
    void               put(const std::string &object, const std::string &key, const std::string &raw);
  };
} // namespace anvil
