#pragma once

#include <deal.II/base/parameter_handler.h>

#include <anvil/core/input_error.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace anvil
{
  /**
   * A scene: one .prm file plus the command-line overrides
   * `--set 'Section/Subsection/Entry=value'`.
   *
   * Reading happens in two passes. Pass one declares only what decides the
   * shape of the rest (`Dimension`, the body names) and skips everything else.
   * Pass two declares every parameter (per body, per dimension) and parses
   * strictly: an unknown entry, a value that does not match its pattern or a
   * missing file is an InputError naming file, line and entry.
   */
  class Scene
  {
  public:
    /// A function that declares all parameters given the body names.
    using Declarator = std::function<void(dealii::ParameterHandler &, const Scene &)>;

    Scene(const std::string                                        &filename,
          const std::vector<std::pair<std::string, std::string>> &overrides);

    /// An empty scene (only defaults and overrides), e.g. for --print-parameters.
    Scene();

    /// Pass one: dimension, body names, contact pair and tool names.
    void read_shape();

    /// Pass two: declare with @p declare and parse strictly.
    void read(const Declarator &declare);

    unsigned int                    dimension() const { return dim; }
    const std::vector<std::string> &body_names() const { return bodies; }
    /// Names in Contact/Pairs and Contact/Tools (each gets a subsection).
    const std::vector<std::string> &contact_pair_names() const { return pairs; }
    const std::vector<std::string> &contact_tool_names() const { return tools; }
    const std::string              &filename() const { return file; }
    dealii::ParameterHandler       &parameters() { return prm; }

    /**
     * "scene.prm:12" for the line where @p path (e.g. "Mechanics/Newton/Tolerance")
     * is set in the file, "--set" if it came from the command line, or
     * "scene.prm" (default value) otherwise. Used to make error messages point
     * at what the user wrote.
     */
    std::string where(const std::string &path) const;

    /// Throw an InputError "<where(path)>: '<path>' <message>".
    [[noreturn]] void fail(const std::string &path, const std::string &message) const;

    /// Parse `Section/Sub/Entry=value` into (path, value); throws InputError.
    static std::pair<std::string, std::string> parse_override(const std::string &text);

    /// Declare the entries read in pass one (Dimension, Bodies/Names, Contact/Pairs, Contact/Tools).
    static void declare_shape_parameters(dealii::ParameterHandler &prm);

  private:
    void apply_overrides(dealii::ParameterHandler &prm, bool skip_undeclared);
    void parse_file(dealii::ParameterHandler &prm, bool skip_undefined);

    std::string                                        file;
    std::vector<std::pair<std::string, std::string>> overrides;
    dealii::ParameterHandler                           prm;
    unsigned int                                       dim = 2;
    std::vector<std::string>                           bodies, pairs, tools;
  };

  /// Split "a, b(c, d); e" at @p separator outside parentheses, trimming blanks.
  std::vector<std::string> split_outside_parentheses(const std::string &text, char separator);

  /// Trim blanks at both ends.
  std::string trim(const std::string &text);
} // namespace anvil
