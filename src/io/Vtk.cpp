#include "io/Vtk.hpp"

#include <bit>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <set>
#include <stdexcept>

#include "core/Error.hpp"
#include "grid/Local.hpp"
#include "io/Csv.hpp"
#include "io/IoError.hpp"

namespace gf::io {

namespace {

// Values of attribute strings (field names, file names) must not break the XML.
std::string xml_escape(const std::string& s) {
  std::string out;
  for (const char c : s) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

constexpr const char* kByteOrder =
    std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";

// Components actually written: 2-vectors are padded to 3 (see the header).
int written_components(int components) { return components == 2 ? 3 : components; }

// Owned-cell count times components, the local size a field Vec must have.
PetscInt owned_values(const Grid& g, int components) {
  return g.box().xm * g.box().ym * components;
}

// Checks that `v` is a Vec with the grid layout and `bs` values per cell (local size on this
// rank); the result is agreed on by all ranks so that all throw together.
void require_layout(const Grid& g, Vec v, int bs, const std::string& what) {
  int bad = 0;
  if (!v) {
    bad = 1;
  } else {
    PetscInt n = 0;
    GF_PETSC(VecGetLocalSize(v, &n));
    bad = n != owned_values(g, bs);
  }
  int any = 0;
  MPI_Allreduce(&bad, &any, 1, MPI_INT, MPI_MAX, g.comm());
  if (any)
    throw std::invalid_argument(what + ": Vec is null or does not have the grid layout with " +
                                std::to_string(bs) + " value(s) per cell");
}

}  // namespace

void cell_velocity(const Grid& g, Vec vel, Vec uc, Vec vc, Vec speed) {
  const Box& b = g.box();
  const int ubs = vc ? 1 : 2;
  if (uc) require_layout(g, uc, ubs, "cell_velocity (uc)");
  if (vc) require_layout(g, vc, 1, "cell_velocity (vc)");
  if (speed) require_layout(g, speed, 1, "cell_velocity (speed)");
  LocalVelocity v(g, vel);
  // Owned values of a global Vec are stored i-fastest from (xs, ys), `bs` per cell.
  PetscScalar *pu = nullptr, *pv = nullptr, *ps = nullptr;
  if (uc) GF_PETSC(VecGetArray(uc, &pu));
  if (vc) GF_PETSC(VecGetArray(vc, &pv));
  if (speed) GF_PETSC(VecGetArray(speed, &ps));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) {
      const PetscInt k = (j - b.ys) * b.xm + (i - b.xs);
      double cu, cv;
      cell_centre_velocity(v, i, j, cu, cv);
      if (pu && ubs == 2) {
        pu[2 * k] = cu;
        pu[2 * k + 1] = cv;
      } else if (pu) {
        pu[k] = cu;
      }
      if (pv) pv[k] = cv;
      if (ps) ps[k] = std::sqrt(cu * cu + cv * cv);
    }
  if (speed) GF_PETSC(VecRestoreArray(speed, &ps));
  if (vc) GF_PETSC(VecRestoreArray(vc, &pv));
  if (uc) GF_PETSC(VecRestoreArray(uc, &pu));
}

VtkSeries::VtkSeries(const Grid& g, std::string dir, std::string basename)
    : g_(g), dir_(std::move(dir)), base_(std::move(basename)) {
  if (base_.empty() || base_.find('/') != std::string::npos)
    throw std::invalid_argument("VtkSeries: basename '" + base_ +
                                "' must be a non-empty file name without '/'");
  raise_on_all_ranks(g_.comm(), g_.rank() == 0 ? make_directories(dir_) : std::string());
}

VtkSeries::~VtkSeries() {
  for (auto& [n, ga] : gathers_) {
    VecDestroy(&ga.on_zero);
    VecScatterDestroy(&ga.to_zero);
    VecDestroy(&ga.natural);
    DMDestroy(&ga.dm);
  }
}

std::string VtkSeries::pvd_path() const {
  return (dir_.empty() ? "" : dir_ + "/") + base_ + ".pvd";
}

std::string VtkSeries::last_file() const {
  if (entries_.empty()) return {};
  return (dir_.empty() ? "" : dir_ + "/") + entries_.back().second;
}

VtkSeries::Gather& VtkSeries::gather_for(int components) {
  auto it = gathers_.find(components);
  if (it != gathers_.end()) return it->second;
  // Same process grid and ownership ranges as the cell DM, so that a Vec of any grid DM (or
  // any Vec with that layout) can be mapped to natural order by this DM.
  PetscInt px = 0, py = 0;
  const PetscInt *lx = nullptr, *ly = nullptr;
  GF_PETSC(DMDAGetInfo(g_.dm_cell(), nullptr, nullptr, nullptr, nullptr, &px, &py, nullptr,
                       nullptr, nullptr, nullptr, nullptr, nullptr, nullptr));
  GF_PETSC(DMDAGetOwnershipRanges(g_.dm_cell(), &lx, &ly, nullptr));
  Gather ga;
  GF_PETSC(DMDACreate2d(g_.comm(), DM_BOUNDARY_NONE, DM_BOUNDARY_NONE, DMDA_STENCIL_BOX,
                        g_.nx(), g_.ny(), px, py, components, 0, lx, ly, &ga.dm));
  GF_PETSC(DMSetUp(ga.dm));
  GF_PETSC(DMDACreateNaturalVector(ga.dm, &ga.natural));
  GF_PETSC(VecScatterCreateToZero(ga.natural, &ga.to_zero, &ga.on_zero));
  return gathers_.emplace(components, ga).first->second;
}

void VtkSeries::write(double t, const std::vector<CellField>& fields) {
  // --- 1. Check the request (identically on all ranks, so that all throw together).
  std::set<std::string> names;
  for (const CellField& f : fields) {
    if (f.name.empty() || !names.insert(f.name).second)
      throw std::invalid_argument("VtkSeries::write: field names must be non-empty and "
                                  "distinct ('" + f.name + "')");
    if (f.components < 1)
      throw std::invalid_argument("VtkSeries::write: field '" + f.name +
                                  "' has components < 1");
    require_layout(g_, f.vec, f.components, "VtkSeries::write: field '" + f.name + "'");
  }

  const Box& b = g_.box();
  const bool root = g_.rank() == 0;
  const std::uint64_t ncell = static_cast<std::uint64_t>(b.nx) * b.ny;
  char num[16];
  std::snprintf(num, sizeof num, "_%06d", next_number_);
  const std::string fname = base_ + num + ".vtr";
  const std::string path = (dir_.empty() ? "" : dir_ + "/") + fname;

  // --- 2. The XML header, with the offset of each block in the appended section. Each block
  // is a UInt64 byte count followed by the Float64 values. Coordinates come first.
  const std::string ext = "0 " + std::to_string(b.nx) + " 0 " + std::to_string(b.ny) + " 0 0";
  std::uint64_t offset = 0;
  auto block = [&offset](std::uint64_t nvalues) {
    const std::uint64_t at = offset;
    offset += sizeof(std::uint64_t) + nvalues * sizeof(double);
    return std::to_string(at);
  };
  std::string scalars, vectors;  // the default active arrays shown by ParaView
  for (const CellField& f : fields) {
    if (f.components == 1 && scalars.empty()) scalars = f.name;
    if (f.components == 2 && vectors.empty()) vectors = f.name;
  }
  std::string xml;
  xml += "<?xml version=\"1.0\"?>\n";
  xml += std::string("<VTKFile type=\"RectilinearGrid\" version=\"1.0\" byte_order=\"") +
         kByteOrder + "\" header_type=\"UInt64\">\n";
  xml += "  <RectilinearGrid WholeExtent=\"" + ext + "\">\n";
  xml += "    <FieldData>\n";
  xml += "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" "
         "format=\"ascii\">" + format_number(t) + "</DataArray>\n";
  xml += "    </FieldData>\n";
  xml += "    <Piece Extent=\"" + ext + "\">\n";
  std::string coords;
  coords += "      <Coordinates>\n";
  for (const char* axis : {"x", "y", "z"}) {
    const std::uint64_t n = axis[0] == 'x' ? b.nx + 1 : axis[0] == 'y' ? b.ny + 1 : 1;
    coords += std::string("        <DataArray type=\"Float64\" Name=\"") + axis +
              "\" NumberOfComponents=\"1\" format=\"appended\" offset=\"" + block(n) + "\"/>\n";
  }
  coords += "      </Coordinates>\n";
  xml += "      <CellData";
  if (!scalars.empty()) xml += " Scalars=\"" + xml_escape(scalars) + "\"";
  if (!vectors.empty()) xml += " Vectors=\"" + xml_escape(vectors) + "\"";
  xml += ">\n";
  for (const CellField& f : fields) {
    const int nc = written_components(f.components);
    xml += "        <DataArray type=\"Float64\" Name=\"" + xml_escape(f.name) +
           "\" NumberOfComponents=\"" + std::to_string(nc) + "\" format=\"appended\" offset=\"" +
           block(ncell * nc) + "\"/>\n";
  }
  xml += "      </CellData>\n" + coords;
  xml += "    </Piece>\n  </RectilinearGrid>\n  <AppendedData encoding=\"raw\">\n   _";

  // --- 3. Rank 0 writes the header and coordinates into a tmp file, then each field as it
  // arrives. Gathers are collective, so every rank runs through all of them even after rank
  // 0 has hit a write error; the error is reported once at the end.
  std::string err;
  std::FILE* fp = nullptr;
  const std::string tmp = path + ".tmp";
  auto put = [&](const void* data, std::size_t bytes) {
    if (err.empty() && std::fwrite(data, 1, bytes, fp) != bytes)
      err = "cannot write '" + tmp + "': " + std::strerror(errno) + " (disk full?)";
  };
  auto put_block = [&](const std::vector<double>& v) {
    const std::uint64_t bytes = v.size() * sizeof(double);
    put(&bytes, sizeof bytes);
    put(v.data(), bytes);
  };
  if (root) {
    fp = std::fopen(tmp.c_str(), "wb");
    if (!fp) err = "cannot open '" + tmp + "' for writing: " + std::strerror(errno);
    put(xml.data(), xml.size());
    // Corner coordinates; the last one is set to L exactly rather than n * (L / n).
    std::vector<double> x(b.nx + 1), y(b.ny + 1), z(1, 0.0);
    for (PetscInt i = 0; i <= b.nx; ++i) x[i] = i == b.nx ? b.Lx : b.xf(i);
    for (PetscInt j = 0; j <= b.ny; ++j) y[j] = j == b.ny ? b.Ly : b.yf(j);
    put_block(x);
    put_block(y);
    put_block(z);
  }
  std::vector<double> buf;
  for (const CellField& f : fields) {
    Gather& ga = gather_for(f.components);
    GF_PETSC(DMDAGlobalToNaturalBegin(ga.dm, f.vec, INSERT_VALUES, ga.natural));
    GF_PETSC(DMDAGlobalToNaturalEnd(ga.dm, f.vec, INSERT_VALUES, ga.natural));
    GF_PETSC(VecScatterBegin(ga.to_zero, ga.natural, ga.on_zero, INSERT_VALUES, SCATTER_FORWARD));
    GF_PETSC(VecScatterEnd(ga.to_zero, ga.natural, ga.on_zero, INSERT_VALUES, SCATTER_FORWARD));
    if (!root) continue;
    const PetscScalar* a = nullptr;
    GF_PETSC(VecGetArrayRead(ga.on_zero, &a));
    const int nc = written_components(f.components);
    buf.assign(ncell * nc, 0.0);
    for (std::uint64_t c = 0; c < ncell; ++c)
      for (int k = 0; k < f.components; ++k) buf[c * nc + k] = a[c * f.components + k];
    GF_PETSC(VecRestoreArrayRead(ga.on_zero, &a));
    put_block(buf);
  }
  if (root) {
    const std::string tail = "\n  </AppendedData>\n</VTKFile>\n";
    put(tail.data(), tail.size());
    if (fp && std::fclose(fp) != 0 && err.empty())
      err = "cannot write '" + tmp + "': " + std::strerror(errno) + " (disk full?)";
    if (err.empty() && std::rename(tmp.c_str(), path.c_str()) != 0)
      err = "cannot rename '" + tmp + "' to '" + path + "': " + std::strerror(errno);
    if (!err.empty()) std::remove(tmp.c_str());
  }

  // --- 4. The collection, rewritten whole after each snapshot so that it is valid XML at
  // any moment and ParaView can open a run that is still going (or was killed). A snapshot
  // whose .vtr failed was reported above and is not listed.
  raise_on_all_ranks(g_.comm(), err);
  entries_.emplace_back(t, fname);
  ++next_number_;
  if (root) err = write_pvd();
  raise_on_all_ranks(g_.comm(), err);
}

std::string VtkSeries::write_pvd() const {
  std::string pvd = "<?xml version=\"1.0\"?>\n";
  pvd += std::string("<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"") +
         kByteOrder + "\">\n  <Collection>\n";
  for (const auto& [te, fe] : entries_)
    pvd += "    <DataSet timestep=\"" + format_number(te) + "\" group=\"\" part=\"0\" file=\"" +
           xml_escape(fe) + "\"/>\n";
  pvd += "  </Collection>\n</VTKFile>\n";
  return write_file_atomic(pvd_path(), pvd);
}

int VtkSeries::resume(const std::vector<std::pair<double, std::string>>& entries) {
  namespace fs = std::filesystem;
  const bool root = g_.rank() == 0;
  const std::string dir = dir_.empty() ? "." : dir_;
  int missing = 0;
  entries_.clear();
  for (const auto& e : entries) {
    if (root && !fs::exists(dir + "/" + e.second)) {
      ++missing;
      continue;
    }
    entries_.push_back(e);
  }
  MPI_Bcast(&missing, 1, MPI_INT, 0, g_.comm());
  // Numbering continues after the checkpoint's last file (not after the kept count, so that
  // a missing file does not make the next one reuse a listed name).
  next_number_ = static_cast<int>(entries.size());
  std::string err;
  if (root) {
    std::error_code ec;
    const std::string prefix = base_ + "_";
    for (const auto& de : fs::directory_iterator(dir, ec)) {
      const std::string name = de.path().filename().string();
      if (name.size() != prefix.size() + 10 || name.compare(0, prefix.size(), prefix) != 0 ||
          name.compare(name.size() - 4, 4, ".vtr") != 0)
        continue;
      const std::string digits = name.substr(prefix.size(), 6);
      if (digits.find_first_not_of("0123456789") != std::string::npos) continue;
      if (std::stoi(digits) >= next_number_) fs::remove(de.path(), ec);
    }
    err = write_pvd();
  }
  raise_on_all_ranks(g_.comm(), err);
  // Only rank 0 looked at the files, and only rank 0 writes the .pvd: the other ranks keep
  // the list as given.
  if (!root) entries_ = entries;
  return missing;
}

}  // namespace gf::io
