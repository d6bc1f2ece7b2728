// granflow: the command line.
//   granflow run CASE.toml [--set key=value ...] [--out DIR] [-- PETSc options]
//   granflow check CASE.toml [--set key=value ...] [--list]
// Options after "--" go to PETSc's options database (e.g. -pres_ksp_monitor, -visc_pc_type).
#include <petscsys.h>

#include <CLI/CLI.hpp>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "core/Case.hpp"
#include "core/Error.hpp"
#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "io/IoError.hpp"
#include "sim/Setup.hpp"
#include "sim/Simulation.hpp"
#include "stepper/Stepper.hpp"

namespace {

struct Args {
  std::string command, case_file, out_dir;
  std::vector<std::string> sets;
  bool list = false;
};

// Everything the output folder needs to reproduce the run.
void write_provenance(const gf::CaseConfig& c, const std::string& dir, int argc_all,
                      char** argv_all, int nranks) {
  namespace fs = std::filesystem;
  fs::create_directories(dir);
  const std::string err = gf::write_resolved_case(c, dir + "/case.toml");
  if (!err.empty()) throw std::runtime_error(err);
  std::ofstream f(dir + "/command.txt");
  f << "command:";
  for (int i = 0; i < argc_all; ++i) f << ' ' << argv_all[i];
  f << "\ngranflow version: " << GRANFLOW_GIT_HASH << "\nMPI ranks: " << nranks
    << "\ncase file: " << c.source << "\n";
  char* opts = nullptr;
  PetscOptionsGetAll(nullptr, &opts);
  f << "PETSc options: " << (opts ? opts : "") << "\n";
  PetscFree(opts);
}

int run_or_check(const Args& a, int argc_all, char** argv_all, int petsc_argc, char** petsc_argv) {
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  if (a.list) {
    if (rank == 0) gf::print_case_help(std::cout);
    return gf::kExitOk;
  }
  const gf::CaseConfig c = gf::load_case(a.case_file, a.sets);
  if (rank == 0)
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
  std::string out = a.out_dir;
  if (out.empty()) out = "out/" + std::filesystem::path(a.case_file).stem().string();
  gf::Grid grid(PETSC_COMM_WORLD, c.nx, c.ny, c.domain.Lx, c.domain.Ly, c.periodic_x);
  if (rank == 0) write_provenance(c, out, argc_all, argv_all, size);
  gf::State state(grid);
  gf::initial_levelset(grid, c, state.phi);
  gf::initial_velocity(grid, c, state.vel, state.vel_old);
  gf::Stepper stepper(grid, gf::physics_from_case(c));
  gf::Simulation sim(grid, state, stepper, gf::run_from_case(c, out));
  if (rank == 0)
    std::cerr << "granflow: " << c.title << ": " << c.nx << " x " << c.ny << " cells on " << size
              << " rank(s), to t = " << c.time.t_end << " s, output in " << out << "\n";
  const gf::RunSummary s = sim.run();
  if (rank == 0)
    std::cerr << "granflow: done, " << s.steps << " steps in " << s.wall_s << " s ("
              << (s.steps ? s.wall_s / s.steps : 0.0) << " s/step), volume change "
              << s.volume_change_pct << " %\n";
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
  auto add_common = [&](CLI::App* sub, bool need_case) {
    auto* o = sub->add_option("case", a.case_file, "case file (TOML)");
    if (need_case) o->required();
    sub->add_option("--set", a.sets, "override a case parameter: key=value (repeatable)")
        ->take_last()
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  };
  auto* run = app.add_subcommand("run", "run a case");
  add_common(run, true);
  run->add_option("--out", a.out_dir, "output folder (default out/<case name>)");
  auto* check = app.add_subcommand("check", "validate a case and print the grid, dt and cost");
  add_common(check, false);
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

  PetscCall(PetscInitialize(&petsc_argc, &petsc_argv, nullptr, nullptr));
  int rc = gf::kExitOk;
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  try {
    rc = run_or_check(a, argc, argv, petsc_argc, petsc_argv);
  } catch (const gf::InputError& e) {
    if (rank == 0) std::cerr << "granflow: error in the case:\n" << e.what() << "\n";
    rc = gf::kExitInput;
  } catch (const gf::RunError& e) {
    std::cerr << "granflow: the run failed: " << e.what() << "\n";
    rc = gf::kExitRunFailure;
  } catch (const gf::io::IoError& e) {
    std::cerr << "granflow: cannot write output: " << e.what() << "\n";
    rc = gf::kExitIo;
  } catch (const std::exception& e) {
    std::cerr << "granflow: error: " << e.what() << "\n";
    rc = gf::kExitInternal;
  }
  PetscFinalize();
  return rc;
}
