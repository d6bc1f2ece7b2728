#pragma once
// Field snapshots for ParaView/VisIt: one VTK XML RectilinearGrid file (.vtr) per output time
// and a ParaView collection (.pvd) listing them with their times.
//
// File layout (VTK XML format, version 1.0): the grid points are the cell corners
// x_i = i hx (i = 0..nx), y_j = j hy (j = 0..ny), z = 0, and every field is CellData, so a
// cell value sits at its cell centre exactly as in the solver. Data are Float64 in the
// "appended raw" encoding with UInt64 block headers (compact, exact, read by ParaView >= 5
// and by VTK's vtkXMLRectilinearGridReader). The time is also stored in each file as the
// FieldData array "TimeValue". 2-component fields are written as 3-component vectors with a
// zero z component, because ParaView treats only 3-component arrays as vectors (glyphs,
// stream tracers).
//
// Parallel: fields are gathered to rank 0 in the natural (global i-fastest) ordering, which
// is also the VTK cell ordering, so the bytes written do not depend on the number of ranks.
// The scatters are built once per component count and reused. File work is done by rank 0;
// a failure there throws io::IoError on every rank.
#include <petscdmda.h>

#include <map>
#include <string>
#include <vector>

#include "grid/Grid.hpp"

namespace gf::io {

// One array of a snapshot: a global Vec with the grid's parallel layout and `components`
// interleaved values per cell, e.g. a Vec of dm_cell (1), of dm_ten (3: Sxx, Sxy, Syy) or a
// dof-2 cell-centred vector filled by cell_velocity (2, written as a 3-vector).
struct CellField {
  std::string name;
  Vec vec = nullptr;
  int components = 1;
};

// Cell-centred velocity from the MAC face velocity `vel` (dm_vel):
//   uc = (u_{i,j} + u_{i+1,j}) / 2,  vc = (v_{i,j} + v_{i,j+1}) / 2,  speed = sqrt(uc^2 + vc^2),
// with the wall faces i = nx / j = ny (not stored) taken as zero, the same definition as
// diag::max_speed. Output forms:
//   * vc != nullptr: uc and vc are dof-1 Vecs with the cell layout (e.g. on dm_cell);
//   * vc == nullptr: uc has 2 interleaved values per cell (e.g. a Vec on dm_vel, reused as a
//     cell-centred vector), ready to write as CellField{"u", uc, 2}.
// `speed` (dof 1) may be nullptr; uc may be nullptr if only the speed is wanted. Collective.
void cell_velocity(const Grid& g, Vec vel, Vec uc, Vec vc, Vec speed);

class VtkSeries {
 public:
  // Collective. Rank 0 creates `dir` if missing. Files are `dir/basename_NNNNNN.vtr` (N
  // counting writes from 0) and `dir/basename.pvd`; an existing series of that name is
  // overwritten, not extended.
  VtkSeries(const Grid& g, std::string dir, std::string basename);
  ~VtkSeries();
  VtkSeries(const VtkSeries&) = delete;
  VtkSeries& operator=(const VtkSeries&) = delete;

  // Collective. Writes one .vtr with `fields` as CellData (in the given order), then rewrites
  // the .pvd atomically to list every file written so far. Field names must be non-empty
  // and distinct, and each Vec must have the grid layout with `components` values per cell
  // (std::invalid_argument on every rank otherwise).
  void write(double t, const std::vector<CellField>& fields);

  // Collective. Continues a series after a restart: `entries` are the (t, file name) pairs
  // listed at the checkpoint. Rank 0 deletes the snapshots of this series written after the
  // checkpoint (numbers >= entries.size(): they would be listed twice or out of order) and
  // rewrites the .pvd; the next write() gets number entries.size(). A listed file that is
  // missing is dropped from the list; returns how many were (same on every rank).
  int resume(const std::vector<std::pair<double, std::string>>& entries);
  const std::vector<std::pair<double, std::string>>& entries() const { return entries_; }

  std::string pvd_path() const;
  int files_written() const { return static_cast<int>(entries_.size()); }
  // Path of the .vtr file written by the last write() ("" before the first).
  std::string last_file() const;

 private:
  // Natural-ordering gather for one component count: a DMDA with the grid's layout (stencil
  // width 0; only its global-to-natural map is used), its natural Vec and a scatter of that
  // to a sequential Vec on rank 0.
  struct Gather {
    DM dm = nullptr;
    Vec natural = nullptr;
    VecScatter to_zero = nullptr;
    Vec on_zero = nullptr;
  };
  Gather& gather_for(int components);
  // Rank 0: rewrites the .pvd from entries_ atomically; returns an error message.
  std::string write_pvd() const;

  const Grid& g_;
  std::string dir_, base_;
  std::map<int, Gather> gathers_;
  std::vector<std::pair<double, std::string>> entries_;  // (t, file name relative to dir_)
  int next_number_ = 0;                                  // of the next file written
};

}  // namespace gf::io
