#include <anvil/core/scene.h>
#include <anvil/postprocess/interface.h>

#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    // Where anvil-plot lives: beside the running executable (build/anvil and
    // build/anvil-plot; bin/ after installation), else in the build tree
    // (a step program's executable lives elsewhere).
    std::string plot_tool()
    {
      std::error_code ec;
      const auto      exe = std::filesystem::read_symlink("/proc/self/exe", ec);
      if (!ec && std::filesystem::exists(exe.parent_path() / "anvil-plot"))
        return (exe.parent_path() / "anvil-plot").string();
#ifdef ANVIL_TOOLS_DIR
      if (std::filesystem::exists(std::string(ANVIL_TOOLS_DIR) + "/anvil-plot"))
        return std::string(ANVIL_TOOLS_DIR) + "/anvil-plot";
#endif
      return "";
    }

    std::string shell_quote(const std::string &text)
    {
      std::string out = "'";
      for (const char c : text)
        out += c == '\'' ? std::string("'\\''") : std::string(1, c);
      return out + "'";
    }
  } // namespace

  /**
   * figures/<name>.png: the scene's standard figures (Output/Figure list),
   * drawn at the end of the run by anvil-plot (matplotlib; fields through
   * anvil-render) when Output/Figures is true. The histories and fields are
   * already on disk then: a figure that cannot be drawn (no matplotlib)
   * costs a warning, never the results.
   */
  template <int dim>
  class Figures : public Postprocessor<dim>
  {
  public:
    static void declare_parameters(ParameterHandler &prm)
    {
      prm.declare_entry("Figures", "false", Patterns::Bool(),
                        "Draw the scene's Figure list into <Output/Directory>/figures at the end "
                        "of the run (needs /usr/bin/python3 with matplotlib and, for fields, "
                        "VTK: contrib/setup.sh installs them). contrib/run.sh sets it to true.");
      prm.declare_entry(
        "Figure list", "", Patterns::Anything(),
        "The scene's standard figures, 'name: X -> Y[, Y...]; name: field F [at TIME] "
        "[undeformed]; ...'. X and Y are columns of the CSV histories (reactions, probes, "
        "energy, contact, thermal, newton; with or without their ' [unit]'; 'file.csv:column' "
        "picks a file), plotted against each other with their units; 'field F' draws the "
        "output field F (e.g. temperature, von_mises_nodal) on the deformed mesh at the output "
        "time nearest TIME [s] (default: the last). Written as figures/<name>.png. The same "
        "plots by hand: build/anvil-plot and build/anvil-render (--help).");
    }

    void parse_parameters(ParameterHandler &prm, Scene &scene, const SceneContents<dim> &) override
    {
      enabled = prm.get_bool({"Output"}, "Figures");
      list    = prm.get({"Output"}, "Figure list");
      for (const auto &item : split_outside_parentheses(list, ';'))
        check_item(item, scene);
    }
    bool applies(const SceneContents<dim> &) const override { return enabled && !trim(list).empty(); }

    void finish(const SimulationState<dim> &s, bool /*failed*/) override
    {
      // Only rank 0 draws: the files are complete once every rank has
      // written (the last collective output precedes finish()).
      if (!s.is_root())
        return;
      const std::string tool = plot_tool();
      if (tool.empty())
        {
          std::cerr << "anvil: warning: no anvil-plot beside the executable: figures not drawn"
                    << std::endl;
          return;
        }
      const std::string command = shell_quote(tool) + " " + shell_quote(s.output_directory) +
                                  " --figures " + shell_quote(list) + " > " +
                                  shell_quote(s.output_directory + "/figures.log") + " 2>&1";
      const int status = std::system(command.c_str());
      if (status != 0)
        std::cerr << "anvil: warning: figures not drawn (anvil-plot failed, see "
                  << s.output_directory << "/figures.log)" << std::endl;
    }

  private:
    bool        enabled = false;
    std::string list;

    // The syntax only, before any work; the columns and fields are known to
    // anvil-plot once the run has written them.
    static void check_item(const std::string &raw, const Scene &scene)
    {
      const std::string item = trim(raw);
      if (item.empty())
        return;
      const auto        colon = item.find(':');
      const std::string name  = colon == std::string::npos ? "" : trim(item.substr(0, colon));
      const std::string body  = colon == std::string::npos ? "" : trim(item.substr(colon + 1));
      const bool        named = !name.empty() && name.find_first_of("/ '\"") == std::string::npos;
      const bool        field = body.rfind("field ", 0) == 0 && trim(body.substr(6)).size() > 0;
      const auto        arrow = body.find("->");
      const bool        history = arrow != std::string::npos && !trim(body.substr(0, arrow)).empty() &&
                           !trim(body.substr(arrow + 2)).empty();
      if (!named || !(field || history))
        scene.fail("Output/Figure list", "item '" + item + "': expected 'name: X -> Y[, Y...]' or "
                                         "'name: field F [at TIME] [undeformed]' (name without "
                                         "spaces or slashes)");
      if (field)
        {
          std::istringstream words(body);
          std::string        w, f;
          words >> w >> f;
          while (words >> w)
            if (w == "at")
              {
                std::string t;
                words >> t;
                char *end = nullptr;
                std::strtod(t.c_str(), &end);
                if (t.empty() || *end != '\0')
                  scene.fail("Output/Figure list", "item '" + item + "': expected a time in s "
                                                   "after 'at', not '" + t + "'");
              }
            else if (w != "undeformed")
              scene.fail("Output/Figure list", "item '" + item + "': unknown word '" + w +
                                                 "' (expected 'at TIME' or 'undeformed')");
        }
    }
  };

  ANVIL_REGISTER_POSTPROCESSOR(Figures, "figures",
                               "figures/<name>.png: the scene's Figure list, drawn at the end "
                               "when Output/Figures is true (anvil-plot, anvil-render).")
} // namespace anvil
