// Case files: the parameter registry and the cross-field checks (core/Params, setup/).
// Each malformed case must fail with a message that names the file, the key, the value and
// what is allowed; several problems must be reported at once; a resolved case must read back
// to the same configuration.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "setup/Case.hpp"
#include "setup/Report.hpp"
#include "setup/Restart.hpp"
#include "core/Error.hpp"

namespace fs = std::filesystem;
using gf::load_case;

namespace {

// A scratch folder per test process (ranks or parallel ctest runs must not collide),
// removed when the tests end.
const fs::path& scratch();

class RemoveScratch : public ::testing::Environment {
 public:
  void TearDown() override {
    std::error_code ec;
    fs::remove_all(scratch(), ec);
  }
};
[[maybe_unused]] ::testing::Environment* const kRemoveScratch =
    ::testing::AddGlobalTestEnvironment(new RemoveScratch);

const fs::path& scratch() {
  static const fs::path dir = [] {
    fs::path d = fs::temp_directory_path() / ("granflow_test_case_" + std::to_string(getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

std::string write_file(const std::string& name, const std::string& text) {
  const fs::path p = scratch() / name;
  std::ofstream(p) << text;
  return p.string();
}

// The message of the InputError thrown by load_case, or "" (and a test failure) if none.
std::string load_error(const std::string& path, const std::vector<std::string>& overrides = {}) {
  try {
    load_case(path, overrides);
  } catch (const gf::InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no InputError for " << path;
  return "";
}

struct BadCase {
  const char* name;
  std::string toml;
  std::vector<std::string> overrides;
  std::vector<std::string> expect;  // substrings of the error message
};

const char* kProbe = R"(
[[probe]]
name = "gate"
x0 = 0.2
y0 = 0.0
x1 = 0.2
y1 = 0.2
)";

std::vector<BadCase> bad_cases() {
  return {
      {"syntax", "[time]\nt_end = = 1\n", {}, {"syntax.toml:2:", "TOML syntax error"}},
      {"unknown_key",
       "[phase.granular]\nrhoo = 1550\n",
       {},
       {"unknown_key.toml:2: phase.granular.rhoo = 1550: unknown key; did you mean "
        "phase.granular.rho?"}},
      {"unknown_section_key",
       "[phase.granuler]\neta = 0.5\n",
       {},
       {"phase.granuler.eta = 0.5: unknown key; did you mean phase.granular.eta?"}},
      {"key_in_wrong_section",
       "[time]\nrho = 3\n",
       {},
       {"time.rho = 3: unknown key; did you mean phase.granular.rho or phase.air.rho?"}},
      {"section_as_value",
       "phase = 3\n",
       {},
       {"phase = 3: is a section of keys such as phase.granular.rho, not a value"}},
      {"wrong_type",
       "[time]\nt_end = \"long\"\n",
       {},
       {"time.t_end = \"long\": wrong type: expected a number (s), got a string"}},
      {"int_as_float",
       "[grid]\nn = 64.0\n",
       {},
       {"grid.n = 64.0: wrong type: expected an integer (cells), got a float"}},
      {"negative_density",
       "[phase.granular]\nrho = -5\n",
       {},
       {"negative_density.toml:2: phase.granular.rho = -5: must be > 0 (kg/m^3)"}},
      {"zero_viscosity",
       "[phase.air]\neta = 0.0\n",
       {},
       {"phase.air.eta = 0.0: must be > 0 (Pa s)"}},
      {"cfl_above_one", "[time]\ncfl = 1.5\n", {}, {"time.cfl = 1.5: must be in (0, 1]"}},
      {"grid_too_coarse", "[grid]\nn = 4\n", {}, {"grid.n = 4: must be in [8, 100000] (cells)"}},
      {"nx_below_8", "[grid]\nnx = 5\n", {}, {"grid.nx = 5: must be 0 or in [8, 100000] (cells)"}},
      {"bad_enum",
       "[boundary.left]\ntype = \"navir\"\n",
       {},
       {"boundary.left.type = \"navir\": must be one of free_slip, no_slip, navier; did you "
        "mean navier?"}},
      {"gravity_one_component",
       "[physics]\ngravity = [0.0]\n",
       {},
       {"physics.gravity = [0.0]: wrong type: expected an array of 2 numbers (m/s^2), got an "
        "array of 1 element"}},
      {"gravity_string_component",
       "[physics]\ngravity = [0.0, \"down\"]\n",
       {},
       {"physics.gravity = [0.0, \"down\"]: wrong type: expected an array of 2 numbers "
        "(m/s^2), but element 2 is a string"}},
      {"column_outside",
       "[initial]\nx1 = 0.9\n",
       {},
       {"initial.x1 = 0.9: the column must lie inside the domain: must be <= domain.Lx = "
        "0.8 m"}},
      {"column_touches_top",
       "[initial]\ny1 = 0.2\n",
       {},
       {"initial.y1 = 0.2: the column touches the top: must be <= Ly - (levelset.eps_cells + "
        "1) hy"}},
      {"column_inverted",
       "[initial]\nx0 = 0.3\n",
       {},
       {"initial.x1 = 0.2 (default): must be > initial.x0 = 0.3 m"}},
      {"dt_min_above_dt_max",
       "[time]\ndt_min = 0.01\n",
       {},
       {"time.dt_min = 0.01: must be < time.dt_max = 0.001 (s)"}},
      {"moving_free_slip_wall",
       "[boundary.top]\nvelocity = 1.0\n",
       {},
       {"boundary.top.velocity = 1: a free-slip wall cannot drive the flow"}},
      {"single_phase_with_shape",
       "[levelset]\nenabled = false\n",
       {},
       {"initial.shape = \"rectangle\" (default): levelset.enabled = false makes the whole "
        "domain granular",
        "must be \"none\""}},
      {"derived_nx_too_small",
       "[domain]\nLx = 0.01\n",
       {},
       {"grid.n = 64 (default): gives grid.nx = round(Lx/Ly * n) = 3, outside [8, 100000]"}},
      {"zalesak_slot_too_deep",
       "[domain]\nLx = 1.0\nLy = 1.0\n[initial]\nshape = \"zalesak\"\nslot_depth = 0.4\n"
       "[flow]\nprescribed = \"rotation\"\n",
       {},
       {"initial.slot_depth = 0.4: must be < 2 initial.radius = 0.3 m"}},
      {"rotation_leaves_domain",
       "[domain]\nLx = 1.0\nLy = 1.0\n[initial]\nshape = \"circle\"\ncx = 0.5\ncy = 0.85\n"
       "radius = 0.1\n[flow]\nprescribed = \"rotation\"\ncx = 0.5\ncy = 0.3\n",
       {},
       {"initial.shape = \"circle\": rotating about (flow.cx, flow.cy) = (0.5, 0.3) carries it "
        "out of the domain"}},
      {"probe_outside",
       "[[probe]]\nname = \"a\"\nx0 = 0.1\ny0 = 0.0\nx1 = 0.9\ny1 = 0.0\n",
       {},
       {"probe_outside.toml:5: probe[1].x1 = 0.9: the probe must lie inside the domain: must "
        "be in [0, domain.Lx = 0.8] (m)"}},
      {"probe_unknown_field",
       "[[probe]]\nname = \"a\"\nx0 = 0.1\ny0 = 0.0\nx1 = 0.5\ny1 = 0.0\n"
       "fields = [\"phi\", \"vel\"]\n",
       {},
       {"probe[1].fields = [\"phi\", \"vel\"]: \"vel\" is not allowed: each must be one of phi, "
        "rho, u, v, speed, p, eta, D_norm, S_norm, kappa; did you mean v?"}},
      {"probe_duplicate_name",
       "",
       {},  // filled below: two copies of kProbe
       {"probe[2].name = \"gate\": probe names must be unique: already used by probe[1]"}},
      {"probe_missing_key",
       "[[probe]]\nname = \"a\"\nx0 = 0.1\ny0 = 0.05\nx1 = 0.5\n",
       {},
       {"probe_missing_key.toml:1: probe[1].y1: missing: this key is required (m)"}},
      {"probe_bad_name",
       "[[probe]]\nname = \"a b\"\nx0 = 0.1\ny0 = 0.05\nx1 = 0.5\ny1 = 0.1\n",
       {},
       {"probe[1].name = \"a b\": must be made of letters, digits, _ and - only"}},
      {"probe_unknown_key",
       "[[probe]]\nname = \"a\"\nx0 = 0.1\ny0 = 0.05\nx1 = 0.5\ny1 = 0.1\npoint = 3\n",
       {},
       {"probe[1].point = 3: unknown key; did you mean probe[1].points?"}},
      {"probe_zero_length",
       "[[probe]]\nname = \"a\"\nx0 = 0.1\ny0 = 0.05\nx1 = 0.1\ny1 = 0.05\n",
       {},
       {"probe[1].x1 = 0.1: the segment has zero length"}},
      {"set_unknown_key",
       "",
       {"phase.granular.rhoo=3"},
       {"--set: phase.granular.rhoo = 3: unknown key; did you mean phase.granular.rho?"}},
      {"set_bad_value",
       "",
       {"grid.n=abc"},
       {"--set: grid.n = \"abc\": wrong type: expected an integer (cells), got a string"}},
      {"set_out_of_range", "", {"time.cfl=2"}, {"--set: time.cfl = 2: must be in (0, 1]"}},
      {"set_bad_enum",
       "",
       {"time.dt_mode=fixd"},
       {"--set: time.dt_mode = \"fixd\": must be one of adaptive, fixed; did you mean fixed?"}},
      {"set_no_equals", "", {"grid.n"}, {"--set grid.n: expected key=value"}},
      {"set_probe",
       "",
       {"probe[1].x0=0.1"},
       {"--set: probe[1].x0 = 0.1: [[probe]] entries can only be given in the case file"}},
      // Rheology.
      {"rheology_bad_enum",
       "[rheology]\nyield = \"drucker\"\n",
       {},
       {"rheology_bad_enum.toml:2: rheology.yield = \"drucker\": must be one of none, bingham, "
        "dp, hp"}},
      {"mu_i_without_d",
       "[rheology]\nyield = \"dp\"\nviscosity = \"mu_i\"\n",
       {},
       {"mu_i_without_d.toml: rheology.d = 0 (default): mu(I) without d: rheology.viscosity = "
        "\"mu_i\" needs the particle diameter (eq. 11): must be > 0 (m)"}},
      {"mu_inf_below_tan_alpha",
       "[rheology]\nyield = \"dp\"\nviscosity = \"mu_i\"\nd = 5e-4\nmu_inf = 0.4\n",
       {},
       {"mu_inf_below_tan_alpha.toml:5: rheology.mu_inf = 0.4: rheology.viscosity = \"mu_i\" "
        "needs mu_inf > tan(rheology.friction_angle) = tan(25.5 deg) = 0.477"}},
      {"mu_inf_below_tan_alpha_by_angle",
       "",
       {"rheology.yield=dp", "rheology.viscosity=mu_i", "rheology.d=5e-4",
        "rheology.friction_angle=40"},
       {"rheology.mu_inf = 0.73 (default): rheology.viscosity = \"mu_i\" needs mu_inf > "
        "tan(rheology.friction_angle) = tan(40 deg) = 0.8391"}},
      {"mu_i_needs_dp",
       "[rheology]\nyield = \"hp\"\nviscosity = \"mu_i\"\nd = 5e-4\n",
       {},
       {"mu_i_needs_dp.toml:3: rheology.viscosity = \"mu_i\": the mu(I) rheology is "
        "Drucker-Prager with the eq. 11 viscosity: needs rheology.yield = \"dp\", not \"hp\""}},
      {"bingham_without_tau_y",
       "[rheology]\nyield = \"bingham\"\n",
       {},
       {"bingham_without_tau_y.toml: rheology.tau_y = 0 (default): rheology.yield = "
        "\"bingham\" needs a yield stress: must be > 0 (Pa)"}},
      {"negative_tau_y",
       "[rheology]\ntau_y = -1.0\n",
       {},
       {"rheology.tau_y = -1.0: must be >= 0 (Pa)"}},
      {"friction_angle_90",
       "[rheology]\nfriction_angle = 90\n",
       {},
       {"rheology.friction_angle = 90: must be in (0, 90) (degrees)"}},
      {"wall_friction_angle_95",
       "[boundary.bottom]\nfriction_angle = 95\n",
       {},
       {"wall_friction_angle_95.toml:2: boundary.bottom.friction_angle = 95: must be in [0, 90) "
        "(degrees)"}},
      {"fp_max_iter_zero",
       "[rheology]\nfp_max_iter = 0\n",
       {},
       {"rheology.fp_max_iter = 0: must be in [1, 1000000]"}},
      {"dp_without_gravity",
       "[rheology]\nyield = \"dp\"\n[physics]\ngravity = [0.0, 0.0]\n",
       {},
       {"dp_without_gravity.toml:4: physics.gravity = [0, 0]: rheology.yield = \"dp\" scales the "
        "yield stress with the pressure of the grains' weight: needs non-zero gravity"}},
      {"hp_with_horizontal_gravity",
       "",
       {"rheology.yield=hp", "physics.gravity=[9.81, 0]"},
       {"--set: physics.gravity = [9.81, 0]: rheology.yield = \"hp\" weighs the granular "
        "column above the point (eq. 15): needs gravity pointing down, gy < 0"}},
      {"collapse_cutoff_out_of_range",
       "",
       {"collapse.cutoffs=[0.075, 1.5]"},
       {"--set: collapse.cutoffs = [0.075, 1.5]: each element must be in (0, 1)"}},
      {"collapse_cutoff_twice", "", {"collapse.cutoffs=[0.1, 0.1]"}, {"0.1 is listed twice"}},
      {"collapse_cutoff_empty", "", {"collapse.cutoffs=[]"}, {"must list at least one number"}},
      {"collapse_cutoff_not_a_number", "", {"collapse.cutoffs=[\"a\"]"}, {"collapse.cutoffs"}},
      {"collapse_slope_range_reversed",
       "",
       {"collapse.slope_back_range=[0.3, 0.1]"},
       {"collapse.slope_back_range = [0.3, 0.1]: must be [lo, hi] with lo < hi (m)"}},
      {"mu_i_eta_bounds",
       "",
       {"rheology.yield=dp", "rheology.viscosity=mu_i", "rheology.d=5e-4", "rheology.eta_min=2"},
       {"--set: rheology.eta_min = 2: must be < rheology.eta_max = 1.2 (Pa s)"}},
      // Issue 20's holes, at the level of the case.
      {"quoted_root_key_beside_its_section",
       "\"grid.n\" = 32\n[grid]\nn = 16\n",
       {},
       {": given twice (also at", "a quoted key \"grid.n\" is the same parameter as n"}},
      {"number_out_of_range_by_set", "", {"domain.Lx=1e999"},
       {"--set: domain.Lx = 1e999: out of range: not representable as a double"}},
      {"escape_in_title", "title = \"a\\u001b[31mred\"\n", {},
       {"title = \"a\\u001B[31mred\"", "control character 0x1B (ESC)"}},
      {"carriage_return_in_title", "title = \"a\\rb\"\n", {}, {"control character 0x0D (CR)"}},
      {"probe_name_too_long",
       "[[probe]]\nname = \"" + std::string(300, 'p') +
           "\"\nx0 = 0\ny0 = 0.01\nx1 = 0.8\ny1 = 0.01\n",
       {},
       {"is 300 characters long: at most 64"}},
      {"fixed_step_of_zero", "", {"time.dt_mode=fixed", "time.dt=0"},
       {"time.dt = 0: time.dt_mode = \"fixed\" needs the step: must be > 0 (s)"}},
      {"fixed_step_far_beyond_stability", "", {"time.dt_mode=fixed", "time.dt=0.5"},
       {"time.dt = 0.5: with time.dt_mode = \"fixed\" the step is", "times the stability limit",
        "CFL number U dt / h ="}},
      {"output_interval_absurd", "", {"output.interval=1e-300"},
       {"output.interval = 1e-300 with", "diagnostics outputs, more than 1e+07"}},
      {"vtk_interval_absurd", "", {"output.vtk_interval=1e-300"},
       {"output.vtk_interval = 1e-300 with", "VTK files, more than 1e+05"}},
      {"t_end_absurd", "", {"time.t_end=1e308"},
       {"time.t_end = 1e+308: time.t_end / time.dt_max", "steps at least", "more than 1e+09"}},
  };
}

}  // namespace

TEST(CaseFile, MalformedCasesReportTheirSpecificError) {
  const auto cases = bad_cases();
  ASSERT_GE(cases.size(), 20u);
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    std::string text = c.toml;
    if (std::string(c.name) == "probe_duplicate_name") text = std::string(kProbe) + kProbe;
    const std::string path = write_file(std::string(c.name) + ".toml", text);
    const std::string msg = load_error(path, c.overrides);
    for (const auto& e : c.expect) EXPECT_NE(msg.find(e), std::string::npos) << "got:\n" << msg;
  }
}

TEST(CaseFile, MissingFileIsReportedWithItsName) {
  const std::string path = (scratch() / "no_such_case.toml").string();
  const std::string msg = load_error(path);
  EXPECT_NE(msg.find(path + ": cannot open the case file"), std::string::npos) << msg;
}

TEST(CaseFile, AFolderIsNotAnEmptyCase) {
  const fs::path dir = scratch() / "a_folder.toml";
  fs::create_directories(dir);
  const std::string msg = load_error(dir.string());
  EXPECT_NE(msg.find(dir.string() + ": is a folder, not a case file"), std::string::npos) << msg;
}

TEST(CaseFile, FixedStepBeyondStabilityIsWarned) {
  // Case A's defaults at n = 64: U = sqrt(9.81 x 0.14) = 1.17 m/s, h = 3.125 mm: CFL 3.75.
  const auto c = load_case(write_file("fixed_dt.toml", ""), {"time.dt_mode=fixed", "time.dt=0.01"});
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_NE(c.warnings[0].find("beyond the stability limit 0.002667 s: CFL number U dt / h = 3.75"),
            std::string::npos)
      << c.warnings[0];
}

TEST(CaseFile, MissingFileStillChecksOverrides) {
  const std::string msg =
      load_error((scratch() / "absent.toml").string(), {"grid.n=2", "time.cfll=0.3"});
  EXPECT_NE(msg.find("cannot open the case file"), std::string::npos) << msg;
  EXPECT_NE(msg.find("--set: grid.n = 2: must be in [8, 100000] (cells)"), std::string::npos);
  EXPECT_NE(msg.find("--set: time.cfll = 0.3: unknown key; did you mean time.cfl?"),
            std::string::npos);
}

TEST(CaseFile, SeveralErrorsAreReportedAtOnceInFileOrder) {
  const std::string path = write_file("many.toml", R"([time]
cfl = 2.0
[phase.granular]
rho = -5
rhoo = 3
[initial]
x1 = 0.9
[[probe]]
name = "p"
x0 = 0.1
y0 = 0.0
x1 = 0.1
y1 = 0.5
fields = ["rho", "rho"]
)");
  const std::string msg = load_error(path, {"time.dt_mode=fixd"});
  std::vector<std::string> lines;
  std::istringstream is(msg);
  for (std::string l; std::getline(is, l);) lines.push_back(l);
  ASSERT_EQ(lines.size(), 7u) << msg;
  EXPECT_NE(lines[0].find("many.toml:2: time.cfl = 2.0: must be in (0, 1]"), std::string::npos);
  EXPECT_NE(lines[1].find("many.toml:4: phase.granular.rho = -5: must be > 0 (kg/m^3)"),
            std::string::npos);
  EXPECT_NE(lines[2].find("many.toml:5: phase.granular.rhoo = 3: unknown key"), std::string::npos);
  EXPECT_NE(lines[3].find("many.toml:14: probe[1].fields = [\"rho\", \"rho\"]: \"rho\" is listed "
                          "twice"),
            std::string::npos);
  EXPECT_NE(lines[4].find("--set: time.dt_mode = \"fixd\": must be one of"), std::string::npos);
  // Cross-field errors come last; the rejected density does not cause follow-up errors.
  EXPECT_NE(lines[5].find("many.toml:7: initial.x1 = 0.9: the column must lie inside"),
            std::string::npos);
  EXPECT_NE(lines[6].find("many.toml:13: probe[1].y1 = 0.5: the probe must lie inside the "
                          "domain: must be in [0, domain.Ly = 0.2] (m)"),
            std::string::npos);
}

TEST(CaseFile, DefaultsGiveThePapersCaseA) {
  const auto c = load_case(write_file("empty.toml", ""), {});
  EXPECT_EQ(c.nx, 256);
  EXPECT_EQ(c.ny, 64);
  EXPECT_DOUBLE_EQ(c.hx, 0.8 / 256);
  EXPECT_DOUBLE_EQ(c.hy, 0.2 / 64);
  EXPECT_EQ(c.initial.shape, gf::CaseConfig::Shape::Rectangle);
  EXPECT_DOUBLE_EQ(c.initial.y1, 0.14);
  EXPECT_DOUBLE_EQ(c.granular.rho, 1550);
  EXPECT_DOUBLE_EQ(c.gravity[1], -9.81);
  EXPECT_EQ(c.walls[gf::CaseConfig::kLeft].type, gf::CaseConfig::Wall::Navier);
  EXPECT_EQ(c.walls[gf::CaseConfig::kBottom].type, gf::CaseConfig::Wall::Navier);
  EXPECT_EQ(c.walls[gf::CaseConfig::kRight].type, gf::CaseConfig::Wall::FreeSlip);
  EXPECT_EQ(c.walls[gf::CaseConfig::kTop].type, gf::CaseConfig::Wall::FreeSlip);
  EXPECT_DOUBLE_EQ(c.walls[gf::CaseConfig::kLeft].eta_b, 1.0);
  EXPECT_TRUE(c.probes.empty());
  EXPECT_TRUE(c.warnings.empty());
}

TEST(CaseFile, RheologyDefaultsAreNewtonianWithThePapersConstants) {
  const auto c = load_case(write_file("rheo_empty.toml", ""), {});
  const auto& rh = c.rheology;
  EXPECT_EQ(rh.yield, gf::CaseConfig::Yield::None);
  EXPECT_EQ(rh.viscosity, gf::CaseConfig::Viscosity::Constant);
  EXPECT_DOUBLE_EQ(rh.tau_y, 0);
  EXPECT_DOUBLE_EQ(rh.friction_angle_deg, 25.5);
  EXPECT_NEAR(rh.tan_alpha(), 0.47698, 1e-5);
  EXPECT_DOUBLE_EQ(rh.mu_inf, 0.73);
  EXPECT_DOUBLE_EQ(rh.I0, 0.279);
  EXPECT_DOUBLE_EQ(rh.d, 0);
  EXPECT_DOUBLE_EQ(rh.eta_min, 1e-3);
  EXPECT_DOUBLE_EQ(rh.eta_max, 1.2);
  EXPECT_DOUBLE_EQ(rh.r_factor, 0.5);
  EXPECT_DOUBLE_EQ(rh.theta_per_dt, 10);
  EXPECT_DOUBLE_EQ(rh.fp_tol, 1e-4);
  EXPECT_EQ(rh.fp_max_iter, 50);
  for (const auto& w : c.walls) {
    EXPECT_DOUBLE_EQ(w.friction_angle_deg, 0);
    EXPECT_DOUBLE_EQ(w.tan_friction(), 0);
  }
  EXPECT_STREQ(gf::to_string(gf::CaseConfig::Yield::DruckerPrager), "dp");
  EXPECT_STREQ(gf::to_string(gf::CaseConfig::Yield::Hydrostatic), "hp");
  EXPECT_STREQ(gf::to_string(gf::CaseConfig::Viscosity::MuI), "mu_i");
  const std::string d = gf::describe_case(c, 1);
  EXPECT_NE(d.find("Newtonian granular phase (rheology.yield = none)"), std::string::npos) << d;
  EXPECT_NE(d.find("Coulomb friction where the granular phase touches: none"), std::string::npos)
      << d;
  EXPECT_EQ(d.find("Bingham number"), std::string::npos) << d;
}

TEST(CaseFile, WallFrictionOnANewtonianPhaseIsLegalButWarned) {
  const auto c =
      load_case(write_file("rheo_wall.toml", "[boundary.bottom]\nfriction_angle = 20\n"), {});
  EXPECT_DOUBLE_EQ(c.walls[gf::CaseConfig::kBottom].friction_angle_deg, 20);
  EXPECT_NEAR(c.walls[gf::CaseConfig::kBottom].tan_friction(),
              std::tan(20 * std::numbers::pi / 180), 1e-15);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0],
            "boundary.bottom.friction_angle = 20 with rheology.yield = none: Coulomb wall "
            "friction on a Newtonian granular phase (legal, but unusual)");
  // With a yield stress it is the paper's setting: no warning.
  EXPECT_TRUE(load_case(write_file("rheo_wall_dp.toml",
                                   "[rheology]\nyield = \"dp\"\n[boundary.bottom]\n"
                                   "friction_angle = 20\n"),
                        {})
                  .warnings.empty());
}

TEST(CaseFile, RheologyKeysOfAnotherModelGiveWarnings) {
  const auto c = load_case(write_file("rheo_unused.toml",
                                      "[rheology]\nyield = \"bingham\"\ntau_y = 20\n"
                                      "friction_angle = 30\nd = 1e-3\n"),
                           {});
  ASSERT_EQ(c.warnings.size(), 2u);
  EXPECT_EQ(c.warnings[0],
            "rheology.friction_angle is set but rheology.yield = bingham does not use it");
  EXPECT_EQ(c.warnings[1], "rheology.d is set but rheology.viscosity = constant does not use it");
}

TEST(CaseFile, MuIRheologyRoundTripsAndIsDescribed) {
  const std::string path = write_file("rheo_mu_i.toml", R"(
[rheology]
yield = "dp"
friction_angle = 22.5
viscosity = "mu_i"
mu_inf = 0.65
I0 = 0.3
d = 7e-4
eta_min = 0.002
eta_max = 2.5
r_factor = 0.5
theta_per_dt = 20
fp_tol = 1e-8
fp_max_iter = 80
[boundary.bottom]
friction_angle = 18.5
[boundary.left]
friction_angle = 10
)");
  const auto a = load_case(path, {"time.dt=5e-4"});
  const auto& rh = a.rheology;
  EXPECT_EQ(rh.yield, gf::CaseConfig::Yield::DruckerPrager);
  EXPECT_EQ(rh.viscosity, gf::CaseConfig::Viscosity::MuI);
  EXPECT_DOUBLE_EQ(rh.friction_angle_deg, 22.5);
  EXPECT_DOUBLE_EQ(rh.mu_inf, 0.65);
  EXPECT_DOUBLE_EQ(rh.I0, 0.3);
  EXPECT_DOUBLE_EQ(rh.d, 7e-4);
  EXPECT_DOUBLE_EQ(rh.eta_min, 0.002);
  EXPECT_DOUBLE_EQ(rh.eta_max, 2.5);
  EXPECT_DOUBLE_EQ(rh.r_factor, 0.5);
  EXPECT_DOUBLE_EQ(rh.theta_per_dt, 20);
  EXPECT_DOUBLE_EQ(rh.fp_tol, 1e-8);
  EXPECT_EQ(rh.fp_max_iter, 80);
  EXPECT_DOUBLE_EQ(a.walls[gf::CaseConfig::kBottom].friction_angle_deg, 18.5);
  EXPECT_DOUBLE_EQ(a.walls[gf::CaseConfig::kLeft].friction_angle_deg, 10);
  EXPECT_DOUBLE_EQ(a.walls[gf::CaseConfig::kRight].friction_angle_deg, 0);
  EXPECT_TRUE(a.warnings.empty());

  const std::string resolved = (scratch() / "rheo_resolved.toml").string();
  ASSERT_EQ(gf::write_resolved_case(a, resolved), "");
  const auto b = load_case(resolved, {});
  EXPECT_TRUE(a == b);
  EXPECT_EQ(a.resolved_toml, b.resolved_toml);
  EXPECT_NE(a.resolved_toml.find("[rheology]\n"), std::string::npos);
  EXPECT_NE(a.resolved_toml.find("\nyield = \"dp\"\n"), std::string::npos);
  EXPECT_NE(a.resolved_toml.find("\nfp_max_iter = 80\n"), std::string::npos);
  EXPECT_NE(a.resolved_toml.find("\nfriction_angle = 18.5\n"), std::string::npos);
  EXPECT_NE(a.resolved_toml.find("# unit: degrees | allowed: in [0, 90) | default: 0"),
            std::string::npos);
  // operator== sees every new member.
  auto c = b;
  c.rheology.fp_tol = 1e-7;
  EXPECT_FALSE(a == c);
  c = b;
  c.walls[gf::CaseConfig::kTop].friction_angle_deg = 1;
  EXPECT_FALSE(a == c);

  const std::string d = gf::describe_case(a, 1);
  EXPECT_NE(d.find("Drucker-Prager (dp): kappa = tan(alpha) p^+ (eq. 19), alpha = 22.5 deg, "
                   "tan alpha = 0.4142"),
            std::string::npos)
      << d;
  EXPECT_NE(d.find("viscosity mu(I) (eq. 11): mu_inf = 0.65"), std::string::npos) << d;
  // theta = 20 /s x 5e-4 s = 0.01.
  EXPECT_NE(d.find("theta = theta_per_dt x first dt = 20 /s x 0.0005 s = 0.01"), std::string::npos)
      << d;
  EXPECT_NE(d.find("left 10 deg (tan 0.1763), bottom 18.5 deg (tan 0.3346)"), std::string::npos)
      << d;
  // rho_s |g| H = 1550 x 9.81 x 0.14 = 2129 Pa.
  EXPECT_NE(d.find("pressure scale rho_s |g| H = 2129 Pa"), std::string::npos) << d;
  EXPECT_NE(d.find("Bingham number Bi = kappa H / (eta(I) U)"), std::string::npos) << d;
}

TEST(CaseFile, BinghamIsDescribedWithItsBinghamNumber) {
  const auto c = load_case(
      write_file("rheo_bingham.toml", "[rheology]\nyield = \"bingham\"\ntau_y = 50\n"), {});
  EXPECT_EQ(c.rheology.yield, gf::CaseConfig::Yield::Bingham);
  const std::string d = gf::describe_case(c, 1);
  EXPECT_NE(d.find("Bingham (bingham): kappa = tau_y = 50 Pa"), std::string::npos) << d;
  // Bi = tau_y H / (eta U) = 50 x 0.14 / (0.5 x sqrt(9.81 x 0.14)) = 11.95.
  EXPECT_NE(d.find("Bingham number Bi = kappa H / (eta_gran U) = 11.95"), std::string::npos) << d;
  EXPECT_EQ(d.find("pressure scale"), std::string::npos) << d;
}

TEST(CaseFile, ProbesMaySampleThePlasticFields) {
  const auto c = load_case(write_file("probe_plastic.toml",
                                      "[[probe]]\nname = \"z\"\nx0 = 0.1\ny0 = 0.0\n"
                                      "x1 = 0.1\ny1 = 0.2\n"
                                      "fields = [\"u\", \"D_norm\", \"S_norm\", \"kappa\"]\n"),
                           {});
  using F = gf::CaseConfig::ProbeField;
  ASSERT_EQ(c.probes.size(), 1u);
  EXPECT_EQ(c.probes[0].fields, (std::vector<F>{F::U, F::DNorm, F::SNorm, F::Kappa}));
  EXPECT_STREQ(gf::to_string(F::DNorm), "D_norm");
  EXPECT_STREQ(gf::to_string(F::SNorm), "S_norm");
  EXPECT_STREQ(gf::to_string(F::Kappa), "kappa");
  EXPECT_STREQ(gf::to_string(F::Eta), "eta");  // the existing names keep their enumerators
}

TEST(CaseFile, SetGridNChangesTheDerivedNx) {
  const std::string path = write_file("grid.toml", "[grid]\nn = 64\n");
  const auto c64 = load_case(path, {});
  EXPECT_EQ(c64.nx, 256);
  const auto c128 = load_case(path, {"grid.n=128"});
  EXPECT_EQ(c128.ny, 128);
  EXPECT_EQ(c128.nx, 512);
  EXPECT_DOUBLE_EQ(c128.hx, 0.8 / 512);
  EXPECT_NE(c128.resolved_toml.find("resolved: nx = round(Lx/Ly * n) = 512"), std::string::npos);
  // An explicit nx is kept.
  EXPECT_EQ(load_case(path, {"grid.nx=100"}).nx, 100);
}

TEST(CaseFile, OverridesReplaceFileValuesAndTakeBareStrings) {
  const std::string path = write_file("ovr.toml", "title = \"x\"\n[phase.granular]\nrho = -5\n");
  // The override replaces the bad file value, so the file's -5 is never validated.
  const auto c = load_case(
      path, {"phase.granular.rho=2000", "initial.shape=layer", "title=a bare title",
             "physics.gravity=[1, -9]", "levelset.enabled=true", "time.dt_mode=\"fixed\"",
             "time.dt=1e-4"});  // a fixed step needs its dt (> 0)
  EXPECT_DOUBLE_EQ(c.granular.rho, 2000);
  EXPECT_EQ(c.initial.shape, gf::CaseConfig::Shape::Layer);
  EXPECT_EQ(c.title, "a bare title");
  EXPECT_EQ(c.gravity, (std::array<double, 2>{1.0, -9.0}));
  EXPECT_EQ(c.time.dt_mode, gf::CaseConfig::DtMode::Fixed);
  // A later --set of the same key wins.
  EXPECT_EQ(load_case(path, {"phase.granular.rho=1", "phase.granular.rho=3"}).granular.rho, 3);
}

TEST(CaseFile, CollapseCutoffsAreAListOfNumbers) {
  const std::string path = write_file("cut.toml", "[collapse]\ncutoffs = [0.1, 0.01, 1e-3]\n");
  const auto c = load_case(path, {});
  EXPECT_EQ(c.collapse.cutoffs, (std::vector<double>{0.1, 0.01, 1e-3}));
  // Integers are numbers too, and --set replaces the whole list.
  EXPECT_EQ(load_case(path, {"collapse.cutoffs=[0.5]"}).collapse.cutoffs, std::vector<double>{0.5});
  EXPECT_NE(c.resolved_toml.find("cutoffs = [0.1, 0.01, 0.001]"), std::string::npos)
      << c.resolved_toml;
  // The defaults are the paper's 7.5 % and 0.75 % (section 4.2.5).
  EXPECT_EQ(load_case(write_file("nocut.toml", ""), {}).collapse.cutoffs,
            (std::vector<double>{0.075, 0.0075}));
}

TEST(CaseFile, ResolvedCaseRoundTrips) {
  const std::string path = write_file("good.toml", R"(
title = "round trip: \"quotes\" and \\ backslash"
[domain]
Lx = 1.38
Ly = 0.46
[grid]
n = 48
[time]
t_end = 0.3
dt_mode = "fixed"
dt = 5e-5
[physics]
gravity = [0.1, -9.81]
[phase.granular]
rho = 1450
eta = 0.1
[initial]
x1 = 0.2
y1 = 0.4
[boundary.bottom]
type = "navier"
eta_b = 0.3
[boundary.top]
type = "no_slip"
velocity = 0.25
[solver]
petsc_options = "-pres_pc_type gamg -pres_ksp_monitor"
[[probe]]
name = "gate"
x0 = 0.2
y0 = 0.0
x1 = 0.2
y1 = 0.46
points = 50
fields = ["phi", "speed", "eta"]
[[probe]]
name = "bottom-line_2"
x0 = 0.0
y0 = 0.01
x1 = 1.38
y1 = 0.01
)");
  const auto a = load_case(path, {"levelset.eps_cells=2", "output.interval=0.003"});
  ASSERT_EQ(a.probes.size(), 2u);
  EXPECT_EQ(a.probes[0].fields,
            (std::vector<gf::CaseConfig::ProbeField>{gf::CaseConfig::ProbeField::Phi,
                                                     gf::CaseConfig::ProbeField::Speed,
                                                     gf::CaseConfig::ProbeField::Eta}));
  EXPECT_EQ(a.probes[1].points, 101);
  EXPECT_EQ(a.nx, 144);

  const std::string resolved = (scratch() / "resolved.toml").string();
  ASSERT_EQ(gf::write_resolved_case(a, resolved), "");
  const auto b = load_case(resolved, {});
  EXPECT_TRUE(a == b);
  EXPECT_EQ(a.title, b.title);
  EXPECT_EQ(a.resolved_toml, b.resolved_toml);  // resolving is a fixed point
  // Units and help are in the comments.
  EXPECT_NE(a.resolved_toml.find("# unit: kg/m^3 | allowed: > 0 | default: 1550"),
            std::string::npos);
  EXPECT_NE(a.resolved_toml.find("[[probe]]"), std::string::npos);
}

TEST(CaseFile, ResolvedCaseListsEveryDeclaredKey) {
  const auto c = load_case(write_file("empty2.toml", ""), {});
  const gf::Params schema = gf::case_params();
  for (const auto& s : schema.specs()) {
    const auto dot = s.key.rfind('.');
    const std::string leaf = dot == std::string::npos ? s.key : s.key.substr(dot + 1);
    EXPECT_NE(c.resolved_toml.find("\n" + leaf + " = "), std::string::npos) << s.key;
  }
  // No probes: the item keys are still documented.
  EXPECT_NE(c.resolved_toml.find("#   fields: Fields sampled: phi,"), std::string::npos);
}

TEST(CaseFile, HelpListsEveryKeyWithUnitDefaultAndRange) {
  std::ostringstream os;
  gf::print_case_help(os);
  const std::string help = os.str();
  const gf::Params schema = gf::case_params();  // (a temporary would die before the loop)
  for (const auto& s : schema.specs())
    EXPECT_NE(help.find(s.key + "  ("), std::string::npos) << s.key;
  EXPECT_NE(help.find("phase.granular.rho  (real, kg/m^3)  default: 1550; allowed: > 0"),
            std::string::npos)
      << help;
  EXPECT_NE(help.find("probe[].fields  (string[])"), std::string::npos);
  EXPECT_NE(help.find("time.dt_mode  (enum)  default: \"adaptive\"; allowed: one of adaptive, "
                      "fixed"),
            std::string::npos);
}

TEST(CaseFile, DescribeReportsGridStepAndEstimates) {
  const auto c = load_case(write_file("desc.toml", ""), {});
  const std::string d = gf::describe_case(c, 2);
  EXPECT_NE(d.find("256 x 64 = 16384 cells"), std::string::npos) << d;
  EXPECT_NE(d.find("h = 0.003125 m"), std::string::npos) << d;
  // U = sqrt(9.81 * 0.14) = 1.172 m/s; cfl h / U = 1.333e-3 s > dt_max = 1e-3 s.
  EXPECT_NE(d.find("U = 1.172 m/s"), std::string::npos) << d;
  EXPECT_NE(d.find("first dt = 0.001 s"), std::string::npos) << d;
  EXPECT_NE(d.find("capped by time.dt_max"), std::string::npos) << d;
  EXPECT_NE(d.find("density ratio rho_gran/rho_air = 1292"), std::string::npos) << d;
  EXPECT_NE(d.find("Re = rho_gran U H / eta_gran = 508.6"), std::string::npos) << d;
  // 1000 steps x 16384 cells x 1.5e-6 s / 2 ranks = 12.29 s.
  EXPECT_NE(d.find("1000 steps"), std::string::npos) << d;
  EXPECT_NE(d.find("about 12.29 s"), std::string::npos) << d;
  EXPECT_NE(d.find("estimate"), std::string::npos) << d;
  EXPECT_DOUBLE_EQ(gf::initial_dt(c), 1e-3);
}

TEST(CaseFile, LidDrivenCavityIsSinglePhaseWithCavityReynolds) {
  const auto c = load_case(write_file("cavity.toml", R"(
[domain]
Lx = 1.0
Ly = 1.0
[grid]
n = 32
[levelset]
enabled = false
[initial]
shape = "none"
[physics]
gravity = [0.0, 0.0]
[phase.granular]
rho = 1.0
eta = 0.01
[boundary.top]
type = "no_slip"
velocity = 1.0
)"),
                           {});
  EXPECT_EQ(c.nx, 32);
  const std::string d = gf::describe_case(c, 1);
  EXPECT_NE(d.find("single phase"), std::string::npos) << d;
  EXPECT_NE(d.find("cavity Re = rho U L / eta = 100 (top wall"), std::string::npos) << d;
  EXPECT_NE(d.find("U = 1 m/s"), std::string::npos) << d;
  // 0.5 * (1/32) / 1 = 0.015625 s, capped by dt_max = 1e-3.
  EXPECT_DOUBLE_EQ(gf::initial_dt(c), 1e-3);
}

TEST(CaseFile, UnusedShapeKeysGiveWarnings) {
  const auto c = load_case(write_file("warn.toml", "[initial]\nradius = 0.05\n"), {});
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0], "initial.radius is set but initial.shape = rectangle does not use it");
}

TEST(CaseFile, ZalesakRotationIsAccepted) {
  const auto c = load_case(write_file("zalesak.toml", R"(
[domain]
Lx = 1.0
Ly = 1.0
[grid]
n = 100
[time]
t_end = 6.283185307179586
[initial]
shape = "zalesak"
[flow]
prescribed = "rotation"
omega = 1.0
)"),
                           {});
  EXPECT_EQ(c.flow.prescribed, gf::CaseConfig::Prescribed::Rotation);
  EXPECT_DOUBLE_EQ(c.initial.cy, 0.75);
  // U = omega * distance to the farthest corner = sqrt(0.5) m/s.
  EXPECT_NEAR(gf::velocity_scale(c), std::sqrt(0.5), 1e-12);
}

TEST(Params, EditDistanceAndSuggestions) {
  EXPECT_EQ(gf::edit_distance("rhoo", "rho"), 1u);
  EXPECT_EQ(gf::edit_distance("eat", "eta"), 1u);  // a transposition costs 1
  EXPECT_EQ(gf::closest_match("phase.granular.rhoo", {"phase.granular.rho", "phase.air.rho"}),
            "phase.granular.rho");
  EXPECT_EQ(gf::closest_match("completely_else", {"time.t_end"}), "");
}

TEST(Params, RangeDescriptions) {
  EXPECT_EQ(gf::Range::gt(0).describe(), "> 0");
  EXPECT_EQ(gf::Range::ge(8).or_zero().describe(), "0 or >= 8");
  EXPECT_EQ(gf::Range::open_closed(0, 1).describe(), "in (0, 1]");
  EXPECT_TRUE(gf::Range::ge(8).or_zero().contains(0));
  EXPECT_FALSE(gf::Range::ge(8).or_zero().contains(3));
  EXPECT_FALSE(gf::Range::open_closed(0, 1).contains(0));
  EXPECT_TRUE(gf::Range::open_closed(0, 1).contains(1));
}

TEST(Params, DeclaringAKeyTwiceOrABadDefaultIsABug) {
  gf::Params p;
  p.add_real("a.b", "m", 1.0, gf::Range::gt(0), "x");
  EXPECT_THROW(p.add_real("a.b", "m", 1.0, gf::Range::gt(0), "x"), std::logic_error);
  EXPECT_THROW(p.add_real("a.c", "m", -1.0, gf::Range::gt(0), "x"), std::logic_error);
  EXPECT_THROW(p.add_enum("a.d", "z", {"x", "y"}, "x"), std::logic_error);
  EXPECT_THROW(p.get_int("a.b"), std::logic_error);
  EXPECT_THROW(p.get_real("nope"), std::logic_error);
}

TEST(CaseFile, PeriodicXHasNoSideWalls) {
  // A speed or a friction on a wall that does not exist is an error; its type only a warning.
  const std::string e = load_error(write_file("periodic_bad.toml", R"(
[boundary]
periodic_x = true
[boundary.left]
type = "no_slip"
velocity = 0.5
[boundary.right]
friction_angle = 20
)"));
  EXPECT_NE(e.find("boundary.left.velocity = 0.5: boundary.periodic_x = true: there is no left "
                   "wall to move: must be 0"),
            std::string::npos)
      << e;
  EXPECT_NE(e.find("boundary.right.friction_angle = 20: boundary.periodic_x = true: there is no "
                   "right wall to rub on: must be 0"),
            std::string::npos)
      << e;
  const auto c = load_case(write_file("periodic.toml", R"(
[boundary]
periodic_x = true
[boundary.left]
type = "no_slip"
[initial]
shape = "layer"
height = 0.05
)"),
                           {});
  EXPECT_TRUE(c.periodic_x);
  ASSERT_EQ(c.warnings.size(), 1u);
  EXPECT_EQ(c.warnings[0],
            "boundary.left.type is set but boundary.periodic_x = true: there is no left wall, "
            "ignored");
  const std::string d = gf::describe_case(c, 1);
  EXPECT_NE(d.find("walls      bottom navier, top free_slip; periodic in x"), std::string::npos)
      << d;
  const std::string resolved = (scratch() / "periodic_resolved.toml").string();
  ASSERT_EQ(gf::write_resolved_case(c, resolved), "");
  EXPECT_TRUE(load_case(resolved, {}) == c);
  EXPECT_FALSE(load_case(write_file("walls.toml", "[initial]\nshape = \"layer\"\n"), {}).periodic_x);
}

TEST(CaseFile, InitialVortexVelocity) {
  EXPECT_NE(load_error(write_file("vortex0.toml", "[initial]\nvelocity = \"vortex\"\n"))
                .find("initial.velocity_amplitude = 0 (default): initial.velocity = \"vortex\" "
                      "needs an amplitude: must be non-zero (m/s)"),
            std::string::npos);
  const auto w = load_case(write_file("amp.toml", "[initial]\nvelocity_amplitude = 2\n"), {});
  ASSERT_EQ(w.warnings.size(), 1u);
  EXPECT_EQ(w.warnings[0],
            "initial.velocity_amplitude is set but initial.velocity = none does not use it");
  // The bundled cessation case: valid, silent, and its velocity scale is the vortex's.
  const auto c = load_case(std::string(GRANFLOW_SOURCE_DIR) + "/cases/verify/bingham_cessation.toml", {});
  EXPECT_TRUE(c.warnings.empty());
  EXPECT_EQ(c.initial.velocity, gf::CaseConfig::InitialVelocity::Vortex);
  EXPECT_STREQ(gf::to_string(c.initial.velocity), "vortex");
  EXPECT_DOUBLE_EQ(gf::velocity_scale(c), c.initial.velocity_amplitude);
}

// A restart compares the resolved case it is given with the one its checkpoint was written
// with: the changeable keys are skipped, every other difference is named (tables and probes).
TEST(CaseFile, RestartDifferencesNameTheKeys) {
  const std::string probe = "[[probe]]\nname = \"a\"\nx0 = 0.0\ny0 = 0.01\nx1 = 0.8\ny1 = 0.01\n";
  const auto a = load_case(write_file("ra.toml", probe), {});
  const auto b = load_case(write_file("rb.toml", probe),
                           {"time.t_end=2", "time.cfl=0.3", "grid.n=32"});
  const auto& keep = gf::restart_changeable_keys();
  EXPECT_TRUE(gf::case_differences(a.resolved_toml, a.resolved_toml, keep).empty());
  auto d = gf::case_differences(a.resolved_toml, b.resolved_toml, keep);
  ASSERT_EQ(d.size(), 1u) << (d.empty() ? "" : d[0]);
  EXPECT_EQ(d[0], "grid.n: 64 at the checkpoint, 32 now");
  // Without the changeable keys skipped, t_end and cfl are differences too.
  EXPECT_EQ(gf::case_differences(a.resolved_toml, b.resolved_toml, {}).size(), 3u);
  const auto c = load_case(write_file("rc.toml", probe + "points = 11\n"), {});
  d = gf::case_differences(a.resolved_toml, c.resolved_toml, keep);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0], "probe[1].points: 101 at the checkpoint, 11 now");
  const auto none = load_case(write_file("rn.toml", ""), {});
  d = gf::case_differences(a.resolved_toml, none.resolved_toml, keep);
  ASSERT_FALSE(d.empty());
  EXPECT_NE(d[0].find("probe[1]."), std::string::npos);
  EXPECT_NE(d[0].find("absent now"), std::string::npos);
}
