#pragma once

#include <deal.II/base/parameter_handler.h>

#include <algorithm>
#include <functional>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace anvil
{
  /**
   * A registry of named parts (coupling schemes, material models, hardening
   * and softening laws, tool shapes, postprocessors): every part is one file
   * that ends with a registration macro, and the parameter that chooses it is
   * a Patterns::Selection built from what is registered, so `anvil --help`
   * lists exactly what exists. A step program registers its own parts the
   * same way, from outside the library (static initialisation of its object
   * files, before main()).
   *
   * @p Base is the interface; parts are made by a factory taking @p Args.
   * Names are kept in registration order (within the library, the link order
   * of its files); lookups are by exact name.
   */
  template <class Base, class... Args>
  class Registry
  {
  public:
    using Factory  = std::function<std::unique_ptr<Base>(Args...)>;
    using Declarer = std::function<void(dealii::ParameterHandler &)>;

    struct Entry
    {
      std::string name;
      std::string documentation;
      Factory     create;
      Declarer    declare_parameters; // may be empty: the part has no parameters of its own
    };

    static Registry &instance()
    {
      static Registry registry;
      return registry;
    }

    /// Registers a part; a second part of the same name is a programming error.
    bool add(const std::string &name, const std::string &documentation, Factory create,
             Declarer declare = {})
    {
      for (const auto &e : entries)
        if (e.name == name)
          throw std::logic_error("anvil: two parts registered under the name '" + name + "'");
      entries.push_back({name, documentation, std::move(create), std::move(declare)});
      return true;
    }

    bool has(const std::string &name) const
    {
      return std::any_of(entries.begin(), entries.end(),
                         [&](const Entry &e) { return e.name == name; });
    }

    const Entry &get(const std::string &name) const
    {
      for (const auto &e : entries)
        if (e.name == name)
          return e;
      throw std::logic_error("anvil: no part registered under the name '" + name +
                             "' (registered: " + names_pattern() + ")");
    }

    std::unique_ptr<Base> create(const std::string &name, Args... args) const
    {
      return get(name).create(std::forward<Args>(args)...);
    }

    std::vector<std::string> names() const
    {
      std::vector<std::string> n;
      for (const auto &e : entries)
        n.push_back(e.name);
      return n;
    }

    /// "a|b|c": the pattern of the selecting parameter.
    std::string names_pattern() const
    {
      std::string p;
      for (const auto &e : entries)
        p += (p.empty() ? "" : "|") + e.name;
      return p;
    }

    /// "'a': doc a 'b': doc b" for the selecting parameter's help.
    std::string documentation(const std::string &separator = " ") const
    {
      std::string d;
      for (const auto &e : entries)
        d += (d.empty() ? "" : separator) + "'" + e.name + "': " + e.documentation;
      return d;
    }

    /// Every part's own parameters (each part declares its own subsection or entries).
    void declare_parameters(dealii::ParameterHandler &prm) const
    {
      for (const auto &e : entries)
        if (e.declare_parameters)
          e.declare_parameters(prm);
    }

    const std::vector<Entry> &all() const { return entries; }

  private:
    Registry() = default;
    std::vector<Entry> entries;
  };
} // namespace anvil

#define ANVIL_REGISTRY_CONCAT_(a, b) a##b
#define ANVIL_REGISTRY_CONCAT(a, b) ANVIL_REGISTRY_CONCAT_(a, b)
/// A unique name for the static object that registers one part.
#define ANVIL_REGISTRY_UNIQUE(prefix) ANVIL_REGISTRY_CONCAT(prefix, __COUNTER__)
