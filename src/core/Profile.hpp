#pragma once
// Where the time of a run goes, by phase of the time step. Each phase is a PETSc log event (so
// `-log_view` shows it with flops and messages) and a wall-clock accumulator (so summary.json
// reports it without -log_view; the benchmark in bench/ reads it from there). Phases nest: the
// fixed point contains the viscous solves, the plastic updates and the Anderson mixing.
#include <petscsys.h>

#include <array>
#include <chrono>

namespace gf::prof {

enum Phase : int {
  Advect,        // level-set transport, eq. 26 (WENO5 + RK3)
  Redistance,    // Min (2010) redistancing
  Properties,    // rho, eta (and the mu(I) viscosity) from phi
  Assemble,      // viscous and pressure matrices
  FixedPoint,    // the whole prediction step of eq. 31 (contains the three below)
  ViscousSolve,  // KSP solves of the viscous operator
  Plastic,       // div(kappa S), D(u~), the projections P and P_b, the wall load
  Anderson,      // Anderson mixing of the fixed-point iterates
  Pressure,      // projection, eq. 32
  Output,        // diagnostics, probes, VTK
  Checkpoint,    // checkpoint files
  kCount
};

const char* name(Phase p);
// Registers the PETSc events on first use (after PetscInitialize).
PetscLogEvent event(Phase p);
// Wall-clock seconds spent in each phase on this rank since the start of the process.
std::array<double, kCount>& seconds();

class Scope {
 public:
  explicit Scope(Phase p) : p_(p), t0_(std::chrono::steady_clock::now()) {
    PetscLogEventBegin(event(p), 0, 0, 0, 0);
  }
  ~Scope() {
    PetscLogEventEnd(event(p_), 0, 0, 0, 0);
    seconds()[p_] += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0_).count();
  }
  Scope(const Scope&) = delete;
  Scope& operator=(const Scope&) = delete;

 private:
  Phase p_;
  std::chrono::steady_clock::time_point t0_;
};

// Peak resident set size of this process, MiB (getrusage).
double peak_rss_mib();
// Memory this machine can still give, bytes: MemAvailable of /proc/meminfo, less if a cgroup
// (a batch job's, a container's) limits this process to less. 0 if unknown.
double available_memory_bytes();

}  // namespace gf::prof
