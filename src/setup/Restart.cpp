#include "setup/Restart.hpp"

#include <algorithm>
#include <filesystem>

#include "core/Error.hpp"
#include <map>
#include <sstream>

namespace gf {

const std::vector<std::string>& restart_changeable_keys() {
  static const std::vector<std::string> keys{
      "time.t_end",          "time.max_steps", "time.dt_mode",
      "time.dt",             "time.cfl",       "time.dt_max",
      "time.dt_min",         "time.max_speed", "output.progress_interval",
      "output.checkpoint_interval_steps",      "output.checkpoint_wall_s",
      "output.volume_warn_pct",                "solver.petsc_options",
      "rheology.fp_fail_change",              "rheology.fp_monitor"};
  return keys;
}

namespace {
// key -> value text of a resolved case: "section.key" for [section] tables, "probe[k].key"
// for the k-th [[probe]]; comments and blank lines skipped.
std::vector<std::pair<std::string, std::string>> resolved_entries(const std::string& toml) {
  std::vector<std::pair<std::string, std::string>> out;
  std::istringstream in(toml);
  std::string line, section;
  std::map<std::string, int> array_count;
  const auto trim = [](std::string x) {
    const auto a = x.find_first_not_of(" \t"), b = x.find_last_not_of(" \t\r");
    return a == std::string::npos ? std::string() : x.substr(a, b - a + 1);
  };
  while (std::getline(in, line)) {
    line = trim(line);
    if (line.empty() || line[0] == '#') continue;
    if (line.rfind("[[", 0) == 0) {
      const std::string name = trim(line.substr(2, line.find("]]") - 2));
      section = name + "[" + std::to_string(++array_count[name]) + "]";
      continue;
    }
    if (line[0] == '[') {
      section = trim(line.substr(1, line.find(']') - 1));
      continue;
    }
    const auto eq = line.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = trim(line.substr(0, eq));
    out.emplace_back(section.empty() ? key : section + "." + key, trim(line.substr(eq + 1)));
  }
  return out;
}
}  // namespace

std::vector<std::string> case_differences(const std::string& checkpoint_toml,
                                          const std::string& now_toml,
                                          const std::vector<std::string>& ignore) {
  const auto a = resolved_entries(checkpoint_toml), b = resolved_entries(now_toml);
  const auto skip = [&](const std::string& k) {
    return std::find(ignore.begin(), ignore.end(), k) != ignore.end();
  };
  const auto value = [](const auto& list, const std::string& k) -> const std::string* {
    for (const auto& [key, v] : list)
      if (key == k) return &v;
    return nullptr;
  };
  std::vector<std::string> diffs;
  for (const auto& [k, v] : a) {
    if (skip(k)) continue;
    const std::string* w = value(b, k);
    if (!w)
      diffs.push_back(k + ": " + v + " at the checkpoint, absent now");
    else if (*w != v)
      diffs.push_back(k + ": " + v + " at the checkpoint, " + *w + " now");
  }
  for (const auto& [k, v] : b)
    if (!skip(k) && !value(a, k)) diffs.push_back(k + ": absent at the checkpoint, " + v + " now");
  return diffs;
}

namespace {
// The keys of --set arguments ("key=value"); a malformed one is left to load_case to report.
std::vector<std::string> set_keys(const std::vector<std::string>& sets) {
  std::vector<std::string> keys;
  for (const auto& s : sets) {
    const auto eq = s.find('=');
    if (eq != std::string::npos) keys.push_back(s.substr(0, eq));
  }
  return keys;
}
}  // namespace

void check_restart_request(const std::string& dir, const std::vector<std::string>& sets) {
  // A restart may only change what does not alter the physics, the grid or the output
  // schedule of the files it continues.
  const auto& ok = restart_changeable_keys();
  std::string refused;
  for (const auto& k : set_keys(sets))
    if (std::find(ok.begin(), ok.end(), k) == ok.end()) refused += (refused.empty() ? "" : ", ") + k;
  if (!refused.empty()) {
    std::string allowed;
    for (const auto& k : ok) allowed += (allowed.empty() ? "" : ", ") + k;
    throw InputError("--restart " + dir + ": --set " + refused +
                     ": a restart continues the same physics on the same grid with the "
                     "same output schedule; it may only change " + allowed +
                     ". Start a new run (--out) to change anything else");
  }
  if (!std::filesystem::is_regular_file(dir + "/case.toml"))
    throw InputError("--restart " + dir + ": not a granflow output folder (no " + dir +
                     "/case.toml)");
}

void check_restart_case(const std::string& dir, const std::string& ckpt_dir,
                        const std::string& checkpoint_toml, const std::string& now_toml) {
  const auto diffs = case_differences(checkpoint_toml, now_toml, restart_changeable_keys());
  if (diffs.empty()) return;
  std::string m = "--restart " + dir + ": the case differs from the one the checkpoint (" +
                  ckpt_dir + ") was written with:";
  for (const auto& d : diffs) m += "\n  " + d;
  m += "\nA restart continues the same case; only " + std::string("time.*, output.checkpoint_*, "
       "output.progress_interval, output.volume_warn_pct and solver.petsc_options may change");
  throw InputError(m);
}

}  // namespace gf
