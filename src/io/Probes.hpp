#pragma once
// Line probes: fields sampled at evenly spaced points of a segment, one CSV per probe.
//
// A probe NAME with fields f1..fk writes dir/probes/NAME.csv with the header t,x,y,f1,...,fk
// and, per write(), one row per point (a block of `points` rows with the same t). Point k of
// n is (x0, y0) + k/(n-1) (x1 - x0, y1 - y0), the last one exactly (x1, y1); a probe with one
// point samples (x0, y0). Points must lie in the closed domain [0, Lx] x [0, Ly].
//
// Interpolation: bilinear between the four nearest sample positions of each field's own
// staggering, so a linear field is reproduced exactly:
//   phi, rho, p, eta and the extra cell fields: cell centres ((i+1/2) hx, (j+1/2) hy);
//   u: left faces (i hx, (j+1/2) hy), including the wall faces i = 0 and i = nx (u = 0 there);
//   v: bottom faces ((i+1/2) hx, j hy), including j = 0 and j = ny (v = 0 there);
//   speed = sqrt(u^2 + v^2) of the interpolated u and v at the point.
// Between the wall and the first row of sample positions (half a cell) the sample index is
// clamped, i.e. the value is held constant in that direction: no extrapolation.
//
// Parallel: each point belongs to the rank owning the cell that contains it (cell index
// floor(x / hx) clamped to [0, nx-1], same in y), which evaluates it on ghosted local
// arrays; the values are then reduced to rank 0, which writes. Non-owners contribute -0.0,
// the exact identity of IEEE addition (x + -0.0 == x for every x, including -0.0 and NaN),
// so the reduced value is bit-identical to the owner's and the files do not depend on the
// number of ranks.
//
// Extra cell fields: besides the built-in fields, a writer knows a list of extra cell-centred
// fields by name (by default D_norm, S_norm and kappa, the plastic fields of the VTK output);
// their Vecs are passed to write() by name, so a new cell field needs no new parameter.
#include <petscvec.h>

#include <string>
#include <utility>
#include <vector>

#include "grid/Grid.hpp"
#include "io/Csv.hpp"

namespace gf::io {

struct ProbeSpec {
  std::string name;          // file name stem: non-empty, letters, digits, '_', '-', '.'
  double x0, y0, x1, y1;     // m
  int points;                // >= 1
  std::vector<std::string> fields;  // built-in {phi, rho, u, v, speed, p, eta} or an extra
                                    // cell field of the writer; distinct
};

// Named cell-centred Vecs (dm_cell) for ProbeWriter::write.
using NamedCellFields = std::vector<std::pair<std::string, Vec>>;

// The extra cell fields a ProbeWriter knows by default: |D(u)| (1/s), |S| and the yield
// stress kappa (Pa), as in the VTK output and the case schema's probe fields.
std::vector<std::string> default_extra_cell_fields();

class ProbeWriter {
 public:
  // Collective. Checks the specs (gf::InputError: they come from the case file), creates
  // dir/probes and one CSV per probe with its header. `extra_cell_fields`: the names of the
  // extra cell fields the specs may ask for (distinct, none a built-in name; a bad list is a
  // programming error: std::invalid_argument).
  // `resume_bytes`: empty for a new run; on a restart, the size of each probe's file at the
  // checkpoint (same order as `specs`): the files are continued from there (CsvWriter).
  ProbeWriter(const Grid& g, std::string dir, std::vector<ProbeSpec> specs,
              std::vector<std::string> extra_cell_fields = default_extra_cell_fields(),
              const std::vector<long long>& resume_bytes = {});

  // Collective. Appends one block per probe at time t. A Vec may be nullptr only if no probe
  // asks for it (std::invalid_argument otherwise): phi, rho, p, eta on dm_cell, vel on dm_vel.
  // `extra`: the extra cell fields by name (dm_cell); each one a probe samples must be there,
  // non-null; the others may be left out; a name the writer does not know, or given twice, is
  // refused (std::invalid_argument). Same names on every rank.
  void write(double t, Vec phi, Vec rho, Vec vel, Vec p, Vec eta,
             const NamedCellFields& extra = {});

  // Whether some probe samples `field` (built-in or extra): lets the caller skip computing a
  // field no probe needs (the answer is the same on every rank).
  bool samples(const std::string& field) const;

  // Per probe (in the order of the specs): its name and the bytes in its file so far (rank 0;
  // 0 elsewhere), for a checkpoint.
  std::vector<std::pair<std::string, long long>> file_bytes() const;

 private:
  // Built-in quantities; extra cell field e is quantity kCount + e.
  enum Quantity { kPhi, kRho, kU, kV, kSpeed, kP, kEta, kCount };
  struct Probe {
    ProbeSpec spec;
    std::vector<int> q;                  // spec.fields, parsed (Quantity or kCount + e)
    std::vector<double> x, y;            // point coordinates, m
    std::vector<char> mine;              // owned by this rank
  };
  const Grid& g_;
  std::vector<Probe> probes_;
  std::vector<CsvWriter> csv_;
  std::vector<std::string> extra_;  // names of the extra cell fields
  std::vector<char> needs_;         // per quantity (kCount + extra_.size())
};

}  // namespace gf::io
