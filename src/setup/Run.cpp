// The two commands of granflow, run after PetscInitialize (apps/granflow.cpp parses the command
// line): `check` validates a case and prints its report; `run` runs it (or continues it from a
// checkpoint), writing the provenance, the log and the results into its output folder. Every
// failure becomes a message and an exit code (core/Error.hpp).
#include "setup/Run.hpp"

#include <petscsys.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <vector>

#include "core/Error.hpp"
#include "core/Log.hpp"
#include "core/Profile.hpp"
#include "core/Signal.hpp"
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

namespace fs = std::filesystem;

// Rank 0's text on every rank (collective).
std::string from_root(MPI_Comm comm, std::string text) {
  int len = static_cast<int>(text.size());
  MPI_Bcast(&len, 1, MPI_INT, 0, comm);
  text.resize(static_cast<std::size_t>(len));
  MPI_Bcast(text.data(), len, MPI_CHAR, 0, comm);
  return text;
}

// Collective: a SIGINT/SIGTERM received during the start-up, before the run folder is touched,
// stops the command here (nothing written, nothing to continue from).
void stop_if_signalled(const char* stage) {
  int sig = signal::stop_signal();
  MPI_Allreduce(MPI_IN_PLACE, &sig, 1, MPI_INT, MPI_MAX, PETSC_COMM_WORLD);
  if (sig)
    throw Interrupted(std::string("stopped by ") + signal::name(sig) + " during the start-up (" +
                      stage + "), before anything was written: no output folder, no checkpoint; "
                      "run the command again to start");
}

// Whether PETSc holds options the user gave (command line after --, solver.petsc_options,
// PETSC_OPTIONS, .petscrc): a PETSc failure of the user-input kind is then theirs.
bool petsc_options_given() {
  char* opts = nullptr;
  PetscOptionsGetAll(nullptr, &opts);
  const bool any = opts && std::string(opts).find_first_not_of(" \t") != std::string::npos;
  PetscFree(opts);
  return any;
}

std::string petsc_options_text() {
  char* opts = nullptr;
  PetscOptionsGetAll(nullptr, &opts);
  std::string s = opts ? opts : "";
  PetscFree(opts);
  while (!s.empty() && s.back() == ' ') s.pop_back();
  return s;
}

// A folder that a granflow run wrote: its command.txt records the version (every run writes
// it first, with case.toml). Only such a folder may be removed by --overwrite.
bool is_run_folder(const std::string& dir) {
  std::ifstream in(dir + "/command.txt");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("granflow version: ", 0) == 0) return fs::is_regular_file(dir + "/case.toml");
  return false;
}

// Rank 0 checks the output folder of a new run, before any computation: it must not exist,
// be empty, or (with --overwrite) be a granflow run folder. An InputError on every rank.
void check_out_folder(const std::string& out, bool overwrite) {
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  std::string err;
  if (rank == 0) {
    std::error_code ec;
    const fs::path p(out);
    if (fs::exists(p, ec) && !fs::is_directory(p, ec)) {
      err = "--out " + out + ": is a file, not a folder: give the path of a new folder";
    } else if (fs::is_directory(p, ec)) {
      const bool empty = fs::is_empty(p, ec);
      if (ec)
        err = "--out " + out + ": cannot read the folder: " + ec.message();
      else if (!empty && !is_run_folder(out))
        err = "--out " + out + ": the folder exists, is not empty and is not a granflow run "
              "folder (no command.txt and case.toml of a run): choose a new or empty folder";
      else if (!empty && !overwrite)
        err = "--out " + out + ": holds a granflow run already (" + out + "/command.txt): "
              "choose another folder, continue it with `granflow run --restart " + out +
              "`, or replace it with --overwrite (which removes the old run first)";
    } else {
      // A parent that is a file cannot hold the folder.
      for (fs::path q = p.parent_path(); !q.empty(); q = q.parent_path()) {
        if (fs::exists(q, ec) && !fs::is_directory(q, ec)) {
          err = "--out " + out + ": " + q.string() + " is a file, not a folder";
          break;
        }
        if (q == q.parent_path()) break;
      }
    }
  }
  err = from_root(PETSC_COMM_WORLD, err);
  if (!err.empty()) throw InputError(err);
}

// --overwrite: rank 0 removes the old run (checked by check_out_folder to be one).
void remove_old_run(const std::string& out) {
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  std::string err;
  if (rank == 0 && is_run_folder(out)) {
    std::error_code ec;
    fs::remove_all(out, ec);
    if (ec) err = "--overwrite: cannot remove the old run in " + out + ": " + ec.message();
    else log::message("granflow: --overwrite: removed the old run in " + out);
  }
  io::raise_on_all_ranks(PETSC_COMM_WORLD, err);
}

// The memory the machines of the ranks have available, bytes (each machine counted once: its
// ranks share it). 0 if unknown.
double machines_memory() {
  char name[MPI_MAX_PROCESSOR_NAME] = {};
  int len = 0;
  MPI_Get_processor_name(name, &len);
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  std::vector<char> names(rank == 0 ? static_cast<std::size_t>(size) * MPI_MAX_PROCESSOR_NAME : 1);
  double mine = prof::available_memory_bytes();
  std::vector<double> avail(rank == 0 ? size : 1);
  MPI_Gather(name, MPI_MAX_PROCESSOR_NAME, MPI_CHAR, names.data(), MPI_MAX_PROCESSOR_NAME,
             MPI_CHAR, 0, PETSC_COMM_WORLD);
  MPI_Gather(&mine, 1, MPI_DOUBLE, avail.data(), 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  double total = 0;
  if (rank == 0) {
    std::vector<std::string> seen;
    for (int r = 0; r < size; ++r) {
      const std::string host(&names[static_cast<std::size_t>(r) * MPI_MAX_PROCESSOR_NAME]);
      if (std::find(seen.begin(), seen.end(), host) != seen.end()) continue;
      seen.push_back(host);
      if (avail[r] <= 0) {
        total = 0;  // one machine unknown: the sum would be a guess
        break;
      }
      total += avail[r];
    }
  }
  MPI_Bcast(&total, 1, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  return total;
}

// The processor grid asked for with -da_processors_x / -da_processors_y (0: PETSc decides).
std::array<int, 2> processor_grid_options() {
  PetscInt px = 0, py = 0;
  PetscBool fx = PETSC_FALSE, fy = PETSC_FALSE;
  try {
    GF_PETSC(PetscOptionsGetInt(nullptr, nullptr, "-da_processors_x", &px, &fx));
    GF_PETSC(PetscOptionsGetInt(nullptr, nullptr, "-da_processors_y", &py, &fy));
  } catch (const PetscFailure& e) {
    throw InputError("a PETSc option was refused (the options given: " + petsc_options_text() +
                     "): " + e.what());
  }
  return {fx ? static_cast<int>(px) : 0, fy ? static_cast<int>(py) : 0};
}

// The checkpoint of a restart, read and checked before anything in the folder changes: the
// latest, or checkpoint.prev if the latest is damaged (said), else an IoError naming both.
std::string restart_checkpoint(const std::string& out, io::CheckpointHeader& header, int rank) {
  std::string dir = io::find_checkpoint(PETSC_COMM_WORLD, out);
  if (dir.empty())
    throw InputError("--restart " + out + ": no checkpoint in this folder (" + out +
                     "/checkpoint): the run stopped before writing one");
  try {
    header = io::read_checkpoint_header(PETSC_COMM_WORLD, dir);
    return dir;
  } catch (const io::IoError& e) {
    const std::string prev = out + "/checkpoint.prev";
    int has_prev = rank == 0 && dir != prev && fs::is_directory(prev);
    MPI_Bcast(&has_prev, 1, MPI_INT, 0, PETSC_COMM_WORLD);
    if (!has_prev)
      throw io::IoError(std::string(e.what()) + " (and there is no " + prev +
                        " to fall back to)");
    try {
      header = io::read_checkpoint_header(PETSC_COMM_WORLD, prev);
    } catch (const io::IoError& e2) {
      throw io::IoError(std::string(e.what()) + "; the previous checkpoint is damaged too: " +
                        e2.what());
    }
    if (rank == 0)
      log::message("granflow: warning: " + dir + " is damaged (" + e.what() +
                   "); continuing from the previous checkpoint, " + prev + " (t = " +
                   std::to_string(header.get_double("t")) + " s, step " +
                   std::to_string(header.get_int("step")) + ")");
    return prev;
  }
}

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
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw io::IoError("cannot create the output folder " + dir + ": " + ec.message());
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
  // A grid that the machine or PETSc cannot hold, or that the ranks cut too thin: refused by
  // both commands, before any computation.
  const double avail = machines_memory();
  const auto [da_px, da_py] = processor_grid_options();
  const auto problems = resource_problems(c, size, avail, da_px, da_py);
  if (!problems.empty()) {
    std::string m;
    for (const auto& p : problems) m += (m.empty() ? "" : "\n") + p;
    throw InputError(m);
  }
  if (a.command == "check") {
    if (rank == 0) std::cout << log::printable(describe_case(c, size, avail));
    return kExitOk;
  }
  const bool restart = !a.restart_dir.empty();
  std::string out = restart ? a.restart_dir : a.out_dir;
  if (out.empty()) out = "out/" + fs::path(a.case_file).stem().string();
  if (!restart) check_out_folder(out, a.overwrite);

  // A restart reads and checks everything before it changes a file in the folder.
  std::string ckpt_dir;
  io::CheckpointHeader header;
  if (restart) {
    ckpt_dir = restart_checkpoint(out, header, rank);
    check_restart_case(out, ckpt_dir,
                       io::read_checkpoint_file(PETSC_COMM_WORLD, ckpt_dir, "case.toml"),
                       c.resolved_toml);
  }
  stop_if_signalled("reading the case");

  // The model. PETSc reads its options here (the solvers' KSPSetFromOptions, the processor
  // grid): a PETSc failure now, with options given, is theirs (a type name PETSc does not
  // know, a value that is not a number).
  std::unique_ptr<Grid> grid;
  std::unique_ptr<State> state;
  std::unique_ptr<TimeStepper> stepper;
  try {
    grid = std::make_unique<Grid>(PETSC_COMM_WORLD, c.nx, c.ny, c.domain.Lx, c.domain.Ly,
                                  c.periodic_x);
    state = std::make_unique<State>(*grid);
    initial_levelset(*grid, c, state->phi);
    initial_fraction(*grid, c, state->frac);
    initial_velocity(*grid, c, state->vel, state->vel_old);
    stepper = make_stepper(*grid, c);
  } catch (const PetscFailure& e) {
    if (!petsc_options_given()) throw;
    throw InputError("a PETSc option was refused (the options given, after -- or in "
                     "solver.petsc_options or PETSC_OPTIONS: " + petsc_options_text() + "): " +
                     e.what());
  }
  Simulation sim(*grid, *state, *stepper, run_from_case(c, out));
  sim.set_checkpoint_files({{"case.toml", c.resolved_toml}});
  if (restart) sim.restart(ckpt_dir, header);  // checks the grid and t_end, loads the fields
  stop_if_signalled("building the model");
  if (a.overwrite) remove_old_run(out);
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
  } catch (const PetscFailure& e) {
    // During the run, a type or a factorization PETSc cannot provide (read at the first
    // solve) is the options' doing too; anything else is ours.
    const int k = e.code();
    if (petsc_options_given() && (k == PETSC_ERR_ARG_UNKNOWN_TYPE || k == PETSC_ERR_USER_INPUT ||
                                  k == PETSC_ERR_MISSING_FACTOR)) {
      report(std::string("granflow: error in the PETSc options: ") + e.what() +
                 " (the options given: " + petsc_options_text() + ")",
             true);
      rc = kExitInput;
    } else {
      report(std::string("granflow: internal error (please report it): ") + e.what(), true);
      rc = kExitInternal;
    }
  } catch (const std::exception& e) {
    report(std::string("granflow: error: ") + e.what(), true);
    rc = kExitInternal;
  }
  return rc;
}

}  // namespace gf
