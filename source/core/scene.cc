#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <anvil/core/scene.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <algorithm>
#include <cctype>
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

    // --- "did you mean": the declared names nearest to a misspelled one.

    // Edit distance, ignoring case (a user's "time step" is 'Time step').
    std::size_t distance(const std::string &a, const std::string &b)
    {
      std::vector<std::size_t> row(b.size() + 1);
      for (std::size_t j = 0; j <= b.size(); ++j)
        row[j] = j;
      for (std::size_t i = 1; i <= a.size(); ++i)
        {
          std::size_t diagonal = row[0];
          row[0]               = i;
          for (std::size_t j = 1; j <= b.size(); ++j)
            {
              const std::size_t up   = row[j];
              const bool        same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                                std::tolower(static_cast<unsigned char>(b[j - 1]));
              row[j]   = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1)});
              diagonal = up;
            }
        }
      return row[b.size()];
    }

    // An entry of deal.II's JSON print is an object with a "value"; a
    // subsection one without (and with at least one entry below it: deal.II
    // creates an empty one when an undeclared subsection is entered).
    bool is_entry(const boost::property_tree::ptree &node)
    {
      return node.find("value") != node.not_found();
    }
    bool has_entries(const boost::property_tree::ptree &node)
    {
      for (const auto &child : node)
        if (is_entry(child.second) || has_entries(child.second))
          return true;
      return false;
    }

    // The entries (or the subsections) declared in subsection @p path.
    std::vector<std::string> declared_names(const ParameterHandler         &prm,
                                            const std::vector<std::string> &path,
                                            const bool                      subsections)
    {
      std::stringstream json;
      prm.print_parameters(json, ParameterHandler::JSON);
      boost::property_tree::ptree tree;
      boost::property_tree::read_json(json, tree);
      const boost::property_tree::ptree *node = &tree;
      for (const auto &name : path)
        {
          const boost::property_tree::ptree *next = nullptr;
          for (const auto &[key, child] : *node)
            if (key == name && !is_entry(child))
              next = &child;
          if (!next)
            return {};
          node = next;
        }
      std::vector<std::string> names;
      for (const auto &[key, child] : *node)
        if (subsections ? !is_entry(child) && has_entries(child) : is_entry(child))
          names.push_back(key);
      return names;
    }

    // " (did you mean 'Time step'?)": the nearest names within a third of
    // the word's length (at least 2 edits); else the list when it is short.
    std::string suggestion(const std::string &wrong, const std::vector<std::string> &names)
    {
      const std::size_t        limit = std::max<std::size_t>(2, wrong.size() / 3);
      std::size_t              best  = limit + 1;
      std::vector<std::string> nearest;
      for (const auto &n : names)
        {
          const std::size_t d = distance(wrong, n);
          if (d > limit)
            continue;
          if (d < best)
            {
              best = d;
              nearest.clear();
            }
          if (d == best)
            nearest.push_back(n);
        }
      std::string text;
      for (std::size_t i = 0; i < nearest.size(); ++i)
        text += (i == 0 ? "'" : i + 1 == nearest.size() ? " or '" : ", '") + nearest[i] + "'";
      if (!text.empty())
        return " (did you mean " + text + "?)";
      if (names.empty() || names.size() > 12)
        return "";
      for (const auto &n : names)
        text += (text.empty() ? "'" : ", '") + n + "'";
      return " (declared here: " + text + ")";
    }

    std::string section_name(const std::vector<std::string> &path)
    {
      std::string text;
      for (const auto &p : path)
        text += (text.empty() ? "" : "/") + p;
      return text.empty() ? "the top level" : "subsection '" + text + "'";
    }

    // The subsection nesting in force at line @p number of @p file (the
    // line itself not included).
    std::vector<std::string> sections_before_line(const std::string &file, const unsigned int number)
    {
      std::ifstream            in(file);
      std::vector<std::string> stack;
      std::string              line;
      for (unsigned int n = 1; n < number && std::getline(in, line); ++n)
        {
          const std::string l = trim(line.substr(0, line.find('#')));
          if (l.rfind("subsection", 0) == 0)
            stack.push_back(trim(l.substr(10)));
          else if (l == "end" && !stack.empty())
            stack.pop_back();
        }
      return stack;
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
        // Read by hand, not with std::regex: it recurses per character and
        // overflows the stack on the 100 000-character lines a hostile file can hold.
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
            const std::string  line_text = msg.substr(line_at + 6, line_end - line_at - 6);
            const std::string  file_text = msg.substr(line_end + 11, file_end - line_end - 11);
            const std::string  text      = trim(msg.substr(rest));
            const unsigned int number    = std::stoul(line_text.substr(0, 9));
            const std::string  at        = file_text + ":" + line_text + ": ";
            msg                          = at + text;
            // A misspelled entry or subsection: name where, and the nearest declared names.
            const auto        stack         = sections_before_line(file, number);
            const std::string entry_head    = "No entry with name <";
            const std::string section_head  = "There is no such subsection to be entered: ";
            const auto        entry_at      = text.find(entry_head);
            const auto        entry_end     = text.find("> was declared", entry_at);
            const auto        section_at    = text.find(section_head);
            if (entry_at != std::string::npos && entry_end != std::string::npos)
              {
                const std::string name =
                  text.substr(entry_at + entry_head.size(), entry_end - entry_at - entry_head.size());
                msg = at + "no entry '" + name + "' in " + section_name(stack) +
                      suggestion(name, declared_names(p, stack, false));
              }
            else if (section_at != std::string::npos)
              {
                // deal.II names the path joined by '.': keep the last part.
                std::string name = trim(text.substr(section_at + section_head.size()));
                std::string path;
                for (const auto &part : stack)
                  path += part + "/";
                for (const auto &part : stack)
                  if (name.rfind(part + ".", 0) == 0)
                    name = name.substr(part.size() + 1);
                const std::string hint =
                  stack.size() == 1 && stack[0] == "Bodies" ?
                    " (a body's subsection needs its name in 'Bodies/Names')" :
                    "";
                msg = at + "no subsection '" + path + name + "'" +
                      suggestion(name, declared_names(p, stack, true)) + hint;
              }
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
            // deal.II enters an undeclared subsection without complaint: find
            // the first path component that is not declared.
            for (unsigned int k = 0; k + 1 < parts.size(); ++k)
              {
                const std::vector<std::string> above(parts.begin(), parts.begin() + k);
                const auto sections = declared_names(p, above, true);
                if (std::find(sections.begin(), sections.end(), parts[k]) == sections.end())
                  {
                    depth = k;
                    break;
                  }
              }
            const std::vector<std::string> entered(parts.begin(), parts.begin() + depth);
            const bool        entry = depth + 1 == parts.size();
            const std::string name  = parts[depth];
            const auto        names = declared_names(p, entered, !entry);
            if (std::find(names.begin(), names.end(), name) != names.end())
              throw InputError("--set '" + path + "=" + value + "': " + exception_text(e));
            throw InputError("--set '" + path + "=" + value + "': no " +
                             (entry ? "entry '" : "subsection '") + name + "' in " +
                             section_name(entered) + suggestion(name, names));
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
