#include "io/Csv.hpp"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "io/IoError.hpp"

namespace gf::io {

std::string format_number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", x);
  return buf;
}

CsvWriter::CsvWriter(std::string path, std::vector<std::string> columns, MPI_Comm comm)
    : CsvWriter(std::move(path), std::move(columns), -1, comm) {}

CsvWriter::CsvWriter(std::string path, std::vector<std::string> columns, long long resume_bytes,
                     MPI_Comm comm)
    : path_(std::move(path)), ncol_(columns.size()) {
  // Argument checks come first and are identical on all ranks, so all ranks throw together.
  if (columns.empty()) throw std::invalid_argument("CsvWriter '" + path_ + "': no columns");
  for (const auto& c : columns)
    if (c.empty() || c.find_first_of(",\"\r\n") != std::string::npos)
      throw std::invalid_argument("CsvWriter '" + path_ + "': bad column name '" + c +
                                  "' (must be non-empty, without commas, quotes, newlines)");
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string err;
  std::string header;
  for (std::size_t k = 0; k < columns.size(); ++k) header += (k ? "," : "") + columns[k];
  header += '\n';
  if (rank == 0 && resume_bytes >= 0) {
    namespace fs = std::filesystem;
    std::error_code ec;
    const auto size = fs::file_size(path_, ec);
    std::string first;
    if (!ec) {
      std::FILE* f = std::fopen(path_.c_str(), "rb");
      if (f) {
        char buf[4096];
        if (std::fgets(buf, sizeof buf, f)) first = buf;
        std::fclose(f);
      }
    }
    if (ec)
      err = "cannot continue '" + path_ + "': " + ec.message();
    else if (first != header)
      err = "cannot continue '" + path_ + "': its header is not the one this run writes "
            "(edited, or written by another granflow version)";
    else if (static_cast<long long>(size) < resume_bytes)
      err = "cannot continue '" + path_ + "': it has " + std::to_string(size) +
            " bytes, fewer than the " + std::to_string(resume_bytes) +
            " it had at the checkpoint (truncated or edited)";
    if (err.empty()) {
      // Rows written after the checkpoint (an interrupted or failed run's last rows) go: the
      // continued run writes them again.
      fs::resize_file(path_, static_cast<std::uintmax_t>(resume_bytes), ec);
      if (ec) err = "cannot cut '" + path_ + "' back to the checkpoint: " + ec.message();
    }
    if (err.empty()) {
      file_.reset(std::fopen(path_.c_str(), "a"));
      if (!file_) err = "cannot open '" + path_ + "' for appending: " + std::strerror(errno);
    }
    bytes_ = resume_bytes;
  } else if (rank == 0) {
    err = make_directories(std::filesystem::path(path_).parent_path().string());
    if (err.empty()) {
      file_.reset(std::fopen(path_.c_str(), "w"));
      if (!file_) err = "cannot open '" + path_ + "' for writing: " + std::strerror(errno);
    }
    if (err.empty()) {
      bytes_ = static_cast<long long>(header.size());
      if (std::fputs(header.c_str(), file_.get()) < 0 || std::fflush(file_.get()) != 0)
        err = "cannot write '" + path_ + "': " + std::strerror(errno);
    }
  }
  raise_on_all_ranks(comm, err);
}

void CsvWriter::row(const std::vector<double>& values) {
  if (values.size() != ncol_)
    throw std::invalid_argument("CsvWriter '" + path_ + "': row has " +
                                std::to_string(values.size()) + " values, header has " +
                                std::to_string(ncol_) + " columns");
  if (!file_) return;
  std::string line;
  line.reserve(ncol_ * 24);
  for (std::size_t k = 0; k < values.size(); ++k) {
    if (k) line += ',';
    line += format_number(values[k]);
  }
  line += '\n';
  bytes_ += static_cast<long long>(line.size());
  if (std::fputs(line.c_str(), file_.get()) < 0 || std::fflush(file_.get()) != 0)
    throw IoError("cannot write '" + path_ + "': " + std::strerror(errno) + " (disk full?)");
  // A file deleted while open (its folder removed during the run) still takes writes, into
  // an inode nobody can reach: the rows are lost, which must not pass as success.
  struct stat st {};
  if (fstat(fileno(file_.get()), &st) == 0 && st.st_nlink == 0)
    throw IoError("'" + path_ + "' was deleted while the run was writing it (its folder "
                  "removed?): its rows are lost");
}

}  // namespace gf::io
