#pragma once
// File-system failures of the output writers, and how a collective writer reports them.
//
// Writers do their file work on rank 0 only, but a failure there (directory not writable,
// disk full) must stop every rank together: a rank-0-only throw would leave the others
// waiting in the next collective call. So a collective writer records rank 0's error text
// and calls raise_on_all_ranks(), which broadcasts it and throws IoError everywhere.
// apps/ maps IoError to exit code kExitIo.
#include <mpi.h>

#include <stdexcept>
#include <string>

namespace gf::io {

class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Collective. `error_on_root` is rank 0's error message (empty: success; ignored on other
// ranks). Throws IoError with that message on every rank when it is not empty.
void raise_on_all_ranks(MPI_Comm comm, const std::string& error_on_root);

// Writes `text` to `path` atomically: to `path.tmp` first, then rename(), so a reader (or a
// run killed mid-write) never sees a half-written file. Not collective. Returns an error
// message, empty on success.
std::string write_file_atomic(const std::string& path, const std::string& text);

// Creates `dir` and its parents if missing. Not collective. Returns an error message, empty
// on success.
std::string make_directories(const std::string& dir);

}  // namespace gf::io
