#include "setup/Restart.hpp"

#include <algorithm>
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

}  // namespace gf
