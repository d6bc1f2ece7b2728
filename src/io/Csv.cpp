#include "io/Csv.hpp"

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
  if (rank == 0) {
    err = make_directories(std::filesystem::path(path_).parent_path().string());
    if (err.empty()) {
      file_.reset(std::fopen(path_.c_str(), "w"));
      if (!file_) err = "cannot open '" + path_ + "' for writing: " + std::strerror(errno);
    }
    if (err.empty()) {
      std::string header;
      for (std::size_t k = 0; k < columns.size(); ++k) header += (k ? "," : "") + columns[k];
      header += '\n';
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
  if (std::fputs(line.c_str(), file_.get()) < 0 || std::fflush(file_.get()) != 0)
    throw IoError("cannot write '" + path_ + "': " + std::strerror(errno) + " (disk full?)");
}

}  // namespace gf::io
