#include "restart/restart.hpp"

#include <fmt/format.h>
#include <omp.h>

#include <fstream>
#include <system_error>

#include "io/keyword/reader.hpp"
#include "io/keyword/restart_deck.hpp"
#include "model/error.hpp"
#include "model/error_context.hpp"
#include "output/d3plot_writer.hpp"
#include "output/output_directory.hpp"
#include "parallel/communicator.hpp"
#include "restart/simulation_access.hpp"

namespace rf::restart {

namespace {

namespace fs = std::filesystem;

io::Dialect dialect_of(const std::string& name) {
  if (name == "impetus") return io::Dialect::Impetus;
  if (name == "lsdyna") return io::Dialect::LsDyna;
  return io::Dialect::Auto;
}

bool same_directory(const fs::path& a, const fs::path& b) {
  std::error_code ec;
  const bool same = fs::equivalent(a, b, ec);
  return !ec && same;
}

void copy_prefix(const fs::path& from, const fs::path& to, std::int64_t bytes) {
  std::ifstream in(from, std::ios::binary);
  std::ofstream out(to, std::ios::binary | std::ios::trunc);
  std::vector<char> buffer(1 << 20);
  std::int64_t left = bytes;
  while (left > 0 && in) {
    const auto chunk = static_cast<std::streamsize>(
        std::min<std::int64_t>(left, static_cast<std::int64_t>(buffer.size())));
    in.read(buffer.data(), chunk);
    out.write(buffer.data(), in.gcount());
    left -= in.gcount();
  }
  if (left != 0 || !out) {
    throw std::runtime_error(
        fmt::format("cannot copy '{}' to '{}' for the restart", from.string(), to.string()));
  }
}

// Where a CSV file is continued: its size at the dump when the file from the dumped run is there
// (copied into a new output directory first), else -1 (started anew, with a warning).
std::int64_t continue_csv(const fs::path& from_dir, const fs::path& to_dir, bool same,
                          const std::string& name, std::int64_t bytes,
                          std::vector<model::Warning>& warnings) {
  if (bytes < 0) return -1;
  const fs::path source = from_dir / name;
  std::error_code ec;
  const auto size = fs::file_size(source, ec);
  if (ec || size < static_cast<std::uintmax_t>(bytes)) {
    warnings.push_back({{},
                        fmt::format("{} of the dumped run is missing or shorter than at the "
                                    "dump ({} bytes); it is started anew and holds only rows "
                                    "from the restart on",
                                    source.string(), bytes)});
    return -1;
  }
  if (!same) copy_prefix(source, to_dir / name, bytes);
  return bytes;
}

// Every dynamic quantity of the simulation from the dump, the model having been rebuilt from the
// dump's deck; on ranks, each rank's own part of what the dump holds gathered.
void read_simulation_state(solver::Simulation& sim, const io::h5::Group& root,
                           const DumpHeader& header) {
  const model::Model& sim_model = SimulationAccess::model(sim);
  solver::State& state = SimulationAccess::state(sim);
  read_nodes(root.group("nodes"), state.nodes, SimulationAccess::v_previous(sim));
  read_hex_blocks(root.group("blocks"), state.hex_blocks);
  if (!state.discrete_blocks.empty()) {
    if (!root.has("discrete")) {
      root.fail("discrete",
                "is missing: the dump has no discrete-element state, the model "
                "rebuilt from its deck has springs or dampers");
    }
    read_discrete_blocks(root.group("discrete"), state.discrete_blocks);
  }
  // Shells, beams and the nodal rotations: present in the dump exactly when the model has them.
  const auto read_family = [&](const char* group, bool in_model, const char* what, auto read) {
    if (in_model != root.has(group)) {
      root.fail(group, fmt::format("is {}: the dump {} {}, the model rebuilt from its deck {}",
                                   in_model ? "missing" : "unexpected", in_model ? "has no" : "has",
                                   what, in_model ? "has some" : "has none"));
    }
    if (in_model) read(root.group(group));
  };
  read_family("shells", !state.shell_blocks.empty(), "shell elements",
              [&](const io::h5::Group& g) { read_shell_blocks(g, state.shell_blocks); });
  read_family("beams", !state.beam_blocks.empty(), "beam elements",
              [&](const io::h5::Group& g) { read_beam_blocks(g, state.beam_blocks); });
  read_family("rotations", !state.rotations.empty(), "nodes with rotations",
              [&](const io::h5::Group& g) { read_rotations(g, state.rotations); });
  read_rigid_system(root.group("rigid"), SimulationAccess::rigid(sim), sim_model,
                    state.nodes.size());
  read_boundary(root.group("boundary"), SimulationAccess::boundary(sim), sim_model);
  SimulationAccess::read_members(sim, root.group("simulation"));
  SimulationAccess::read_output(sim, root.group("output"));
  SimulationAccess::read_features(sim, root.group("features"));
  SimulationAccess::resume_on_ranks(sim, root.group("output"), header.ranks);
}

// The dump schedule continued (or --dump-every's), and the restart deck's termination and
// switches.
void restart_dumps_and_deck(solver::Simulation& sim, ModelInput input, const io::h5::Group& root,
                            const RestartOptions& options,
                            const std::optional<io::RestartDeck>& deck) {
  const solver::State& state = SimulationAccess::state(sim);
  DumpSchedule schedule = read_dump_schedule(root.group("dumps"));
  if (options.dump_interval) {
    schedule.interval = std::max(0.0, *options.dump_interval);
    schedule.next = state.time + schedule.interval;
  }
  sim.enable_restart_dumps(std::make_unique<Dumper>(std::move(input), schedule));

  if (deck) {
    double end_time = sim.end_time();
    std::int64_t end_cycle = SimulationAccess::end_cycle(sim);
    if (deck->end_time) {
      if (*deck->end_time <= state.time) {
        throw InputError(
            model::context_of(deck->termination_where, "ENDTIM"),
            fmt::format("{} does not lie after the dump's time {}", *deck->end_time, state.time));
      }
      end_time = *deck->end_time;
    }
    if (deck->end_cycle) {
      if (*deck->end_cycle <= state.cycle) {
        throw InputError(model::context_of(deck->termination_where, "ENDCYC"),
                         fmt::format("{} does not lie after the dump's cycle {}", *deck->end_cycle,
                                     state.cycle));
      }
      end_cycle = *deck->end_cycle;
    }
    SimulationAccess::set_end(sim, end_time, end_cycle);
    sim.apply_restart_switches(deck->switches);
  }
}

}  // namespace

Restarted restart_from_dump(const RestartOptions& options) {
  Restarted result;
  const io::h5::File file = io::h5::File::open(options.dump);
  result.header = read_dump_header(file, options.dump);
  const io::h5::Group root = file.root();
  if (result.header.rigidflex_version != RIGIDFLEX_VERSION) {
    result.warnings.push_back(
        {{},
         fmt::format("the dump was written by RigidFlex {}, this is {}: the continued run may "
                     "differ from one made with a single version",
                     result.header.rigidflex_version, RIGIDFLEX_VERSION)});
  }

  // The model, from the deck texts in the dump.
  ModelInput input = read_model_input(root.group("model"));
  io::ReadOptions read_options;
  read_options.dialect = dialect_of(input.dialect);
  read_options.parameter_overrides = input.overrides;
  read_options.file_texts = &input.files;
  // The dumped run was accepted as it was (with --ignore-unsupported if it had to be): a
  // restart continues that model.
  read_options.ignore_unsupported = true;
  model::Model model = io::read_deck(input.main_deck, read_options);

  std::optional<io::RestartDeck> deck;
  if (!options.restart_deck.empty()) deck = io::read_restart_deck(options.restart_deck, model);

  // Thread count: the dumped run's unless asked otherwise (element kernels combine per-thread
  // partial sums in thread order, so another count changes the last digits of energies).
  result.threads = options.threads > 0 ? options.threads : std::max(1, result.header.threads);
  if (options.threads > 0 && options.threads != result.header.threads) {
    result.warnings.push_back(
        {{},
         fmt::format("the dumped run used {} thread(s), this restart uses {}: results can "
                     "differ from an uninterrupted run in the last digits",
                     result.header.threads, options.threads)});
  }
  omp_set_num_threads(result.threads);
  // Rank count: a distributed run continues bit for bit on as many ranks (the same partition,
  // each rank its own share of the per-rank sums); on another count the partition differs.
  const int ranks = parallel::world().size();
  if (ranks != result.header.ranks) {
    result.warnings.push_back(
        {{},
         fmt::format("the dumped run used {} MPI rank(s), this restart uses {}: results can "
                     "differ from an uninterrupted run in the last digits",
                     result.header.ranks, ranks)});
  }

  const io::h5::Group output = root.group("output");
  solver::SimulationOptions sim_options;
  sim_options.from_dump = true;
  if (!options.writes_files) {
    // A follower rank: the state only, no output directory, no file.
    sim_options.write_fields = false;
    result.simulation = std::make_unique<solver::Simulation>(std::move(model), sim_options);
    read_simulation_state(*result.simulation, root, result.header);
    restart_dumps_and_deck(*result.simulation, std::move(input), root, options, deck);
    return result;
  }

  // Output: the dump's directory unless -o says otherwise; CSV files cut at their dump sizes.
  fs::path dump_dir = options.dump.parent_path();
  if (dump_dir.empty()) dump_dir = ".";
  result.output_directory = options.output_directory.empty() ? dump_dir : options.output_directory;
  output::prepare_output_directory(result.output_directory);
  const bool same = same_directory(dump_dir, result.output_directory);
  sim_options.output_directory = result.output_directory;
  sim_options.write_fields = options.write_fields;
  sim_options.continuation.glstat =
      continue_csv(dump_dir, result.output_directory, same, "glstat.csv",
                   output.get_int("glstat_bytes"), result.warnings);
  sim_options.continuation.nodout =
      continue_csv(dump_dir, result.output_directory, same, "nodout.csv",
                   output.get_int("nodout_bytes"), result.warnings);
  sim_options.continuation.rbdout =
      continue_csv(dump_dir, result.output_directory, same, "rbdout.csv",
                   output.get_int("rbdout_bytes"), result.warnings);
  sim_options.continuation.switches =
      continue_csv(dump_dir, result.output_directory, same, "switch.csv",
                   output.get_int("switch_bytes"), result.warnings);
  sim_options.continuation.sensor =
      continue_csv(dump_dir, result.output_directory, same, "sensor.csv",
                   output.get_int("sensor_bytes"), result.warnings);
  sim_options.continuation.rwforc =
      continue_csv(dump_dir, result.output_directory, same, "rwforc.csv",
                   output.get_int("rwforc_bytes"), result.warnings);
  sim_options.continuation.rcforc =
      output.has_attribute("rcforc_bytes")
          ? continue_csv(dump_dir, result.output_directory, same, "rcforc.csv",
                         output.get_int("rcforc_bytes"), result.warnings)
          : -1;
  if (output.has_attribute("modal_bytes")) {
    sim_options.continuation.modal =
        continue_csv(dump_dir, result.output_directory, same, "modal.csv",
                     output.get_int("modal_bytes"), result.warnings);
  }
  // Per-part and per-element histories (absent in dumps of older versions).
  const std::pair<const char*, std::int64_t*> histories[] = {
      {"matsum", &sim_options.continuation.matsum},
      {"spcforc", &sim_options.continuation.spcforc},
      {"elout", &sim_options.continuation.elout},
      {"secforc", &sim_options.continuation.secforc},
      {"elout_shell", &sim_options.continuation.elout_shell},
      {"jntforc", &sim_options.continuation.jntforc},
      {"swforc", &sim_options.continuation.swforc},
      {"erosion", &sim_options.continuation.erosion}};
  for (const auto& [name, target] : histories) {
    const std::string attribute = std::string(name) + "_bytes";
    if (!output.has_attribute(attribute)) continue;
    *target = continue_csv(dump_dir, result.output_directory, same, std::string(name) + ".csv",
                           output.get_int(attribute), result.warnings);
  }
  if (!same && options.write_fields) {
    // The LS-DYNA d3plot family; the restart cuts it back to the dump's states.
    for (int k = 0; k < 100; ++k) {
      const std::string name = output::D3plotWriter::member_name(k);
      std::error_code ec;
      if (!fs::exists(dump_dir / name, ec)) break;
      fs::copy_file(dump_dir / name, result.output_directory / name,
                    fs::copy_options::overwrite_existing, ec);
    }
    // Earlier frames, so that the new directory's frames.pvd is complete.
    for (const std::string& name : SimulationAccess::read_frames(output).files) {
      std::error_code ec;
      // Rigid walls drawn beside the frame (walls_NNNN.vtu), when the model has walls.
      const std::string walls = output::FieldWriter::walls_file_of(name);
      if (fs::exists(dump_dir / walls, ec)) {
        fs::copy_file(dump_dir / walls, result.output_directory / walls,
                      fs::copy_options::overwrite_existing, ec);
      }
      fs::copy_file(dump_dir / name, result.output_directory / name,
                    fs::copy_options::overwrite_existing, ec);
      if (ec) {
        result.warnings.push_back(
            {{},
             fmt::format("frame {} of the dumped run could not be copied ({}); frames.pvd "
                         "lists it all the same",
                         (dump_dir / name).string(), ec.message())});
      }
    }
  }

  result.simulation = std::make_unique<solver::Simulation>(std::move(model), sim_options);
  read_simulation_state(*result.simulation, root, result.header);
  restart_dumps_and_deck(*result.simulation, std::move(input), root, options, deck);
  return result;
}

}  // namespace rf::restart
