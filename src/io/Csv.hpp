#pragma once
// Time series as CSV: one header line of column names, then one line per row() call.
// Numbers are written with 17 significant digits ("%.17g"), enough to read back the exact
// double, so a CSV written by a run can be compared bit for bit with another run's. Each row
// is flushed at once: a crashed or killed run keeps everything logged up to the crash.
//
// Only rank 0 of `comm` opens and writes the file; the other ranks hold an inert writer, so
// row() may be called on every rank (their values are ignored) or on rank 0 only.
#include <petscsys.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace gf::io {

// The number format of every writer in io/: 17 significant digits, shortest C form
// ("0.10000000000000001", "1e-05", "nan", "inf").
std::string format_number(double x);

class CsvWriter {
 public:
  // Collective on `comm`: rank 0 creates the parent folder, truncates `path` and writes the
  // header; an IoError is thrown on every rank if that fails. Column names must be non-empty
  // and free of commas, quotes and line breaks (they are written unquoted).
  CsvWriter(std::string path, std::vector<std::string> columns,
            MPI_Comm comm = PETSC_COMM_WORLD);
  // Collective. Continues an existing file (a restart): rank 0 checks that its header line is
  // `columns`, cuts it back to `resume_bytes` (its size at the checkpoint, so rows written
  // after the checkpoint are not duplicated) and appends from there. IoError on every rank if
  // the file is missing, has another header or is shorter than `resume_bytes`.
  CsvWriter(std::string path, std::vector<std::string> columns, long long resume_bytes,
            MPI_Comm comm = PETSC_COMM_WORLD);
  CsvWriter(CsvWriter&&) noexcept = default;
  CsvWriter& operator=(CsvWriter&&) noexcept = default;

  // Not collective. `values.size()` must equal the number of columns (checked on every rank:
  // std::invalid_argument). On rank 0 a failed write throws IoError on rank 0 only; so does a
  // file deleted since it was opened (its rows would go nowhere).
  void row(const std::vector<double>& values);

  const std::string& path() const { return path_; }
  std::size_t columns() const { return ncol_; }
  // Bytes in the file so far (header included), on rank 0; 0 on the other ranks.
  long long bytes() const { return bytes_; }

 private:
  struct Closer {
    void operator()(std::FILE* f) const { std::fclose(f); }
  };
  std::string path_;
  std::size_t ncol_ = 0;
  long long bytes_ = 0;
  std::unique_ptr<std::FILE, Closer> file_;  // null on ranks other than 0
};

}  // namespace gf::io
