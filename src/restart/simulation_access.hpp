// The one door into Simulation's private members, for the restart code only: a dump must hold
// every member that carries state from one cycle to the next, and a restart must put them back.
#pragma once

#include "io/restart/hdf5_file.hpp"
#include "solver/simulation.hpp"

namespace rf::restart {

class Dumper;

struct SimulationAccess {
  using Simulation = solver::Simulation;

  static const model::Model& model(const Simulation& s) { return s.model_; }
  static const solver::NodeIndex& node_index(const Simulation& s) { return s.node_index_; }
  static solver::State& state(Simulation& s) { return s.state_; }
  static solver::RigidSystem& rigid(Simulation& s) { return s.rigid_; }
  static solver::Boundary& boundary(Simulation& s) { return s.boundary_; }
  static solver::Vec3Array& v_previous(Simulation& s) { return s.v_previous_; }
  static const std::filesystem::path& output_directory(const Simulation& s) {
    return s.options_.output_directory;
  }
  static Dumper* dumper(Simulation& s) { return s.dumper_.get(); }
  // Distributed runs (docs/parallel.md): every rank takes part in a dump, rank 0 writes it.
  static bool distributed(const Simulation& s) { return s.distribution_ != nullptr; }
  static bool writes_files(const Simulation& s);
  static void prepare_dump_on_ranks(Simulation& s) { s.prepare_restart_dump_on_ranks(); }
  static void finish_dump_on_ranks(Simulation& s) { s.finish_restart_dump_on_ranks(); }
  // After a distributed run's restart has read the dump (restart.cpp): each rank's own force
  // slots and share of the part work; `dumped_ranks` is the dumped run's rank count.
  static void resume_on_ranks(Simulation& s, const io::h5::Group& members, int dumped_ranks);
  static bool end_reached(const Simulation& s) { return s.end_reached(); }
  static std::int64_t end_cycle(const Simulation& s) { return s.end_cycle_; }
  static void set_end(Simulation& s, double end_time, std::int64_t end_cycle) {
    s.end_time_ = end_time;
    s.end_cycle_ = end_cycle;
  }

  // The members of Simulation itself: time-step history, energy account, termination, output
  // schedules. One group each way, so a member added to Simulation is added in one place here.
  static void write_members(Simulation& s, const io::h5::Group& g);
  static void read_members(Simulation& s, const io::h5::Group& g);
  // Output files: flushed, their sizes (where a restart cuts them) and the VTU frame list.
  static void write_output(Simulation& s, const io::h5::Group& g);
  static void read_output(Simulation& s, const io::h5::Group& g);
  // Part switching, rigid walls and sensors: what each carries from cycle to cycle.
  static void write_features(Simulation& s, const io::h5::Group& g);
  static void read_features(Simulation& s, const io::h5::Group& g);
  struct Frames {
    std::vector<double> times;
    std::vector<std::string> files;  // file names in the output directory
  };
  static Frames read_frames(const io::h5::Group& g);
};

}  // namespace rf::restart
