#include <deal.II/base/mpi.h>
#include <deal.II/base/utilities.h>

#include <anvil/core/input_error.h>
#include <anvil/core/named_values.h>
#include <anvil/simulator/simulator.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <vector>

namespace anvil
{
  using namespace dealii;

  namespace
  {
    // state.txt: a header line with the format version, then one named entry
    // per line ("key value..."), then the contact state after a "contact" line.
    // A new entry is a new key: restarts read by name, never by position.
    // Format 3 (session 18): the mechanics' vectors packed with its points
    // per cell, not through deal.II's SolutionTransfer. Format 4 (session
    // 21): each dof's values once, with one cell of its owner; zero vectors
    // not saved (mechanics/checkpoint.cc).
    constexpr int checkpoint_format = 4;
    const char   *checkpoint_magic  = "anvil-checkpoint";

    // Size and FNV-1a hash of a file: a checkpoint's mesh files damaged or cut
    // short after it was written are refused at parse (p4est aborts on them).
    // Checkpoints before session 17 hold these ("file." entries).
    std::string fingerprint(const std::string &filename)
    {
      std::ifstream      in(filename, std::ios::binary);
      std::uint64_t      hash = 1469598103934665603ull, size = 0;
      char               buffer[1 << 16];
      while (in.read(buffer, sizeof buffer) || in.gcount() > 0)
        {
          for (std::streamsize i = 0; i < in.gcount(); ++i)
            hash = (hash ^ static_cast<unsigned char>(buffer[i])) * 1099511628211ull;
          size += in.gcount();
        }
      std::ostringstream s;
      s << size << ' ' << std::hex << hash;
      return s.str();
    }

    // The same check in 1 MiB chunks ("chunks." entries): FNV-1a over 8-byte
    // words of each chunk, then over the chunks' hashes. The chunks are hashed
    // by all processes in turn, so that the checkpoint's files (all the
    // processes' cell data) are not read through by process 0 alone, a byte
    // at a time (~6 instructions a byte: ~100 M on the contact strip).
    constexpr std::uint64_t chunk_bytes = 1 << 20;

    std::uint64_t chunk_hash(const std::string &filename, const std::uint64_t chunk)
    {
      std::ifstream in(filename, std::ios::binary);
      in.seekg(chunk * chunk_bytes);
      std::vector<char> bytes(chunk_bytes);
      in.read(bytes.data(), chunk_bytes);
      const std::size_t n    = in.gcount();
      std::uint64_t     hash = 1469598103934665603ull, word = 0;
      std::size_t       i    = 0;
      for (; i + sizeof word <= n; i += sizeof word)
        {
          std::memcpy(&word, bytes.data() + i, sizeof word);
          hash = (hash ^ word) * 1099511628211ull;
        }
      for (; i < n; ++i)
        hash = (hash ^ static_cast<unsigned char>(bytes[i])) * 1099511628211ull;
      return hash;
    }

    // The fingerprints of @p files; chunk k hashed by process k mod
    // n_processes (all of them on one process at restart).
    std::vector<std::string> chunked_fingerprints(const std::vector<std::string> &files,
                                                  const MPI_Comm comm, const bool collective)
    {
      const unsigned int rank = collective ? Utilities::MPI::this_mpi_process(comm) : 0;
      const unsigned int n    = collective ? Utilities::MPI::n_mpi_processes(comm) : 1;
      std::vector<std::uint64_t> sizes, hashes; // hashes of every chunk of every file, 0 if not ours
      for (const auto &f : files)
        {
          std::error_code     error;
          const std::uint64_t size = std::filesystem::file_size(f, error);
          sizes.push_back(error ? 0 : size);
          for (std::uint64_t k = 0; k < (sizes.back() + chunk_bytes - 1) / chunk_bytes; ++k)
            hashes.push_back(k % n == rank ? chunk_hash(f, k) : 0);
        }
      if (collective) // each chunk's hash comes from one process, the others add 0
        Utilities::MPI::sum(hashes, comm, hashes);
      std::vector<std::string> result;
      std::size_t              next = 0;
      for (const std::uint64_t size : sizes)
        {
          std::uint64_t hash = 1469598103934665603ull;
          for (std::uint64_t k = 0; k < (size + chunk_bytes - 1) / chunk_bytes; ++k)
            hash = (hash ^ hashes[next++]) * 1099511628211ull;
          std::ostringstream s;
          s << size << ' ' << std::hex << hash;
          result.push_back(s.str());
        }
      return result;
    }

    // What write_checkpoint() hashed (all processes), for write_state() to
    // write (process 0): file name -> fingerprint.
    std::map<std::string, std::string> saved_fingerprints;

    // Counts the restart adds to: whole numbers that fit their counters.
    const char *const counters[] = {"steps", "cut_backs", "newton_iterations", "linear_iterations",
                                    "heat_internal_steps", "heat_nonlinear_iterations",
                                    "staggered_iterations"};

    std::string joined(const std::vector<std::string> &names)
    {
      std::string s;
      for (const auto &n : names)
        s += (s.empty() ? "" : ",") + n;
      return s;
    }

    struct StateFile
    {
      int                                format = 0;
      std::map<std::string, std::string> entries;
      std::string                        contact;

      explicit StateFile(const std::string &filename)
      {
        std::ifstream in(filename);
        std::string   magic;
        in >> magic >> format;
        if (magic != checkpoint_magic)
          format = 0;
        std::string line;
        std::getline(in, line);
        while (std::getline(in, line))
          {
            if (line == "contact")
              {
                std::getline(in, contact);
                break;
              }
            const auto space = line.find(' ');
            if (space != std::string::npos)
              entries[line.substr(0, space)] = line.substr(space + 1);
          }
      }
      std::string text(const std::string &key) const
      {
        const auto it = entries.find(key);
        if (it == entries.end())
          throw InputError("the checkpoint has no entry '" + key + "' (damaged?)");
        return it->second;
      }
      double number(const std::string &key) const { return to_number(key, text(key)); }
      static double to_number(const std::string &key, const std::string &value)
      {
        char        *end = nullptr;
        const double x   = std::strtod(value.c_str(), &end);
        if (end == value.c_str() || !std::isfinite(x))
          throw InputError("the checkpoint entry '" + key + "' = '" + value.substr(0, 40) +
                           "' is not a finite number (damaged?)");
        return x;
      }
      NamedValues group(const std::string &prefix) const
      {
        NamedValues v;
        for (const auto &[key, value] : entries)
          if (key.rfind(prefix + ".", 0) == 0)
            v[key.substr(prefix.size() + 1)] = to_number(key, value);
        return v;
      }
    };
  } // namespace

  template <int dim>
  void Simulator<dim>::check_checkpoint() const
  {
    const std::string path = "Output/Restart from";
    const std::string file = restart_directory + "/state.txt";
    if (!std::filesystem::exists(file))
      scene.fail(path, "= '" + restart_directory + "' is not a checkpoint directory (no state.txt in it)");
    const StateFile state(file);
    if (state.format == 0)
      scene.fail(path, "= '" + restart_directory + "' holds no anvil checkpoint (its state.txt "
                         "does not begin with '" + checkpoint_magic + "')");
    if (state.format != checkpoint_format)
      scene.fail(path, "= '" + restart_directory + "' was written in checkpoint format " +
                         std::to_string(state.format) + "; this anvil reads format " +
                         std::to_string(checkpoint_format) + " (rerun the scene from t = 0)");
    auto refuse_if = [&](const std::string &key, const std::string &what, const std::string &here) {
      const auto it = state.entries.find(key);
      const std::string there = it == state.entries.end() ? "(none)" : it->second;
      if (there != here)
        scene.fail(path, "= '" + restart_directory + "' was written by a scene with " + what +
                           " = '" + there + "', this scene has '" + here + "'");
    };
    refuse_if("dimension", "Dimension", std::to_string(dim));
    refuse_if("coupling", "Physics/Coupling", coupling);
    refuse_if("bodies", "Bodies/Names", joined(scene.body_names()));
    refuse_if("contact_pairs", "Contact/Pairs", joined(scene.contact_pair_names()));
    // The two kinds save different files (p4est: the refinement of the coarse
    // mesh; fully distributed: each process's cells); checkpoints before
    // Geometry/Partition existed are p4est's.
    if (state.entries.count("partition") || geometry.partition_kind() != "space-filling curve")
      refuse_if("partition", "Geometry/Partition", geometry.partition_kind());
    if (geometry.partition_kind() == "per body")
      {
        const std::string here = std::to_string(Utilities::MPI::n_mpi_processes(mpi_communicator));
        const auto        it   = state.entries.find("processes");
        if (it == state.entries.end() || it->second != here)
          scene.fail(path, "= '" + restart_directory + "' was written by " +
                             (it == state.entries.end() ? std::string("(unknown)") : it->second) +
                             " processes with Geometry/Partition = per body, which restarts only "
                             "on as many; this run has " + here);
      }
    // Every number the restart will read, read now: a damaged file is refused
    // before any work, not halfway through setting up.
    try
      {
        for (const auto &[key, value] : state.entries)
          if (key.rfind("file.", 0) == 0 || key.rfind("chunks.", 0) == 0)
            {
              const std::string name = key.substr(key.find('.') + 1);
              const std::string path = restart_directory + "/" + name;
              if ((key[0] == 'f' ? fingerprint(path) :
                                   chunked_fingerprints({path}, mpi_communicator, false)[0]) != value)
                throw InputError("its file '" + name + "' is not the one written with "
                                 "it (size and checksum differ: damaged or incomplete)");
            }
          else if (key != "scene" && key != "coupling" && key != "bodies" &&
                   key != "contact_pairs" && key != "partition" && key.rfind("output.", 0) != 0)
            StateFile::to_number(key, value);
        for (const char *key : counters)
          {
            const double n = state.number(key);
            if (!(n >= 0 && n <= 4294967295. && n == std::floor(n)))
              throw InputError("the checkpoint entry '" + std::string(key) + "' = '" +
                               state.text(key).substr(0, 40) +
                               "' is not a count (a whole number below 2^32; damaged?)");
          }
        std::istringstream contact(state.contact);
        std::size_t        n = 0, tokens = 0;
        contact >> n;
        for (std::string token; contact >> token;)
          ++tokens;
        if (!state.contact.empty() && n > tokens)
          throw InputError("its contact state announces " + std::to_string(n) + " values and holds " +
                           std::to_string(tokens) + " (damaged?)");
      }
    catch (const InputError &e)
      {
        scene.fail(path, "= '" + restart_directory + "': " + e.what());
      }
  }

  template <int dim>
  void Simulator<dim>::write_checkpoint(const double t, const double dt)
  {
    TimerOutput::Scope s(*timer, "Checkpoint");
    // Written under a new name and renamed when complete: a run killed or a
    // disk filled mid-write never destroys the last good checkpoint.
    const std::string final_dir = output_dir + "/checkpoint";
    const std::string dir       = final_dir + ".new";
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      {
        std::filesystem::remove_all(dir);
        std::filesystem::create_directories(dir);
      }
    MPI_Barrier(mpi_communicator);
    // Attachments are read back in this order: mechanics (vectors, points), heat.
    if (physics.mechanics())
      physics.mechanics()->prepare_checkpoint();
    if (physics.heat())
      physics.heat()->prepare_checkpoint();
    triangulation->save(dir + "/mesh");
    {
      // The mesh files save() wrote (complete: it is collective), hashed by
      // all processes.
      std::vector<std::string> names;
      if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
        for (const auto &f : std::filesystem::directory_iterator(dir))
          if (f.path().filename().string().rfind("mesh", 0) == 0)
            names.push_back(f.path().filename().string());
      names = Utilities::MPI::broadcast(mpi_communicator, names, 0);
      std::sort(names.begin(), names.end());
      std::vector<std::string> paths;
      for (const auto &name : names)
        paths.push_back(dir + "/" + name);
      const auto prints = chunked_fingerprints(paths, mpi_communicator, true);
      saved_fingerprints.clear();
      for (unsigned int i = 0; i < names.size(); ++i)
        saved_fingerprints[names[i]] = prints[i];
    }
    std::ostringstream contact_state; // collective
    if (!physics.contact_problem().empty())
      physics.contact_problem().save(contact_state);
    std::map<std::string, std::string> output_state;
    for (const auto &o : outputs)
      o->save(output_state);
    // A failure (disk full, no permission) on process 0 must end every
    // process at once, not leave the others in a barrier: the reason is
    // broadcast, and the previous good checkpoint stays in place.
    std::string failure;
    if (Utilities::MPI::this_mpi_process(mpi_communicator) == 0)
      try
        {
          write_state(dir + "/state.txt", t, dt, contact_state.str(), output_state);
          std::filesystem::remove_all(final_dir + ".old");
          if (std::filesystem::exists(final_dir))
            std::filesystem::rename(final_dir, final_dir + ".old");
          std::filesystem::rename(dir, final_dir);
          std::filesystem::remove_all(final_dir + ".old");
        }
      catch (const std::exception &e)
        {
          failure = e.what();
        }
    failure = Utilities::MPI::broadcast(mpi_communicator, failure, 0);
    if (!failure.empty())
      throw SimulationError(failure + "; the previous checkpoint in " + final_dir +
                            " is kept");
  }

  template <int dim>
  void Simulator<dim>::write_state(const std::string &filename, const double t, const double dt,
                                   const std::string                        &contact_state,
                                   const std::map<std::string, std::string> &output_state) const
  {
    // ANVIL_CHECKPOINT_FAULT=full:N (tests only): the N-th checkpoint's state
    // file is written to /dev/full, a real "no space left on device".
    static unsigned int written = 0;
    ++written;
    const char *fault = std::getenv("ANVIL_CHECKPOINT_FAULT");
    if (fault && std::string(fault) == "full:" + std::to_string(written))
      std::filesystem::create_symlink("/dev/full", filename);
    std::ofstream out(filename);
    out << std::setprecision(17) << checkpoint_magic << ' ' << checkpoint_format << '\n';
    auto entry = [&](const std::string &key, const auto &value) {
      out << key << ' ' << value << '\n';
    };
    entry("scene", scene.filename());
    entry("dimension", dim);
    entry("coupling", coupling);
    entry("bodies", joined(scene.body_names()));
    entry("contact_pairs", joined(scene.contact_pair_names()));
    entry("partition", geometry.partition_kind());
    entry("processes", Utilities::MPI::n_mpi_processes(mpi_communicator));
    entry("time", t);
    entry("time_step", dt);
    entry("steps", statistics.steps);
    entry("cut_backs", statistics.cut_backs);
    entry("newton_iterations", statistics.newton_iterations);
    entry("linear_iterations", statistics.linear_iterations);
    entry("heat_internal_steps", statistics.heat_internal_steps);
    entry("heat_nonlinear_iterations", statistics.heat_nonlinear_iterations);
    entry("staggered_iterations", statistics.staggered_iterations);
    if (physics.mechanics())
      for (const auto &[key, value] : physics.mechanics()->checkpoint_scalars())
        entry("mechanics." + key, value);
    if (auto *heat = physics.heat())
      {
        for (const auto &[key, value] : heat->checkpoint_scalars())
          entry("heat." + key, value);
        const auto &a = physics.heat_audit();
        entry("heat_audit.initial_content", physics.initial_heat_content());
        entry("heat_audit.plastic", a.plastic);
        entry("heat_audit.thermoelastic", a.thermoelastic);
        entry("heat_audit.contact", a.contact);
      }
    for (const auto &[key, value] : output_state)
      entry("output." + key, value);
    // The mesh files saved beside this file (write_checkpoint() hashed them).
    for (const auto &[name, print] : saved_fingerprints)
      entry("chunks." + name, print);
    if (!physics.contact_problem().empty())
      out << "contact\n" << contact_state;
    out.flush();
    if (!out)
      throw SimulationError("could not write the checkpoint " + filename + ": " +
                            std::strerror(errno));
  }

  template <int dim>
  void Simulator<dim>::read_checkpoint(double &t, double &dt)
  {
    if (physics.mechanics())
      physics.mechanics()->load_checkpoint();
    if (physics.heat())
      physics.heat()->load_checkpoint();
    const StateFile state(restart_directory + "/state.txt");
    try
      {
        t                                    = state.number("time");
        dt                                   = state.number("time_step");
        statistics.steps                     = state.number("steps");
        statistics.cut_backs                 = state.number("cut_backs");
        statistics.newton_iterations         = state.number("newton_iterations");
        statistics.linear_iterations         = state.number("linear_iterations");
        statistics.heat_internal_steps       = state.number("heat_internal_steps");
        statistics.heat_nonlinear_iterations = state.number("heat_nonlinear_iterations");
        statistics.staggered_iterations      = state.number("staggered_iterations");
        if (physics.mechanics())
          physics.mechanics()->restore_scalars(state.group("mechanics"));
        if (physics.heat())
          {
            physics.heat()->restore_scalars(state.group("heat"));
            const auto audit                = state.group("heat_audit");
            physics.initial_heat_content()  = named_value(audit, "initial_content");
            physics.heat_audit().plastic       = named_value(audit, "plastic");
            physics.heat_audit().thermoelastic = named_value(audit, "thermoelastic");
            physics.heat_audit().contact       = named_value(audit, "contact");
          }
        std::map<std::string, std::string> output_state;
        for (const auto &[key, value] : state.entries)
          if (key.rfind("output.", 0) == 0)
            output_state[key.substr(7)] = value;
        for (auto &o : outputs)
          o->load(output_state);
        if (!physics.contact_problem().empty())
          {
            std::istringstream in(state.contact);
            physics.contact_problem().load(in);
            if (!in)
              throw InputError("cannot read the contact state");
          }
      }
    catch (const InputError &e)
      {
        throw InputError(restart_directory + "/state.txt: " + e.what());
      }
    current_time = t;
  }

#define INSTANTIATE(dim)                                                                           \
  template void Simulator<dim>::check_checkpoint() const;                                        \
  template void Simulator<dim>::write_checkpoint(double, double);                                \
  template void Simulator<dim>::write_state(const std::string &, double, double,                 \
                                            const std::string &,                                 \
                                            const std::map<std::string, std::string> &) const;   \
  template void Simulator<dim>::read_checkpoint(double &, double &);
  ANVIL_INSTANTIATE(INSTANTIATE)
#undef INSTANTIATE
} // namespace anvil
