// granflow: the command line.
//   granflow run CASE.toml [--set key=value ...] [--out DIR] [-- PETSc options]
//   granflow run --restart DIR [--set key=value ...] [-- PETSc options]
//   granflow check CASE.toml [--set key=value ...] [--list]
// Options after "--" go to PETSc's options database (e.g. -pres_ksp_monitor, -visc_pc_type).
// This file only parses the command line; the commands are in setup/Run.hpp.
#include <petscsys.h>

#include <CLI/CLI.hpp>
#include <cstring>
#include <iostream>
#include <vector>

#include "core/Error.hpp"
#include "core/Log.hpp"
#include "core/Signal.hpp"
#include "setup/Run.hpp"

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

  gf::CommandLine a;
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
  a.argc_all = argc;
  a.argv_all = argv;
  a.petsc_argc = petsc_argc;
  a.petsc_argv = petsc_argv;
  const int rc = gf::execute(a);
  gf::log::close();
  PetscFinalize();
  return rc;
}
