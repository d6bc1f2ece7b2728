#pragma once
// Checkpoints: everything a run needs to continue exactly where it stopped.
//
// Layout of OUT/checkpoint/ (one checkpoint, the latest):
//   state.bin   the fields, PETSc binary format, one VecView after another. A DMDA global Vec
//               is written in the natural (global i-fastest) ordering and VecLoad maps it
//               back to any decomposition, so a checkpoint written on N ranks loads on M.
//   header.txt  "granflow-checkpoint 2", then one "key value" line per entry: the field
//               names and global sizes, the size and FNV-1a 64 checksum of state.bin and of
//               each of the caller's files, and whatever the caller stores (time, step, loop
//               counters, grid; sim/ decides). Doubles are written in C99 hex-float notation
//               ("%a", an exact round trip on any platform) followed by "# decimal" for
//               humans. Last, "header.fnv1a64" with the checksum of every line above it (an
//               edited step, t or dt is caught), then "end". Headers of version 1 (older
//               granflow, without the header checksum) are still read.
//   other files the caller's (e.g. the resolved case the checkpoint was written with).
//
// Atomicity: a checkpoint is written into OUT/checkpoint.tmp/, each file fsync'ed, then rank
// 0 renames the old OUT/checkpoint to OUT/checkpoint.prev (replacing the one before) and
// OUT/checkpoint.tmp to OUT/checkpoint, and fsyncs OUT. A crash at any moment leaves either a
// complete checkpoint or a complete checkpoint.prev; checkpoint.tmp is never read. The
// checksums catch a file damaged later (a truncated copy, a full disk during a copy, an
// edit); checkpoint.prev, the checkpoint before the latest, is kept for that case (a restart
// falls back to it, setup/Run.cpp): the checkpoints take twice the space of one.
#include <petscvec.h>

#include <string>
#include <utility>
#include <vector>

namespace gf::io {

class CheckpointHeader {
 public:
  // Keys: non-empty, no whitespace. Setting a key twice replaces its value.
  void set(const std::string& key, double v);
  void set(const std::string& key, long long v);
  void set(const std::string& key, int v) { set(key, static_cast<long long>(v)); }
  // A single-line text (a newline is an error: std::invalid_argument).
  void set_text(const std::string& key, const std::string& v);

  bool has(const std::string& key) const;
  // The caller's files whose checksum the header records ("file.<name>.fnv1a64").
  std::vector<std::string> file_names() const;
  // Throw IoError naming `source` and the key when it is missing or malformed.
  double get_double(const std::string& key) const;
  long long get_int(const std::string& key) const;
  std::string get_text(const std::string& key) const;

  std::string str() const;
  // Parses str()'s format; throws IoError naming `source` on a malformed text.
  static CheckpointHeader parse(const std::string& text, const std::string& source);
  const std::string& source() const { return source_; }

 private:
  const std::string* find(const std::string& key) const;
  std::vector<std::pair<std::string, std::string>> entries_;
  std::string source_;
};

struct CheckpointField {
  std::string name;
  Vec vec = nullptr;  // a DMDA global Vec
};

// Collective on `comm`. Writes `fields`, `header` (plus the field list and checksum) and the
// `files` (name, text; written by rank 0) as OUT_DIR/checkpoint, atomically (see above).
// Throws IoError on every rank on failure; the previous checkpoint is then left in place.
void write_checkpoint(MPI_Comm comm, const std::string& out_dir, CheckpointHeader header,
                      const std::vector<CheckpointField>& fields,
                      const std::vector<std::pair<std::string, std::string>>& files);

// Collective. The folder of the latest complete checkpoint of OUT_DIR (checkpoint, or
// checkpoint.prev after a crash between the two renames), "" if there is none. The caller
// falls back to OUT_DIR/checkpoint.prev when the latest one fails read_checkpoint_header.
std::string find_checkpoint(MPI_Comm comm, const std::string& out_dir);

// Collective. Reads CKPT_DIR/header.txt (checked against its own checksum) and checks
// state.bin and the caller's files against their recorded sizes and checksums (a truncated,
// corrupt or edited checkpoint is an IoError saying which file and how).
CheckpointHeader read_checkpoint_header(MPI_Comm comm, const std::string& ckpt_dir);

// Collective. A text file of the checkpoint folder (read on rank 0, broadcast). IoError if
// it cannot be read.
std::string read_checkpoint_file(MPI_Comm comm, const std::string& ckpt_dir,
                                 const std::string& name);

// Collective. Loads `fields` (same names, same order and global sizes as written: otherwise
// an IoError naming the first difference) from CKPT_DIR/state.bin into the given Vecs, which
// may have any parallel layout of the same DMDA grid.
void read_checkpoint_fields(MPI_Comm comm, const std::string& ckpt_dir,
                            const CheckpointHeader& header,
                            const std::vector<CheckpointField>& fields);

}  // namespace gf::io
