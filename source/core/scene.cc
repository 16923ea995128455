#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <anvil/core/scene.h>

#include <fstream>
#include <sstream>

namespace anvil
{
  using namespace dealii;

  std::string trim(const std::string &text)
  {
    const auto first = text.find_first_not_of(" \t\n\r");
    if (first == std::string::npos)
      return "";
    const auto last = text.find_last_not_of(" \t\n\r");
    return text.substr(first, last - first + 1);
  }

  std::vector<std::string> split_outside_parentheses(const std::string &text, const char separator)
  {
    std::vector<std::string> parts;
    std::string              current;
    int                      depth = 0;
    for (const char c : text)
      {
        if (c == '(')
          ++depth;
        else if (c == ')')
          --depth;
        if (c == separator && depth == 0)
          {
            parts.push_back(trim(current));
            current.clear();
          }
        else
          current += c;
      }
    if (!trim(current).empty() || !parts.empty())
      parts.push_back(trim(current));
    return parts;
  }

  namespace
  {
    // deal.II's parser exceptions print several indented lines; make them one.
    std::string one_line(const std::string &text)
    {
      std::string out;
      bool        blank = false;
      for (const char c : text)
        {
          if (c == '\n' || c == '\t' || c == ' ')
            {
              blank = true;
              continue;
            }
          if (blank && !out.empty())
            out += ' ';
          blank = false;
          out += c;
        }
      return out;
    }

    std::string exception_text(const ExceptionBase &e)
    {
      std::ostringstream s;
      e.print_info(s);
      return one_line(s.str());
    }

    std::vector<std::string> split_path(const std::string &path)
    {
      std::vector<std::string> parts;
      std::string              current;
      for (const char c : path)
        if (c == '/')
          {
            parts.push_back(trim(current));
            current.clear();
          }
        else
          current += c;
      parts.push_back(trim(current));
      return parts;
    }
  } // namespace

  Scene::Scene(const std::string                                        &filename,
               const std::vector<std::pair<std::string, std::string>> &overrides)
    : file(filename)
    , overrides(overrides)
  {
    std::ifstream in(file);
    if (!in)
      throw InputError(file + ": cannot open the scene file (expected a readable .prm file)");
  }

  Scene::Scene() = default;

  void Scene::declare_shape_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Dimension",
                      "2",
                      Patterns::Integer(2, 3),
                      "Space dimension of the scene: 2 (plane strain, or axisymmetric "
                      "where the mechanics says so) or 3. Read before anything else.");
    prm.enter_subsection("Bodies");
    prm.declare_entry("Names",
                      "body",
                      Patterns::List(Patterns::Anything(), 1),
                      "Names of the bodies of the scene, as the geometry names them "
                      "(a generator's Body name, or the physical names of a gmsh file). "
                      "Each gets a subsection of its own with its material.");
    prm.leave_subsection();
    prm.enter_subsection("Contact");
    prm.declare_entry("Pairs", "", Patterns::List(Patterns::Anything(), 0),
                      "Names of the contact pairs; each gets a subsection Contact/<name> with "
                      "its Slave and Master surfaces, penalties, friction and thermal contact. "
                      "Empty: no contact (no search, nothing built).");
    prm.declare_entry("Tools", "", Patterns::List(Patterns::Anything(), 0),
                      "Names of the rigid tools; each gets a subsection Contact/<name> with its "
                      "surface, motion and temperature. A pair's Master may name a tool.");
    prm.leave_subsection();
  }

  std::pair<std::string, std::string> Scene::parse_override(const std::string &text)
  {
    const auto eq = text.find('=');
    if (eq == std::string::npos || trim(text.substr(0, eq)).empty())
      throw InputError("--set '" + text +
                       "': expected 'Section/Subsection/Entry=value', e.g. "
                       "--set 'Time/End time=2'");
    return {trim(text.substr(0, eq)), trim(text.substr(eq + 1))};
  }

  void Scene::parse_file(ParameterHandler &p, const bool skip_undefined)
  {
    if (file.empty())
      return;
    try
      {
        p.parse_input(file, "", skip_undefined, false);
      }
    catch (const ExceptionBase &e)
      {
        std::string msg = exception_text(e);
        // deal.II says "Line <12> of file <scene.prm>: ..." — reformat as file:line.
        // Read by hand: std::regex recurses per character and overflows the
        // stack on the 100 000-character lines a hostile file can hold.
        const auto line_at  = msg.find("Line <");
        const auto line_end = msg.find("> of file <", line_at);
        const auto file_end = msg.find_first_of(">:", line_end + 11);
        if (line_at != std::string::npos && line_end != std::string::npos &&
            file_end != std::string::npos && line_end > line_at + 6 &&
            msg.find_first_not_of("0123456789", line_at + 6) == line_end)
          {
            auto rest = file_end;
            if (msg[rest] == '>')
              ++rest;
            if (rest < msg.size() && msg[rest] == ':')
              ++rest;
            msg = msg.substr(line_end + 11, file_end - line_end - 11) + ":" +
                  msg.substr(line_at + 6, line_end - line_at - 6) + ": " + trim(msg.substr(rest));
          }
        else
          msg = file + ": " + msg;
        // The body subsections exist only for the bodies named in Bodies/Names.
        if (msg.find("subsection to be entered: Bodies.") != std::string::npos)
          msg += " (a body's subsection needs its name in 'Bodies/Names')";
        throw InputError(msg);
      }
  }

  void Scene::apply_overrides(ParameterHandler &p, const bool skip_undeclared)
  {
    for (const auto &[path, value] : overrides)
      {
        const auto parts = split_path(path);
        unsigned int depth = 0;
        try
          {
            for (unsigned int i = 0; i + 1 < parts.size(); ++i, ++depth)
              p.enter_subsection(parts[i]);
            p.set(parts.back(), value);
          }
        catch (const ExceptionBase &e)
          {
            for (unsigned int i = 0; i < depth; ++i)
              p.leave_subsection();
            if (skip_undeclared)
              continue;
            throw InputError("--set '" + path + "=" + value + "': " + exception_text(e));
          }
        for (unsigned int i = 0; i < depth; ++i)
          p.leave_subsection();
      }
  }

  void Scene::read_shape()
  {
    ParameterHandler shape;
    declare_shape_parameters(shape);
    parse_file(shape, true);
    apply_overrides(shape, true);
    dim = shape.get_integer("Dimension");
    shape.enter_subsection("Bodies");
    bodies.clear();
    for (const auto &name : Utilities::split_string_list(shape.get("Names")))
      {
        for (const auto &other : bodies)
          if (other == name)
            fail("Bodies/Names", "lists the body '" + name + "' twice");
        bodies.push_back(name);
      }
    shape.leave_subsection();
    shape.enter_subsection("Contact");
    pairs = Utilities::split_string_list(shape.get("Pairs"));
    tools = Utilities::split_string_list(shape.get("Tools"));
    shape.leave_subsection();
    std::vector<std::string> all = bodies;
    for (const auto *list : {&pairs, &tools})
      for (const auto &name : *list)
        {
          if (std::find(all.begin(), all.end(), name) != all.end() || name == "Pairs" || name == "Tools")
            fail(list == &pairs ? "Contact/Pairs" : "Contact/Tools",
                 "uses the name '" + name + "' twice (pairs, tools and bodies need distinct names)");
          all.push_back(name);
        }
  }

  void Scene::read(const Declarator &declare)
  {
    declare(prm, *this);
    parse_file(prm, false);
    apply_overrides(prm, false);
  }

  std::string Scene::where(const std::string &path) const
  {
    for (const auto &o : overrides)
      if (o.first == path)
        return "--set";
    if (file.empty())
      return "(defaults)";

    // Walk the file, tracking the subsection nesting, to find "set Entry".
    const auto    parts = split_path(path);
    std::ifstream in(file);
    std::string   line;
    std::vector<std::string> stack;
    unsigned int  number = 0;
    while (std::getline(in, line))
      {
        ++number;
        std::string l = line.substr(0, line.find('#'));
        l             = trim(l);
        if (l.rfind("subsection", 0) == 0)
          stack.push_back(trim(l.substr(10)));
        else if (l == "end" && !stack.empty())
          stack.pop_back();
        else if (l.rfind("set", 0) == 0)
          {
            const auto eq = l.find('=');
            if (eq == std::string::npos)
              continue;
            const std::string entry = trim(l.substr(3, eq - 3));
            if (stack.size() + 1 == parts.size() && entry == parts.back() &&
                std::equal(stack.begin(), stack.end(), parts.begin()))
              return file + ":" + std::to_string(number);
          }
      }
    return file + " (default value)";
  }

  void Scene::fail(const std::string &path, const std::string &message) const
  {
    throw InputError(where(path) + ": '" + path + "' " + message);
  }
} // namespace anvil
