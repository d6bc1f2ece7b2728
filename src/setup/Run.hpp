#pragma once
// The commands of the granflow program (`run`, `check`), as parsed by apps/granflow.cpp.
#include <string>
#include <vector>

namespace gf {

struct CommandLine {
  std::string command;  // "run" or "check"
  std::string case_file, out_dir, restart_dir;
  std::vector<std::string> sets;  // --set key=value
  bool list = false;              // check --list
  bool overwrite = false;         // run --overwrite: replace the run folder at --out
  int argc_all = 0;               // the whole command line, for the provenance
  char** argv_all = nullptr;
  int petsc_argc = 0;  // the options after "--" (argv[0] first), for PETSc
  char** petsc_argv = nullptr;
};

// Runs the command (collective; after PetscInitialize and the stop handlers). Returns the exit
// code: kExitOk, or the code of the failure, whose message it has printed (and logged).
int execute(const CommandLine& cl);

}  // namespace gf
