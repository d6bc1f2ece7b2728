// The two commands of granflow, run after PetscInitialize (apps/granflow.cpp parses the command
// line): `check` validates a case and prints its report; `run` runs it (or continues it from a
// checkpoint), writing the provenance, the log and the results into its output folder. Every
// failure becomes a message and an exit code (core/Error.hpp).
#include "setup/Run.hpp"

#include <petscsys.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "core/Error.hpp"
#include "core/Log.hpp"
#include "core/Version.hpp"
#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "io/Checkpoint.hpp"
#include "io/IoError.hpp"
#include "setup/Build.hpp"
#include "setup/Case.hpp"
#include "setup/Report.hpp"
#include "setup/Restart.hpp"
#include "sim/Simulation.hpp"

namespace gf {

namespace {

// The command line, version, ranks and PETSc options: one block per run (a restart appends
// its own below the original run's).
std::string provenance_block(const CaseConfig& c, int argc_all, char** argv_all, int nranks,
                             const std::string& title) {
  std::ostringstream f;
  f << title << "command:";
  for (int i = 0; i < argc_all; ++i) f << ' ' << argv_all[i];
  f << "\ngranflow version: " << git_version() << "\nMPI ranks: " << nranks
    << "\ncase file: " << c.source << "\n";
  char* opts = nullptr;
  PetscOptionsGetAll(nullptr, &opts);
  f << "PETSc options: " << (opts ? opts : "") << "\n";
  PetscFree(opts);
  return f.str();
}

// Everything the output folder needs to reproduce the run.
void write_provenance(const CaseConfig& c, const std::string& dir, int argc_all,
                      char** argv_all, int nranks, bool restart) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  const std::string err = write_resolved_case(c, dir + "/case.toml");
  if (!err.empty()) throw io::IoError(err);
  std::ofstream f(dir + "/command.txt", restart ? std::ios::app : std::ios::trunc);
  f << provenance_block(c, argc_all, argv_all, nranks, restart ? "\nrestart\n" : "");
  if (!f) throw io::IoError("cannot write " + dir + "/command.txt");
}

// The case of the command (a restart's is DIR/case.toml with the allowed --set changes), its
// warnings printed, and its PETSc options applied.
CaseConfig command_case(const CommandLine& a, int rank) {
  const bool restart = !a.restart_dir.empty();
  if (restart) check_restart_request(a.restart_dir, a.sets);
  const CaseConfig c = load_case(restart ? a.restart_dir + "/case.toml" : a.case_file, a.sets);
  // A resolved case.toml sets every key, so its "set but unused" warnings would be noise:
  // the original run reported the warnings of the case as written.
  if (rank == 0 && !restart)
    for (const auto& w : c.warnings) std::cerr << "granflow: warning: " << w << "\n";
  // The case's PETSc options first, then the command line's again so that they win.
  if (!c.solver.petsc_options.empty()) {
    GF_PETSC(PetscOptionsInsertString(nullptr, c.solver.petsc_options.c_str()));
    GF_PETSC(PetscOptionsInsertArgs(nullptr, a.petsc_argc - 1, a.petsc_argv + 1));
  }
  return c;
}

// The provenance and the log of the output folder, and the first message of the run.
void open_run_folder(const CaseConfig& c, const CommandLine& a, const std::string& out, int size,
                     const std::string& ckpt_dir, const io::CheckpointHeader& header) {
  const bool restart = !a.restart_dir.empty();
  write_provenance(c, out, a.argc_all, a.argv_all, size, restart);
  const std::string err = log::open(out + "/granflow.log", restart);
  if (!err.empty()) std::cerr << "granflow: warning: " << err << " (no log file)\n";
  log::to_file(provenance_block(c, a.argc_all, a.argv_all, size, restart ? "restart\n" : ""));
  if (!restart)
    for (const auto& w : c.warnings) log::to_file("granflow: warning: " + w);
  std::ostringstream m;
  m << "granflow: " << c.title << ": " << c.nx << " x " << c.ny << " cells on " << size
    << " rank(s), ";
  if (restart)
    m << "restarted from " << ckpt_dir << " at t = " << header.get_double("t") << " s (step "
      << header.get_int("step") << ")";
  else
    m << "from t = 0";
  m << " to t = " << c.time.t_end << " s, output in " << out;
  log::message(m.str());
}

int run_or_check(const CommandLine& a) {
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (a.list) {
    if (rank == 0) print_case_help(std::cout);
    return kExitOk;
  }
  const CaseConfig c = command_case(a, rank);
  if (a.command == "check") {
    if (rank == 0) std::cout << describe_case(c, size);
    return kExitOk;
  }
  const bool restart = !a.restart_dir.empty();
  std::string out = restart ? a.restart_dir : a.out_dir;
  if (out.empty()) out = "out/" + std::filesystem::path(a.case_file).stem().string();

  // A restart reads and checks everything before it changes a file in the folder.
  std::string ckpt_dir;
  io::CheckpointHeader header;
  if (restart) {
    ckpt_dir = io::find_checkpoint(PETSC_COMM_WORLD, out);
    if (ckpt_dir.empty())
      throw InputError("--restart " + out + ": no checkpoint in this folder (" + out +
                       "/checkpoint): the run stopped before writing one");
    header = io::read_checkpoint_header(PETSC_COMM_WORLD, ckpt_dir);
    check_restart_case(out, ckpt_dir,
                       io::read_checkpoint_file(PETSC_COMM_WORLD, ckpt_dir, "case.toml"),
                       c.resolved_toml);
  }

  Grid grid(PETSC_COMM_WORLD, c.nx, c.ny, c.domain.Lx, c.domain.Ly, c.periodic_x);
  State state(grid);
  initial_levelset(grid, c, state.phi);
  initial_fraction(grid, c, state.frac);
  initial_velocity(grid, c, state.vel, state.vel_old);
  const auto stepper = make_stepper(grid, c);
  Simulation sim(grid, state, *stepper, run_from_case(c, out));
  sim.set_checkpoint_files({{"case.toml", c.resolved_toml}});
  if (restart) sim.restart(ckpt_dir, header);  // checks the grid and t_end, loads the fields
  if (rank == 0) open_run_folder(c, a, out, size, ckpt_dir, header);
  MPI_Barrier(PETSC_COMM_WORLD);
  const RunSummary s = sim.run();
  if (rank == 0) {
    std::ostringstream m;
    m << "granflow: done, " << s.steps << " steps in " << s.wall_s << " s ("
      << (s.steps ? s.wall_s / s.steps : 0.0) << " s/step), volume change "
      << s.volume_change_pct << " %";
    log::message(m.str());
  }
  return kExitOk;
}

}  // namespace

int execute(const CommandLine& cl) {
  int rc = kExitOk;
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  // Messages of collective failures come from rank 0 only (every rank has the same text);
  // they also go to the log once it is open.
  auto report = [&](const std::string& m, bool all_ranks) {
    if (rank == 0) log::message(m);
    else if (all_ranks) std::cerr << m << "\n";
  };
  try {
    rc = run_or_check(cl);
  } catch (const InputError& e) {
    report(std::string("granflow: error in the case:\n") + e.what(), false);
    rc = kExitInput;
  } catch (const RunError& e) {
    report(std::string("granflow: the run failed: ") + e.what(), false);
    rc = kExitRunFailure;
  } catch (const Interrupted& e) {
    report(std::string("granflow: ") + e.what(), false);
    rc = kExitInterrupted;
  } catch (const io::IoError& e) {
    report(std::string("granflow: file error: ") + e.what(), true);
    rc = kExitIo;
  } catch (const std::exception& e) {
    report(std::string("granflow: error: ") + e.what(), true);
    rc = kExitInternal;
  }
  return rc;
}

}  // namespace gf
