#include "io/Probes.hpp"

#include <mpi.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <set>
#include <stdexcept>

#include "core/Error.hpp"
#include "grid/Local.hpp"
#include "io/IoError.hpp"

namespace gf::io {

namespace {

constexpr const char* kNames[] = {"phi", "rho", "u", "v", "speed", "p", "eta"};

// Position along one axis of a field sampled at (k + off) h, k = 0..n-1: the lower sample
// index k0 and the weight w of sample k0 + 1. Clamping s to [0, n-1] holds the value constant
// between the outermost sample and the wall. On a periodic axis there is no wall: k0 may be -1
// or n - 1 (reading the wrapped ghosts, sample n = sample 0).
struct Axis {
  PetscInt k0;
  double w;
};
Axis axis(double x, double h, double off, PetscInt n, bool periodic = false) {
  if (periodic) {
    const double s = x / h - off;
    const auto k0 = static_cast<PetscInt>(std::floor(s));
    return {k0, s - k0};
  }
  const double s = std::clamp(x / h - off, 0.0, static_cast<double>(n - 1));
  const PetscInt k0 = std::min(static_cast<PetscInt>(std::floor(s)), n - 2);
  return {k0, s - k0};
}

template <class Get>
double bilinear(const Axis& ax, const Axis& ay, Get f) {
  const PetscInt i = ax.k0, j = ay.k0;
  return (1 - ay.w) * ((1 - ax.w) * f(j, i) + ax.w * f(j, i + 1)) +
         ay.w * ((1 - ax.w) * f(j + 1, i) + ax.w * f(j + 1, i + 1));
}

bool valid_name(const std::string& s) {
  if (s.empty() || s == "." || s == "..") return false;
  for (const char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.'))
      return false;
  return true;
}

// The coordinate clamped into [0, L], accepting a round-off overshoot (a case file giving
// x1 = Lx as a sum of decimals), rejecting a real one.
double inside(double x, double L, const std::string& what) {
  const double tol = 1e-9 * L;
  if (!std::isfinite(x) || x < -tol || x > L + tol)
    throw InputError(what + " = " + std::to_string(x) + " is outside the domain [0, " +
                     std::to_string(L) + "]");
  return std::clamp(x, 0.0, L);
}

}  // namespace

std::vector<std::string> default_extra_cell_fields() { return {"D_norm", "S_norm", "kappa"}; }

ProbeWriter::ProbeWriter(const Grid& g, std::string dir, std::vector<ProbeSpec> specs,
                         std::vector<std::string> extra_cell_fields,
                         const std::vector<long long>& resume_bytes)
    : g_(g), extra_(std::move(extra_cell_fields)) {
  if (!resume_bytes.empty() && resume_bytes.size() != specs.size())
    throw std::invalid_argument("ProbeWriter: resume_bytes must have one entry per probe");
  const Box& b = g.box();
  {
    std::set<std::string> ex;
    for (const std::string& e : extra_)
      if (e.empty() || !ex.insert(e).second ||
          std::find(std::begin(kNames), std::end(kNames), e) != std::end(kNames))
        throw std::invalid_argument("ProbeWriter: extra cell field '" + e +
                                    "' is empty, repeated or a built-in name");
  }
  needs_.assign(kCount + extra_.size(), 0);
  std::string known = "phi, rho, u, v, speed, p, eta";
  for (const std::string& e : extra_) known += ", " + e;
  std::set<std::string> names;
  for (ProbeSpec& s : specs) {
    const std::string where = "probe '" + s.name + "'";
    if (!valid_name(s.name))
      throw InputError(where + ": the name must be non-empty and use only letters, digits, "
                               "'_', '-', '.' (it names the CSV file)");
    if (!names.insert(s.name).second) throw InputError(where + ": name used twice");
    if (s.points < 1) throw InputError(where + ": points must be >= 1");
    if (s.fields.empty()) throw InputError(where + ": no fields");
    Probe p;
    std::set<std::string> seen;
    for (const std::string& f : s.fields) {
      const auto* it = std::find_if(std::begin(kNames), std::end(kNames),
                                    [&](const char* n) { return f == n; });
      const auto ex = std::find(extra_.begin(), extra_.end(), f);
      if (it == std::end(kNames) && ex == extra_.end())
        throw InputError(where + ": unknown field '" + f + "' (known: " + known + ")");
      if (!seen.insert(f).second) throw InputError(where + ": field '" + f + "' listed twice");
      p.q.push_back(it != std::end(kNames) ? static_cast<int>(it - std::begin(kNames))
                                           : kCount + static_cast<int>(ex - extra_.begin()));
    }
    const double x0 = inside(s.x0, b.Lx, where + " x0"), x1 = inside(s.x1, b.Lx, where + " x1");
    const double y0 = inside(s.y0, b.Ly, where + " y0"), y1 = inside(s.y1, b.Ly, where + " y1");
    for (int k = 0; k < s.points; ++k) {
      const double a = s.points == 1 ? 0.0 : static_cast<double>(k) / (s.points - 1);
      const bool last = s.points > 1 && k == s.points - 1;
      p.x.push_back(last ? x1 : x0 + a * (x1 - x0));
      p.y.push_back(last ? y1 : y0 + a * (y1 - y0));
      // Owner: the rank owning the containing cell; a point on an inner cell edge goes to
      // the cell on its right/top, one on the right/top wall to the last cell.
      const PetscInt ic = std::clamp(static_cast<PetscInt>(std::floor(p.x.back() / b.hx)),
                                     PetscInt(0), b.nx - 1);
      const PetscInt jc = std::clamp(static_cast<PetscInt>(std::floor(p.y.back() / b.hy)),
                                     PetscInt(0), b.ny - 1);
      p.mine.push_back(ic >= b.xs && ic < b.xe() && jc >= b.ys && jc < b.ye());
    }
    for (const int q : p.q) needs_[q] = 1;
    p.spec = std::move(s);
    probes_.push_back(std::move(p));
  }
  // u and v are needed for speed; rho/phi/p/eta only if asked for.
  if (needs_[kSpeed]) needs_[kU] = needs_[kV] = 1;

  for (std::size_t n = 0; n < probes_.size(); ++n) {
    const Probe& p = probes_[n];
    std::vector<std::string> cols = {"t", "x", "y"};
    cols.insert(cols.end(), p.spec.fields.begin(), p.spec.fields.end());
    const std::string path = dir + "/probes/" + p.spec.name + ".csv";
    if (resume_bytes.empty())
      csv_.emplace_back(path, std::move(cols), g.comm());
    else
      csv_.emplace_back(path, std::move(cols), resume_bytes[n], g.comm());
  }
}

std::vector<std::pair<std::string, long long>> ProbeWriter::file_bytes() const {
  std::vector<std::pair<std::string, long long>> out;
  for (std::size_t n = 0; n < probes_.size(); ++n)
    out.emplace_back(probes_[n].spec.name, csv_[n].bytes());
  return out;
}

bool ProbeWriter::samples(const std::string& field) const {
  for (const Probe& pr : probes_)
    if (std::find(pr.spec.fields.begin(), pr.spec.fields.end(), field) != pr.spec.fields.end())
      return true;
  return false;
}

void ProbeWriter::write(double t, Vec phi, Vec rho, Vec vel, Vec p, Vec eta,
                        const NamedCellFields& extra) {
  const Box& b = g_.box();
  const std::size_t nq = needs_.size();
  // The cell-centred Vec of every quantity (null for u, v, speed).
  std::vector<Vec> cellvec(nq, nullptr);
  cellvec[kPhi] = phi;
  cellvec[kRho] = rho;
  cellvec[kP] = p;
  cellvec[kEta] = eta;
  std::vector<char> given(extra_.size(), 0);
  for (const auto& [name, vec] : extra) {
    const auto it = std::find(extra_.begin(), extra_.end(), name);
    if (it == extra_.end())
      throw std::invalid_argument("ProbeWriter::write: unknown extra cell field '" + name + "'");
    const std::size_t e = static_cast<std::size_t>(it - extra_.begin());
    if (given[e]) throw std::invalid_argument("ProbeWriter::write: extra cell field '" + name +
                                              "' given twice");
    given[e] = 1;
    cellvec[kCount + e] = vec;
  }
  auto name_of = [&](std::size_t q) {
    return q < kCount ? std::string(kNames[q]) : extra_[q - kCount];
  };
  for (std::size_t q = 0; q < nq; ++q)
    if (q != kU && q != kV && q != kSpeed && needs_[q] && !cellvec[q])
      throw std::invalid_argument("ProbeWriter::write: a probe samples '" + name_of(q) +
                                  "' but its Vec is " + (q < kCount ? "null" : "null or missing"));
  if ((needs_[kU] || needs_[kV]) && !vel)
    throw std::invalid_argument("ProbeWriter::write: a probe samples the velocity but vel is null");

  // Ghosted local copies, only of what some probe samples (the exchange is collective, so
  // this choice is the same on all ranks).
  std::vector<std::unique_ptr<LocalCells>> cells(nq);
  for (std::size_t q = 0; q < nq; ++q)
    if (cellvec[q] && needs_[q])
      cells[q] = std::make_unique<LocalCells>(g_.dm_cell(), cellvec[q]);
  std::unique_ptr<LocalVelocity> v;
  if (needs_[kU] || needs_[kV]) v = std::make_unique<LocalVelocity>(g_, vel);

  // One buffer for all probes: -0.0 where this rank does not own the point (see the header).
  std::size_t total = 0;
  for (const Probe& pr : probes_) total += pr.x.size() * pr.q.size();
  std::vector<double> mine(total, -0.0), all(g_.rank() == 0 ? total : 0);
  std::size_t at = 0;
  for (const Probe& pr : probes_)
    for (std::size_t k = 0; k < pr.x.size(); ++k, at += pr.q.size()) {
      if (!pr.mine[k]) continue;
      const double x = pr.x[k], y = pr.y[k];
      const Axis cx = axis(x, b.hx, 0.5, b.nx, b.periodic_x), cy = axis(y, b.hy, 0.5, b.ny);
      double u = 0, w = 0;
      if (v) {
        const LocalVelocity& vv = *v;
        // periodic x: the u-faces are nx samples with period nx (face nx = face 0)
        u = bilinear(axis(x, b.hx, 0.0, b.periodic_x ? b.nx : b.nx + 1, b.periodic_x), cy,
                     [&](PetscInt j, PetscInt i) { return vv[j][i].u; });
        w = bilinear(cx, axis(y, b.hy, 0.0, b.ny + 1),
                     [&](PetscInt j, PetscInt i) { return vv[j][i].v; });
      }
      for (std::size_t m = 0; m < pr.q.size(); ++m) {
        const int q = pr.q[m];
        double val;
        if (q == kU) val = u;
        else if (q == kV) val = w;
        else if (q == kSpeed) val = std::sqrt(u * u + w * w);
        else {
          const LocalCells& c = *cells[q];
          val = bilinear(cx, cy, [&](PetscInt j, PetscInt i) { return c[j][i]; });
        }
        mine[at + m] = val;
      }
    }
  if (total > 0)
    MPI_Reduce(mine.data(), g_.rank() == 0 ? all.data() : nullptr, static_cast<int>(total),
               MPI_DOUBLE, MPI_SUM, 0, g_.comm());

  // Rank 0 writes (CsvWriter::row is a no-op elsewhere); a write error there is passed to
  // every rank so that all stop together.
  std::string err;
  try {
    at = 0;
    std::vector<double> row;
    for (std::size_t n = 0; n < probes_.size(); ++n) {
      const Probe& pr = probes_[n];
      for (std::size_t k = 0; k < pr.x.size(); ++k, at += pr.q.size()) {
        row.assign({t, pr.x[k], pr.y[k]});
        for (std::size_t m = 0; m < pr.q.size(); ++m)
          row.push_back(g_.rank() == 0 ? all[at + m] : 0.0);
        csv_[n].row(row);
      }
    }
  } catch (const IoError& e) {
    err = e.what();
  }
  raise_on_all_ranks(g_.comm(), err);
}

}  // namespace gf::io
