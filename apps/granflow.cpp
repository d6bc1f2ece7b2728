// granflow: the command line.
//   granflow run CASE.toml [--set key=value ...] [--out DIR] [-- PETSc options]
//   granflow run --restart DIR [--set key=value ...] [-- PETSc options]
//   granflow check CASE.toml [--set key=value ...] [--list]
// Options after "--" go to PETSc's options database (e.g. -pres_ksp_monitor, -visc_pc_type).
#include <petscsys.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "core/Error.hpp"
#include "core/Version.hpp"
#include "core/Log.hpp"
#include "core/Signal.hpp"
#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "io/Checkpoint.hpp"
#include "io/IoError.hpp"
#include "setup/Build.hpp"
#include "setup/Case.hpp"
#include "setup/Report.hpp"
#include "setup/Restart.hpp"
#include "sim/Simulation.hpp"

namespace {

struct Args {
  std::string command, case_file, out_dir, restart_dir;
  std::vector<std::string> sets;
  bool list = false;
};

// The command line, version, ranks and PETSc options: one block per run (a restart appends
// its own below the original run's).
std::string provenance_block(const gf::CaseConfig& c, int argc_all, char** argv_all, int nranks,
                             const std::string& title) {
  std::ostringstream f;
  f << title << "command:";
  for (int i = 0; i < argc_all; ++i) f << ' ' << argv_all[i];
  f << "\ngranflow version: " << gf::git_version() << "\nMPI ranks: " << nranks
    << "\ncase file: " << c.source << "\n";
  char* opts = nullptr;
  PetscOptionsGetAll(nullptr, &opts);
  f << "PETSc options: " << (opts ? opts : "") << "\n";
  PetscFree(opts);
  return f.str();
}

// Everything the output folder needs to reproduce the run.
void write_provenance(const gf::CaseConfig& c, const std::string& dir, int argc_all,
                      char** argv_all, int nranks, bool restart) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  const std::string err = gf::write_resolved_case(c, dir + "/case.toml");
  if (!err.empty()) throw gf::io::IoError(err);
  std::ofstream f(dir + "/command.txt", restart ? std::ios::app : std::ios::trunc);
  f << provenance_block(c, argc_all, argv_all, nranks, restart ? "\nrestart\n" : "");
  if (!f) throw gf::io::IoError("cannot write " + dir + "/command.txt");
}

// The keys of --set arguments ("key=value"); a malformed one is left to load_case to report.
std::vector<std::string> set_keys(const std::vector<std::string>& sets) {
  std::vector<std::string> keys;
  for (const auto& s : sets) {
    const auto eq = s.find('=');
    if (eq != std::string::npos) keys.push_back(s.substr(0, eq));
  }
  return keys;
}

int run_or_check(const Args& a, int argc_all, char** argv_all, int petsc_argc, char** petsc_argv) {
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (a.list) {
    if (rank == 0) gf::print_case_help(std::cout);
    return gf::kExitOk;
  }
  const bool restart = !a.restart_dir.empty();
  const std::string dir = a.restart_dir;
  if (restart) {
    // A restart may only change what does not alter the physics, the grid or the output
    // schedule of the files it continues (setup/Restart.hpp, restart_changeable_keys).
    const auto& ok = gf::restart_changeable_keys();
    std::string refused;
    for (const auto& k : set_keys(a.sets))
      if (std::find(ok.begin(), ok.end(), k) == ok.end()) refused += (refused.empty() ? "" : ", ") + k;
    if (!refused.empty()) {
      std::string allowed;
      for (const auto& k : ok) allowed += (allowed.empty() ? "" : ", ") + k;
      throw gf::InputError("--restart " + dir + ": --set " + refused +
                           ": a restart continues the same physics on the same grid with the "
                           "same output schedule; it may only change " + allowed +
                           ". Start a new run (--out) to change anything else");
    }
    if (!std::filesystem::is_regular_file(dir + "/case.toml"))
      throw gf::InputError("--restart " + dir + ": not a granflow output folder (no " + dir +
                           "/case.toml)");
  }
  const std::string case_file = restart ? dir + "/case.toml" : a.case_file;
  const gf::CaseConfig c = gf::load_case(case_file, a.sets);
  // A resolved case.toml sets every key, so its "set but unused" warnings would be noise:
  // the original run reported the warnings of the case as written.
  if (rank == 0 && !restart)
    for (const auto& w : c.warnings) std::cerr << "granflow: warning: " << w << "\n";
  // The case's PETSc options first, then the command line's again so that they win.
  if (!c.solver.petsc_options.empty()) {
    GF_PETSC(PetscOptionsInsertString(nullptr, c.solver.petsc_options.c_str()));
    GF_PETSC(PetscOptionsInsertArgs(nullptr, petsc_argc - 1, petsc_argv + 1));
  }
  if (a.command == "check") {
    if (rank == 0) std::cout << gf::describe_case(c, size);
    return gf::kExitOk;
  }
  std::string out = restart ? dir : a.out_dir;
  if (out.empty()) out = "out/" + std::filesystem::path(a.case_file).stem().string();

  // A restart reads and checks everything before it changes a file in the folder.
  std::string ckpt_dir;
  gf::io::CheckpointHeader header;
  if (restart) {
    ckpt_dir = gf::io::find_checkpoint(PETSC_COMM_WORLD, dir);
    if (ckpt_dir.empty())
      throw gf::InputError("--restart " + dir + ": no checkpoint in this folder (" + dir +
                           "/checkpoint): the run stopped before writing one");
    header = gf::io::read_checkpoint_header(PETSC_COMM_WORLD, ckpt_dir);
    const std::string then = gf::io::read_checkpoint_file(PETSC_COMM_WORLD, ckpt_dir, "case.toml");
    const auto diffs = gf::case_differences(then, c.resolved_toml, gf::restart_changeable_keys());
    if (!diffs.empty()) {
      std::string m = "--restart " + dir + ": the case differs from the one the checkpoint (" +
                      ckpt_dir + ") was written with:";
      for (const auto& d : diffs) m += "\n  " + d;
      m += "\nA restart continues the same case; only " + std::string("time.*, output.checkpoint_*, "
           "output.progress_interval, output.volume_warn_pct and solver.petsc_options may change");
      throw gf::InputError(m);
    }
  }

  gf::Grid grid(PETSC_COMM_WORLD, c.nx, c.ny, c.domain.Lx, c.domain.Ly, c.periodic_x);
  gf::State state(grid);
  gf::initial_levelset(grid, c, state.phi);
  gf::initial_velocity(grid, c, state.vel, state.vel_old);
  const auto stepper = gf::make_stepper(grid, c);
  gf::Simulation sim(grid, state, *stepper, gf::run_from_case(c, out));
  sim.set_checkpoint_files({{"case.toml", c.resolved_toml}});
  if (restart) sim.restart(ckpt_dir, header);  // checks the grid and t_end, loads the fields

  if (rank == 0) {
    write_provenance(c, out, argc_all, argv_all, size, restart);
    const std::string err = gf::log::open(out + "/granflow.log", restart);
    if (!err.empty()) std::cerr << "granflow: warning: " << err << " (no log file)\n";
    gf::log::to_file(provenance_block(c, argc_all, argv_all, size, restart ? "restart\n" : ""));
    if (!restart)
      for (const auto& w : c.warnings) gf::log::to_file("granflow: warning: " + w);
    std::ostringstream m;
    m << "granflow: " << c.title << ": " << c.nx << " x " << c.ny << " cells on " << size
      << " rank(s), ";
    if (restart)
      m << "restarted from " << ckpt_dir << " at t = " << header.get_double("t") << " s (step "
        << header.get_int("step") << ")";
    else
      m << "from t = 0";
    m << " to t = " << c.time.t_end << " s, output in " << out;
    gf::log::message(m.str());
  }
  MPI_Barrier(PETSC_COMM_WORLD);
  const gf::RunSummary s = sim.run();
  if (rank == 0) {
    std::ostringstream m;
    m << "granflow: done, " << s.steps << " steps in " << s.wall_s << " s ("
      << (s.steps ? s.wall_s / s.steps : 0.0) << " s/step), volume change "
      << s.volume_change_pct << " %";
    gf::log::message(m.str());
  }
  return gf::kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  // Split: granflow's own arguments before "--", PETSc's after.
  int split = argc;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--") == 0) { split = i; break; }
  std::vector<char*> petsc_args{argv[0]};
  for (int i = split + 1; i < argc; ++i) petsc_args.push_back(argv[i]);
  petsc_args.push_back(nullptr);
  int petsc_argc = static_cast<int>(petsc_args.size()) - 1;
  char** petsc_argv = petsc_args.data();

  Args a;
  CLI::App app{"granflow: dense granular flows as a two-phase viscoplastic fluid (PETSc)"};
  app.require_subcommand(1);
  auto add_common = [&](CLI::App* sub) {
    sub->add_option("case", a.case_file, "case file (TOML)");
    sub->add_option("--set", a.sets, "override a case parameter: key=value (repeatable)")
        ->take_last()
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  };
  auto* run = app.add_subcommand("run", "run a case");
  add_common(run);
  run->add_option("--out", a.out_dir, "output folder (default out/<case name>)");
  run->add_option("--restart", a.restart_dir,
                  "continue the run in this output folder from its checkpoint (its case.toml; "
                  "--set may only change the end time, the time-step controls and the "
                  "checkpoint schedule)");
  auto* check = app.add_subcommand("check", "validate a case and print the grid, dt and cost");
  add_common(check);
  check->add_flag("--list", a.list, "list every case parameter with unit, default and range");
  try {
    app.parse(split, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? gf::kExitOk : gf::kExitUsage;
  }
  a.command = run->parsed() ? "run" : "check";
  if (a.command == "check" && !a.list && a.case_file.empty()) {
    std::cerr << "granflow check: a case file is required (or --list)\n";
    return gf::kExitUsage;
  }
  if (a.command == "run" && a.case_file.empty() == a.restart_dir.empty()) {
    std::cerr << "granflow run: give either a case file or --restart DIR (not both)\n";
    return gf::kExitUsage;
  }
  if (a.command == "run" && !a.restart_dir.empty() && !a.out_dir.empty()) {
    std::cerr << "granflow run: --restart continues in its own folder; --out is not allowed "
                 "with it\n";
    return gf::kExitUsage;
  }

  PetscCall(PetscInitialize(&petsc_argc, &petsc_argv, nullptr, nullptr));
  // After PetscInitialize: replaces PETSc's SIGTERM handler (an abort) by a polite stop.
  gf::signal::install_stop_handlers();
  int rc = gf::kExitOk;
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  // Messages of collective failures come from rank 0 only (every rank has the same text);
  // they also go to the log once it is open.
  auto report = [&](const std::string& m, bool all_ranks) {
    if (rank == 0) gf::log::message(m);
    else if (all_ranks) std::cerr << m << "\n";
  };
  try {
    rc = run_or_check(a, argc, argv, petsc_argc, petsc_argv);
  } catch (const gf::InputError& e) {
    report(std::string("granflow: error in the case:\n") + e.what(), false);
    rc = gf::kExitInput;
  } catch (const gf::RunError& e) {
    report(std::string("granflow: the run failed: ") + e.what(), false);
    rc = gf::kExitRunFailure;
  } catch (const gf::Interrupted& e) {
    report(std::string("granflow: ") + e.what(), false);
    rc = gf::kExitInterrupted;
  } catch (const gf::io::IoError& e) {
    report(std::string("granflow: file error: ") + e.what(), true);
    rc = gf::kExitIo;
  } catch (const std::exception& e) {
    report(std::string("granflow: error: ") + e.what(), true);
    rc = gf::kExitInternal;
  }
  gf::log::close();
  PetscFinalize();
  return rc;
}
