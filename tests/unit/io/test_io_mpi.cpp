// VTK series, cell velocity and line probes, on 1 and 2 ranks (the _mpi suffix runs both):
// the files are read back on rank 0 and checked value by value, and the files written on the
// world communicator must be byte-identical to those written by rank 0 alone.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <numbers>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "core/Error.hpp"
#include "diagnostics/Diagnostics.hpp"
#include "fields/Fields.hpp"
#include "grid/Grid.hpp"
#include "io/Csv.hpp"
#include "io/Json.hpp"
#include "io/Probes.hpp"
#include "io/Vtk.hpp"

namespace {

namespace fs = std::filesystem;
using gf::Grid;

int world_rank() {
  int r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// A fresh folder named by rank 0 and shared by all ranks; removed at the end.
class IoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string d;
    if (world_rank() == 0) {
      d = (fs::temp_directory_path() /
           ("gf_test_io_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name()))
              .string();
      fs::remove_all(d);
    }
    int n = static_cast<int>(d.size());
    MPI_Bcast(&n, 1, MPI_INT, 0, PETSC_COMM_WORLD);
    d.resize(n);
    MPI_Bcast(d.data(), n, MPI_CHAR, 0, PETSC_COMM_WORLD);
    dir = d;
  }
  void TearDown() override {
    MPI_Barrier(PETSC_COMM_WORLD);
    if (world_rank() == 0) fs::remove_all(dir);
  }
  fs::path dir;
};

template <class F>
void set_cells(const Grid& g, Vec v, F f) {
  const gf::Box& b = g.box();
  PetscScalar** a;
  GF_PETSC(DMDAVecGetArray(g.dm_cell(), v, &a));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) a[j][i] = f(i, j);
  GF_PETSC(DMDAVecRestoreArray(g.dm_cell(), v, &a));
}

template <class Fu, class Fv>
void set_vel(const Grid& g, Vec v, Fu fu, Fv fv) {
  const gf::Box& b = g.box();
  gf::Vel** a;
  GF_PETSC(DMDAVecGetArray(g.dm_vel(), v, &a));
  for (PetscInt j = b.ys; j < b.ye(); ++j)
    for (PetscInt i = b.xs; i < b.xe(); ++i) a[j][i] = {fu(i, j), fv(i, j)};
  GF_PETSC(DMDAVecRestoreArray(g.dm_vel(), v, &a));
}

// ---- A minimal reader of the .vtr files this writer produces (appended raw, UInt64 headers).
struct VtrArray {
  int components = 0;
  std::vector<double> data;
};
struct Vtr {
  bool ok = false;
  std::string extent;
  double time = NAN;
  std::map<std::string, VtrArray> arrays;  // cell arrays and coordinates x, y, z
};

Vtr read_vtr(const fs::path& p) {
  Vtr v;
  const std::string s = slurp(p);
  const std::string tag = "<AppendedData encoding=\"raw\">";
  const std::size_t at = s.find(tag);
  if (at == std::string::npos) return v;
  const std::size_t base = s.find('_', at) + 1;
  const std::string head = s.substr(0, at);
  std::smatch m;
  if (std::regex_search(head, m, std::regex("<Piece Extent=\"([0-9 ]+)\">"))) v.extent = m[1];
  if (std::regex_search(head, m, std::regex("Name=\"TimeValue\"[^>]*>([^<]+)<")))
    v.time = std::stod(m[1]);
  const std::regex da(
      "<DataArray type=\"Float64\" Name=\"([^\"]+)\" NumberOfComponents=\"([0-9]+)\" "
      "format=\"appended\" offset=\"([0-9]+)\"/>");
  std::size_t end = base;
  for (auto it = std::sregex_iterator(head.begin(), head.end(), da); it != std::sregex_iterator();
       ++it) {
    VtrArray a;
    a.components = std::stoi((*it)[2]);
    const std::size_t off = base + std::stoull((*it)[3]);
    std::uint64_t bytes = 0;
    if (off + 8 > s.size()) return v;
    std::memcpy(&bytes, s.data() + off, 8);
    if (off + 8 + bytes > s.size()) return v;
    a.data.resize(bytes / 8);
    std::memcpy(a.data.data(), s.data() + off + 8, bytes);
    end = std::max<std::size_t>(end, off + 8 + bytes);
    v.arrays[(*it)[1]] = std::move(a);
  }
  v.ok = s.substr(end) == "\n  </AppendedData>\n</VTKFile>\n";
  return v;
}

// (timestep, file) entries of a .pvd, and whether its frame is what ParaView expects.
std::vector<std::pair<double, std::string>> read_pvd(const fs::path& p, bool& well_formed) {
  const std::string s = slurp(p);
  well_formed = s.rfind("<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\"", 0) == 0 &&
                s.find("<Collection>") != std::string::npos &&
                s.ends_with("  </Collection>\n</VTKFile>\n");
  std::vector<std::pair<double, std::string>> out;
  const std::regex ds(
      "<DataSet timestep=\"([^\"]+)\" group=\"\" part=\"0\" file=\"([^\"]+)\"/>");
  for (auto it = std::sregex_iterator(s.begin(), s.end(), ds); it != std::sregex_iterator(); ++it)
    out.emplace_back(std::stod((*it)[1]), (*it)[2]);
  // Every line between the tags is a DataSet: nothing else slipped in.
  std::size_t lines = 0;
  for (char c : s) lines += c == '\n';
  well_formed = well_formed && lines == out.size() + 5;
  return out;
}

// ---- Fields used by several tests. Values depend on global (i, j) only.
double fphi(PetscInt i, PetscInt j) { return 0.25 + i + 100.0 * j; }
double fu(PetscInt i, PetscInt j) { return i == 0 ? 0.0 : 0.1 * i - 0.03 * j * j; }
double fv(PetscInt i, PetscInt j) { return j == 0 ? 0.0 : std::sin(0.7 * i + 0.3 * j); }

TEST_F(IoTest, VtkSeriesReadBack) {
  const PetscInt nx = 12, ny = 10;
  Grid g(PETSC_COMM_WORLD, nx, ny, 1.2, 0.5);
  gf::State s(g);
  set_cells(g, s.phi, fphi);
  set_vel(g, s.vel, fu, fv);
  {  // S on dm_ten: three interleaved components.
    const gf::Box& b = g.box();
    PetscScalar*** a;
    GF_PETSC(DMDAVecGetArrayDOF(g.dm_ten(), s.S, &a));
    for (PetscInt j = b.ys; j < b.ye(); ++j)
      for (PetscInt i = b.xs; i < b.xe(); ++i) {
        a[j][i][0] = i;
        a[j][i][1] = -j;
        a[j][i][2] = i * j;
      }
    GF_PETSC(DMDAVecRestoreArrayDOF(g.dm_ten(), s.S, &a));
  }
  // The velocity as one dof-2 cell vector (a dm_vel Vec reused) plus the speed.
  gf::Field uv(g.dm_vel(), "u"), speed(g.dm_cell(), "speed");
  gf::io::cell_velocity(g, s.vel, uv, nullptr, speed);

  gf::io::VtkSeries vtk(g, (dir / "out").string(), "fields");
  const std::vector<double> times = {0.0, 0.125, 1.0 / 3.0};
  for (double t : times)
    vtk.write(t, {{"phi", s.phi, 1}, {"u", uv, 2}, {"speed", speed, 1}, {"S", s.S, 3}});
  EXPECT_EQ(vtk.files_written(), 3);
  EXPECT_EQ(vtk.last_file(), (dir / "out" / "fields_000002.vtr").string());
  EXPECT_THROW(vtk.write(0.5, {{"phi", s.phi, 1}, {"phi", s.phi, 1}}), std::invalid_argument);
  EXPECT_THROW(vtk.write(0.5, {{"phi", s.phi, 2}}), std::invalid_argument);
  EXPECT_EQ(vtk.files_written(), 3);
  if (world_rank() != 0) return;

  // The collection lists every file with its time, and nothing else is left in the folder.
  bool well_formed = false;
  const auto entries = read_pvd(dir / "out" / "fields.pvd", well_formed);
  EXPECT_TRUE(well_formed) << slurp(dir / "out" / "fields.pvd");
  ASSERT_EQ(entries.size(), times.size());
  for (std::size_t k = 0; k < times.size(); ++k) {
    EXPECT_EQ(entries[k].first, times[k]);
    char name[32];
    std::snprintf(name, sizeof name, "fields_%06zu.vtr", k);
    EXPECT_EQ(entries[k].second, name);
    EXPECT_TRUE(fs::exists(dir / "out" / name));
  }
  std::size_t nfiles = 0;
  for (const auto& e : fs::directory_iterator(dir / "out")) {
    ++nfiles;
    EXPECT_NE(e.path().extension(), ".tmp");
  }
  EXPECT_EQ(nfiles, times.size() + 1);

  const Vtr v = read_vtr(dir / "out" / "fields_000002.vtr");
  ASSERT_TRUE(v.ok);
  EXPECT_EQ(v.extent, "0 12 0 10 0 0");
  EXPECT_EQ(v.time, 1.0 / 3.0);
  ASSERT_EQ(v.arrays.size(), 7u);  // 4 fields + 3 coordinates
  const auto& x = v.arrays.at("x").data;
  const auto& y = v.arrays.at("y").data;
  ASSERT_EQ(x.size(), 13u);
  ASSERT_EQ(y.size(), 11u);
  EXPECT_EQ(v.arrays.at("z").data, std::vector<double>{0.0});
  EXPECT_EQ(x.front(), 0.0);
  EXPECT_EQ(x.back(), 1.2);
  EXPECT_EQ(y.back(), 0.5);
  EXPECT_NEAR(x[5], 0.5, 1e-15);

  const VtrArray &phi = v.arrays.at("phi"), &u = v.arrays.at("u"), &sp = v.arrays.at("speed"),
                 &S = v.arrays.at("S");
  ASSERT_EQ(phi.components, 1);
  ASSERT_EQ(u.components, 3);  // 2-vector padded with z = 0
  ASSERT_EQ(S.components, 3);
  ASSERT_EQ(phi.data.size(), 120u);
  ASSERT_EQ(u.data.size(), 360u);
  ASSERT_EQ(sp.data.size(), 120u);
  ASSERT_EQ(S.data.size(), 360u);
  for (PetscInt j = 0; j < ny; ++j)
    for (PetscInt i = 0; i < nx; ++i) {
      const std::size_t c = j * nx + i;  // VTK cell order: x fastest
      EXPECT_EQ(phi.data[c], fphi(i, j));
      // Face averages, with the unstored wall faces i = nx / j = ny at zero.
      const double uc = 0.5 * (fu(i, j) + (i + 1 < nx ? fu(i + 1, j) : 0.0));
      const double vc = 0.5 * (fv(i, j) + (j + 1 < ny ? fv(i, j + 1) : 0.0));
      EXPECT_EQ(u.data[3 * c], uc) << i << "," << j;
      EXPECT_EQ(u.data[3 * c + 1], vc) << i << "," << j;
      EXPECT_EQ(u.data[3 * c + 2], 0.0);
      EXPECT_EQ(sp.data[c], std::sqrt(uc * uc + vc * vc));
      EXPECT_EQ(S.data[3 * c], i);
      EXPECT_EQ(S.data[3 * c + 1], -j);
      EXPECT_EQ(S.data[3 * c + 2], i * j);
    }
}

TEST_F(IoTest, CellVelocityScalarForm) {
  // The two dof-1 form gives the same numbers as the dof-2 form.
  Grid g(PETSC_COMM_WORLD, 12, 10, 1.0, 1.0);
  gf::State s(g);
  set_vel(g, s.vel, fu, fv);
  gf::Field uv(g.dm_vel(), "uv"), uc(g.dm_cell(), "uc"), vc(g.dm_cell(), "vc");
  gf::io::cell_velocity(g, s.vel, uv, nullptr, nullptr);
  gf::io::cell_velocity(g, s.vel, uc, vc, nullptr);
  Vec both[2] = {uc, vc};
  gf::Field joined(g.dm_vel(), "joined");
  GF_PETSC(VecStrideScatterAll(both, joined, INSERT_VALUES));
  PetscBool eq = PETSC_FALSE;
  GF_PETSC(VecEqual(uv, joined, &eq));
  EXPECT_TRUE(eq);
  // The largest value of the speed is what diag::max_speed reports.
  gf::Field speed(g.dm_cell(), "speed");
  gf::io::cell_velocity(g, s.vel, nullptr, nullptr, speed);
  PetscReal smax = 0;
  GF_PETSC(VecMax(speed, nullptr, &smax));
  EXPECT_EQ(smax, gf::diag::max_speed(g, s.vel));
  // A Vec with the wrong layout is refused on every rank.
  EXPECT_THROW(gf::io::cell_velocity(g, s.vel, uc, nullptr, nullptr), std::invalid_argument);
}

// Parses a probe CSV: header and rows of numbers.
struct Table {
  std::string header;
  std::vector<std::vector<double>> rows;
};
Table read_csv(const fs::path& p) {
  Table t;
  std::ifstream f(p);
  std::getline(f, t.header);
  for (std::string line; std::getline(f, line);) {
    std::vector<double> r;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) r.push_back(std::stod(cell));
    t.rows.push_back(r);
  }
  return t;
}

TEST_F(IoTest, ProbesReproduceLinearFields) {
  // hx = 0.1, hy = 0.05. Linear fields sampled at their own staggered positions; the u and v
  // wall faces i = 0 / j = 0 are zero as the convention demands, so the probe line keeps at
  // least one cell away from the walls, where bilinear interpolation is exact.
  Grid g(PETSC_COMM_WORLD, 16, 12, 1.6, 0.6);
  gf::State s(g);
  const gf::Box& b = g.box();
  auto phi = [](double x, double y) { return 1 + 2 * x + 3 * y; };
  auto rho = [](double x, double) { return 1000 + 10 * x; };
  auto pr = [](double x, double y) { return -5 + x - y; };
  auto eta = [](double, double y) { return 0.5 * y; };
  auto U = [](double x, double y) { return 0.2 + 0.5 * x + 0.7 * y; };
  auto V = [](double x, double y) { return -0.1 + 0.3 * x + 0.4 * y; };
  set_cells(g, s.phi, [&](PetscInt i, PetscInt j) { return phi(b.xc(i), b.yc(j)); });
  set_cells(g, s.rho, [&](PetscInt i, PetscInt j) { return rho(b.xc(i), b.yc(j)); });
  set_cells(g, s.p, [&](PetscInt i, PetscInt j) { return pr(b.xc(i), b.yc(j)); });
  set_cells(g, s.eta, [&](PetscInt i, PetscInt j) { return eta(b.xc(i), b.yc(j)); });
  set_vel(g, s.vel, [&](PetscInt i, PetscInt j) { return i == 0 ? 0.0 : U(b.xf(i), b.yc(j)); },
          [&](PetscInt i, PetscInt j) { return j == 0 ? 0.0 : V(b.xc(i), b.yf(j)); });

  std::vector<gf::io::ProbeSpec> specs = {
      {"diag", 0.15, 0.08, 1.45, 0.52, 7, {"phi", "rho", "u", "v", "speed", "p", "eta"}},
      {"walls", 0.0, 0.3, 1.6, 0.6, 2, {"u", "v", "phi"}},
  };
  gf::io::ProbeWriter pw(g, dir.string(), specs);
  pw.write(0.0, s.phi, s.rho, s.vel, s.p, s.eta);
  pw.write(0.5, s.phi, s.rho, s.vel, s.p, s.eta);
  // Missing Vec for a sampled field: refused.
  EXPECT_THROW(pw.write(1.0, s.phi, nullptr, s.vel, s.p, s.eta), std::invalid_argument);
  if (world_rank() != 0) return;

  const Table d = read_csv(dir / "probes" / "diag.csv");
  EXPECT_EQ(d.header, "t,x,y,phi,rho,u,v,speed,p,eta");
  ASSERT_EQ(d.rows.size(), 14u);  // 2 blocks of 7 points
  for (std::size_t r = 0; r < d.rows.size(); ++r) {
    const auto& row = d.rows[r];
    ASSERT_EQ(row.size(), 10u);
    const std::size_t k = r % 7;
    EXPECT_EQ(row[0], r < 7 ? 0.0 : 0.5);
    const double x = row[1], y = row[2];
    EXPECT_NEAR(x, 0.15 + 1.3 * k / 6.0, 1e-15);
    EXPECT_NEAR(y, 0.08 + 0.44 * k / 6.0, 1e-15);
    const double tol = 1e-13;
    EXPECT_NEAR(row[3], phi(x, y), tol) << "phi at " << x << "," << y;
    EXPECT_NEAR(row[4], rho(x, y), 1e-11);
    EXPECT_NEAR(row[5], U(x, y), tol) << "u at " << x << "," << y;
    EXPECT_NEAR(row[6], V(x, y), tol) << "v at " << x << "," << y;
    EXPECT_NEAR(row[7], std::hypot(U(x, y), V(x, y)), tol);
    EXPECT_NEAR(row[8], pr(x, y), tol);
    EXPECT_NEAR(row[9], eta(x, y), tol);
  }
  EXPECT_EQ(d.rows[6][1], 1.45);  // the end point is exact
  EXPECT_EQ(d.rows[6][2], 0.52);

  // At the walls: u = 0 on x = 0 and x = Lx, v = 0 on y = Ly; phi is held at the value of
  // the outermost centres (clamping, no extrapolation).
  const Table w = read_csv(dir / "probes" / "walls.csv");
  EXPECT_EQ(w.header, "t,x,y,u,v,phi");
  ASSERT_EQ(w.rows.size(), 4u);
  EXPECT_EQ(w.rows[0][3], 0.0);                                     // u(0, 0.3)
  EXPECT_NEAR(w.rows[0][4], V(0.05, 0.3), 1e-13);                   // v held at x = hx/2
  EXPECT_NEAR(w.rows[0][5], phi(0.05, 0.3), 1e-13);                 // phi held at x = hx/2
  EXPECT_EQ(w.rows[1][3], 0.0);                                     // u(Lx, Ly)
  EXPECT_EQ(w.rows[1][4], 0.0);                                     // v(Lx, Ly)
  EXPECT_NEAR(w.rows[1][5], phi(1.55, 0.575), 1e-13);
}

TEST_F(IoTest, ProbesSampleExtraCellFields) {
  // The plastic fields D_norm, S_norm, kappa (the default extra cell fields) are passed by
  // name and sampled like the other cell-centred fields: linear fields are reproduced.
  Grid g(PETSC_COMM_WORLD, 16, 12, 1.6, 0.6);
  gf::State s(g);
  const gf::Box& b = g.box();
  gf::Field dn(g.dm_cell(), "D_norm"), sn(g.dm_cell(), "S_norm"), kap(g.dm_cell(), "kappa");
  auto D = [](double x, double y) { return 2 + 3 * x - y; };
  auto S = [](double x, double y) { return 0.1 * x + 0.9 * y; };
  auto K = [](double x, double y) { return 100 - 20 * y + x; };
  set_cells(g, dn, [&](PetscInt i, PetscInt j) { return D(b.xc(i), b.yc(j)); });
  set_cells(g, sn, [&](PetscInt i, PetscInt j) { return S(b.xc(i), b.yc(j)); });
  set_cells(g, kap, [&](PetscInt i, PetscInt j) { return K(b.xc(i), b.yc(j)); });
  set_vel(g, s.vel, [&](PetscInt, PetscInt j) { return 0.5 * b.yc(j); },
          [&](PetscInt, PetscInt) { return 0.0; });

  gf::io::ProbeWriter pw(g, dir.string(),
                         {{"plastic", 0.15, 0.08, 1.45, 0.52, 5, {"kappa", "u", "D_norm", "S_norm"}},
                          {"only_u", 0.8, 0.1, 0.8, 0.5, 3, {"u"}}});
  EXPECT_EQ(gf::io::default_extra_cell_fields(),
            (std::vector<std::string>{"D_norm", "S_norm", "kappa"}));
  EXPECT_TRUE(pw.samples("D_norm"));
  EXPECT_TRUE(pw.samples("u"));
  EXPECT_FALSE(pw.samples("p"));
  // Order of the extras does not matter; phi, rho, p, eta are not sampled: null is fine.
  pw.write(0.25, nullptr, nullptr, s.vel, nullptr, nullptr,
           {{"S_norm", sn}, {"kappa", kap}, {"D_norm", dn}});
  // A sampled extra field missing or null, an unknown name, a name twice: refused, and
  // nothing is written (checked before any collective work).
  EXPECT_THROW(pw.write(1, nullptr, nullptr, s.vel, nullptr, nullptr, {{"S_norm", sn}, {"kappa", kap}}),
               std::invalid_argument);
  EXPECT_THROW(pw.write(1, nullptr, nullptr, s.vel, nullptr, nullptr,
                        {{"S_norm", sn}, {"kappa", kap}, {"D_norm", nullptr}}),
               std::invalid_argument);
  EXPECT_THROW(pw.write(1, nullptr, nullptr, s.vel, nullptr, nullptr,
                        {{"S_norm", sn}, {"kappa", kap}, {"D_norm", dn}, {"yielded", dn}}),
               std::invalid_argument);
  EXPECT_THROW(pw.write(1, nullptr, nullptr, s.vel, nullptr, nullptr,
                        {{"S_norm", sn}, {"kappa", kap}, {"D_norm", dn}, {"kappa", kap}}),
               std::invalid_argument);
  // An unknown field in a spec is still an input error, and names the extras among the known.
  try {
    gf::io::ProbeWriter(g, dir.string(), {{"bad", 0, 0, 1, 0, 3, {"yielded"}}});
    ADD_FAILURE() << "no exception";
  } catch (const gf::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("known: phi, rho, u, v, speed, p, eta, D_norm, S_norm, "
                                         "kappa"),
              std::string::npos)
        << e.what();
  }
  // A writer with its own list of extra cell fields; a bad list is a programming error.
  {
    gf::io::ProbeWriter own(g, (dir / "own").string(), {{"y", 0.8, 0.1, 0.8, 0.5, 2, {"yielded"}}},
                            {"yielded"});
    own.write(0.0, nullptr, nullptr, nullptr, nullptr, nullptr, {{"yielded", kap}});
    EXPECT_THROW(gf::io::ProbeWriter(g, (dir / "own2").string(), {}, {"p"}), std::invalid_argument);
    EXPECT_THROW(gf::io::ProbeWriter(g, (dir / "own2").string(), {}, {"a", "a"}),
                 std::invalid_argument);
  }
  if (world_rank() != 0) return;

  const Table d = read_csv(dir / "probes" / "plastic.csv");
  EXPECT_EQ(d.header, "t,x,y,kappa,u,D_norm,S_norm");
  ASSERT_EQ(d.rows.size(), 5u);
  for (const auto& row : d.rows) {
    ASSERT_EQ(row.size(), 7u);
    EXPECT_EQ(row[0], 0.25);
    const double x = row[1], y = row[2];
    EXPECT_NEAR(row[3], K(x, y), 1e-12) << "kappa at " << x << "," << y;
    EXPECT_NEAR(row[4], 0.5 * y, 1e-14);
    EXPECT_NEAR(row[5], D(x, y), 1e-13) << "D_norm at " << x << "," << y;
    EXPECT_NEAR(row[6], S(x, y), 1e-13) << "S_norm at " << x << "," << y;
  }
  const Table u = read_csv(dir / "probes" / "only_u.csv");
  EXPECT_EQ(u.header, "t,x,y,u");
  EXPECT_EQ(u.rows.size(), 3u);  // one block: the refused writes wrote nothing
  const Table y = read_csv(dir / "own" / "probes" / "y.csv");
  EXPECT_EQ(y.header, "t,x,y,yielded");
  ASSERT_EQ(y.rows.size(), 2u);
  EXPECT_NEAR(y.rows[1][3], K(0.8, 0.5), 1e-12);
}

TEST_F(IoTest, ProbeSpecErrors) {
  Grid g(PETSC_COMM_WORLD, 16, 12, 1.6, 0.6);
  auto make = [&](gf::io::ProbeSpec s) {
    gf::io::ProbeWriter(g, dir.string(), {std::move(s)});
  };
  EXPECT_THROW(make({"a", 0, 0, 2.0, 0, 3, {"phi"}}), gf::InputError);      // outside
  EXPECT_THROW(make({"a", 0, 0, 1, 0, 0, {"phi"}}), gf::InputError);        // no points
  EXPECT_THROW(make({"a", 0, 0, 1, 0, 3, {"temp"}}), gf::InputError);       // unknown field
  EXPECT_THROW(make({"a", 0, 0, 1, 0, 3, {"u", "u"}}), gf::InputError);     // twice
  EXPECT_THROW(make({"../a", 0, 0, 1, 0, 3, {"u"}}), gf::InputError);       // bad name
  EXPECT_NO_THROW(make({"ok", 0, 0, 1.6 + 1e-12, 0.6, 1, {"u"}}));          // round-off
}

// ---- One small run written on `comm`: two snapshots, probes crossing the rank boundary, a
// CSV of maxima (decomposition-independent, unlike sums) and a JSON summary.
void write_everything(MPI_Comm comm, const fs::path& out) {
  Grid g(comm, 20, 16, 1.0, 0.8);
  gf::State s(g);
  const gf::Box& b = g.box();
  const double pi = std::numbers::pi;
  set_cells(g, s.phi, [&](PetscInt i, PetscInt j) { return b.yc(j) - 0.3 - 0.1 * std::sin(pi * b.xc(i)); });
  set_cells(g, s.rho, [&](PetscInt i, PetscInt j) { return 1 + 1e-3 * i * j; });
  // p = -0.0 in the bottom rows: probe values there are -0.0 and must stay so after the
  // reduction (a +0.0 identity would turn them into "0" on 2 ranks but not on 1).
  set_cells(g, s.p, [&](PetscInt i, PetscInt j) {
    return j < 4 ? -0.0 : std::exp(-0.1 * i) * std::cos(j);
  });
  set_cells(g, s.eta, [&](PetscInt i, PetscInt j) { return 1.0 / (1 + i + j); });
  set_vel(g, s.vel, [&](PetscInt i, PetscInt j) { return i == 0 ? 0.0 : std::sin(i * 0.37 + j); },
          [&](PetscInt i, PetscInt j) { return j == 0 ? 0.0 : -0.1 * std::cos(i - 0.2 * j); });
  gf::Field uv(g.dm_vel(), "u"), speed(g.dm_cell(), "speed");
  gf::io::cell_velocity(g, s.vel, uv, nullptr, speed);

  gf::io::VtkSeries vtk(g, (out / "vtk").string(), "fields");
  gf::io::ProbeWriter probes(
      g, out.string(),
      {{"horizontal", 0.0, 0.41, 1.0, 0.41, 23, {"phi", "u", "v", "speed", "p"}},
       {"vertical", 0.5, 0.0, 0.5, 0.8, 17, {"rho", "eta", "v", "p", "kappa"}},
       {"point", 0.73, 0.12, 0.73, 0.12, 1, {"speed"}}});
  gf::io::CsvWriter csv((out / "diagnostics.csv").string(),
                        {"t", "max_speed", "max_divergence", "max_eta_granular"}, comm);
  for (double t : {0.0, 0.1}) {
    vtk.write(t, {{"phi", s.phi, 1}, {"u", uv, 2}, {"speed", speed, 1}, {"p", s.p, 1},
                  {"S", s.S, 3}});
    probes.write(t, s.phi, s.rho, s.vel, s.p, s.eta, {{"kappa", s.rho}});
    csv.row({t, gf::diag::max_speed(g, s.vel), gf::diag::max_divergence(g, s.vel),
             gf::diag::max_in_granular(g, s.eta, s.phi)});
    GF_PETSC(VecScale(s.p, 0.5));
  }
  gf::io::JsonObject js;
  js.set("max_speed", gf::diag::max_speed(g, s.vel)).object("grid").set("nx", g.nx());
  js.write_root((out / "summary.json").string(), comm);
}

TEST_F(IoTest, FilesDoNotDependOnRankCount) {
  write_everything(PETSC_COMM_WORLD, dir / "world");
  if (world_rank() == 0) {
    write_everything(PETSC_COMM_SELF, dir / "self");
    std::size_t compared = 0;
    for (const auto& e : fs::recursive_directory_iterator(dir / "self")) {
      if (!e.is_regular_file()) continue;
      const fs::path rel = fs::relative(e.path(), dir / "self");
      ASSERT_TRUE(fs::exists(dir / "world" / rel)) << rel;
      EXPECT_TRUE(slurp(e.path()) == slurp(dir / "world" / rel)) << rel << " differs";
      ++compared;
    }
    // 2 .vtr + .pvd + 3 probes + diagnostics.csv + summary.json
    EXPECT_EQ(compared, 8u);
  }
}

}  // namespace
