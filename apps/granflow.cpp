// granflow: the command line.
//   granflow run CASE.toml [--set key=value ...] [--out DIR [--overwrite]] [-- PETSc options]
//   granflow run --restart DIR [--set key=value ...] [-- PETSc options]
//   granflow check CASE.toml [--set key=value ...] [--list]
//   granflow --version
// Options after "--" go to PETSc's options database (e.g. -pres_ksp_monitor, -visc_pc_type).
// This file only parses the command line; the commands are in setup/Run.hpp. It is built as
// granflow-core, which users start through the launcher granflow (apps/launcher.c).
#include <petscsys.h>

#include <CLI/CLI.hpp>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "core/Error.hpp"
#include "core/Log.hpp"
#include "core/Signal.hpp"
#include "core/Version.hpp"
#include "setup/Run.hpp"

namespace {

// `granflow --version`: the sources' git commit and the PETSc it was built with.
std::string version_text() {
  return std::string("granflow ") + gf::git_version() + "\nPETSc " +
         std::to_string(PETSC_VERSION_MAJOR) + "." + std::to_string(PETSC_VERSION_MINOR) + "." +
         std::to_string(PETSC_VERSION_SUBMINOR) + " (" + std::to_string(8 * sizeof(PetscInt)) +
         "-bit indices, " + std::to_string(8 * sizeof(PetscScalar)) + "-bit scalars)";
}

}  // namespace

int main(int argc, char** argv) {
  // First of all: a SIGTERM from here on is recorded, not the default kill (exit 143 with
  // nothing said); the run's start-up polls it between its stages (core/Signal.hpp). The
  // launcher (apps/launcher.c) held the signals blocked until now: one that came meanwhile is
  // delivered here, to the handler.
  gf::signal::install_stop_handlers();
  gf::signal::unblock();
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
  app.set_version_flag("--version", version_text(), "print the git commit and PETSc version");
  auto add_common = [&](CLI::App* sub) {
    sub->add_option("case", a.case_file, "case file (TOML)");
    // CLI11 takes the first word after --set whatever it is: "--set --out DIR" would make
    // "--out" a value. Such values are refused after parsing (below).
    sub->add_option("--set", a.sets, "override a case parameter: key=value (repeatable)")
        ->take_last()
        ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  };
  auto* run = app.add_subcommand("run", "run a case");
  add_common(run);
  run->add_option("--out", a.out_dir,
                  "output folder (default out/<case name>); it must not exist, be empty, or be "
                  "a granflow run folder with --overwrite");
  run->add_flag("--overwrite", a.overwrite,
                "with --out: remove the granflow run already in that folder first (its log, "
                "results and checkpoints)");
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
  // A --set value that is an option ("--set --out DIR") is a --set without its value.
  for (const auto& s : a.sets)
    if (s.rfind("-", 0) == 0) {
      std::cerr << "granflow " << a.command << ": --set needs key=value right after it, got '"
                << gf::log::printable(s) << "' (an option)\n";
      return gf::kExitUsage;
    }
  if (a.command == "check" && !a.list && a.case_file.empty()) {
    std::cerr << "granflow check: a case file is required (or --list)\n";
    return gf::kExitUsage;
  }
  if (a.command == "run" && a.case_file.empty() == a.restart_dir.empty()) {
    std::cerr << "granflow run: give either a case file or --restart DIR (not both)\n";
    return gf::kExitUsage;
  }
  if (a.command == "run" && !a.restart_dir.empty() && (!a.out_dir.empty() || a.overwrite)) {
    std::cerr << "granflow run: --restart continues in its own folder; --out and --overwrite "
                 "are not allowed with it\n";
    return gf::kExitUsage;
  }

  {
    // PetscInitialize installs PETSc's SIGTERM handler (an abort with a stack trace): the stop
    // signals wait, blocked, until this process's handlers are back.
    gf::signal::Blocked blocked;
    PetscCall(PetscInitialize(&petsc_argc, &petsc_argv, nullptr, nullptr));
    gf::signal::install_stop_handlers();
  }
  gf::install_petsc_error_capture();
  a.argc_all = argc;
  a.argv_all = argv;
  a.petsc_argc = petsc_argc;
  a.petsc_argv = petsc_argv;
  const int rc = gf::execute(a);
  gf::log::close();
  PetscFinalize();
  return rc;
}
