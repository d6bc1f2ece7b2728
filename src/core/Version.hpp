#pragma once
// The granflow version recorded in every output folder (command.txt, summary.json, checkpoints):
// the git commit of the sources the binary was built from, "-dirty" if tracked files differed
// from it, "unknown" outside a git checkout. Generated at build time by cmake/version.cmake.
namespace gf {
const char* git_version();
}  // namespace gf
