#pragma once
// The typed parameter registry behind case files.
//
// Every parameter is declared ONCE (setup/Schema.cpp: case_params()) with its dotted key, type,
// SI unit, default, allowed range and help text. From that single declaration the registry
//   * loads a TOML file and `--set key=value` overrides (the override wins),
//   * validates every value and collects ALL problems before reporting them, each naming the
//     file (and line), the key, the value and what is allowed, e.g.
//       case.toml:7: phase.granular.rho = -5: must be > 0 (kg/m^3)
//   * rejects unknown keys, suggesting the closest declared key,
//   * writes the fully resolved case back as TOML (units and help as comments), and
//   * prints the help listing of `granflow check --list`.
// Arrays of tables (`[[probe]]`) are declared with their own item registry, so items are
// validated the same way; their messages name the item, e.g. `probe[2].x1` (numbered from 1).
//
// Values are looked up by string only while the case is read; solvers use the plain struct
// CaseConfig (setup/Case.hpp) filled from here once.
#include <array>
#include <cstddef>
#include <functional>
#include <iosfwd>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace gf {

// Collects input errors so one run reports all of them; throw_if_any() raises one
// InputError holding every message, one per line, in the order they were added.
class InputErrors {
 public:
  void add(std::string message) { messages_.push_back(std::move(message)); }
  bool empty() const { return messages_.empty(); }
  std::size_t size() const { return messages_.size(); }
  const std::vector<std::string>& messages() const { return messages_; }
  void throw_if_any() const;  // gf::InputError

 private:
  std::vector<std::string> messages_;
};

enum class ParamType { Real, Integer, Boolean, String, Enum, Real2, StringList, RealList };

// Storage for every parameter type. Enum values are stored as their string.
using ParamValue = std::variant<double, long long, bool, std::string, std::array<double, 2>,
                                std::vector<std::string>, std::vector<double>>;

// Allowed interval of a number (of each component of a Real2 or element of a RealList). Ends may be open or closed.
// `zero_ok` admits the sentinel 0 outside the interval, for keys where 0 means "automatic"
// or "never" (grid.nx = 0 derives nx from the aspect ratio).
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;
  bool zero_ok = false;

  static Range any() { return {}; }
  static Range gt(double v) {
    Range r;
    r.lo = v;
    r.lo_open = true;
    return r;
  }
  static Range ge(double v) {
    Range r;
    r.lo = v;
    return r;
  }
  // lo < x <= hi
  static Range open_closed(double lo, double hi) {
    Range r;
    r.lo = lo;
    r.hi = hi;
    r.lo_open = true;
    return r;
  }
  // lo < x < hi
  static Range open(double lo, double hi) {
    Range r = open_closed(lo, hi);
    r.hi_open = true;
    return r;
  }
  Range or_zero() const {
    Range r = *this;
    r.zero_ok = true;
    return r;
  }

  bool contains(double v) const;
  // "> 0", ">= 8", "in (0, 1]", "0 or >= 8"; "" when everything is allowed.
  std::string describe() const;
};

// A check of a string value beyond its type (e.g. a probe name's character set): returns ""
// when the value is fine, otherwise what is allowed.
using StringRule = std::function<std::string(const std::string&)>;

struct ParamSpec {
  std::string key;  // dotted, relative to the registry ("time.t_end"; "x0" inside [[probe]])
  ParamType type = ParamType::Real;
  std::string unit;                  // SI, "" when dimensionless
  std::optional<ParamValue> def;     // nullopt: required (no sensible default)
  Range range;                       // Real, Integer, Real2, RealList (each component)
  std::vector<std::string> choices;  // Enum; StringList (each element)
  StringRule rule;                   // String (optional)
  std::string rule_text;             // what `rule` allows, for the help listing
  std::string help;
};

class Params {
 public:
  // ---- Declaration. A duplicate key is a programming error (std::logic_error).
  Params& add_real(const std::string& key, const std::string& unit, std::optional<double> def,
                   Range range, const std::string& help);
  Params& add_int(const std::string& key, const std::string& unit, std::optional<long long> def,
                  Range range, const std::string& help);
  Params& add_bool(const std::string& key, bool def, const std::string& help);
  Params& add_string(const std::string& key, std::optional<std::string> def,
                     const std::string& help, StringRule rule = {},
                     const std::string& rule_text = "");
  Params& add_enum(const std::string& key, const std::string& def, std::vector<std::string> choices,
                   const std::string& help);
  Params& add_real2(const std::string& key, const std::string& unit, std::array<double, 2> def,
                    Range range, const std::string& help);
  Params& add_string_list(const std::string& key, std::vector<std::string> def,
                          std::vector<std::string> choices, const std::string& help);
  // A non-empty list of numbers, each in `range`, no value twice (e.g. the deposit cut-offs).
  Params& add_real_list(const std::string& key, const std::string& unit, std::vector<double> def,
                        Range range, const std::string& help);
  // An array of tables `[[name]]`; each item is validated against `item` (relative keys).
  Params& add_table_array(const std::string& name, Params item, const std::string& help);

  // ---- Loading. Values are reset to their defaults first. Reads `path`, then applies the
  // overrides ("key=value"; value parsed as a TOML value, bare words taken as strings).
  // Problems are appended to `errors` (nothing thrown); the 2-argument forms throw
  // InputError if there were any.
  void load(const std::string& path, const std::vector<std::string>& overrides,
            InputErrors& errors);
  void load(const std::string& path, const std::vector<std::string>& overrides);
  // Same, from TOML text in memory; `source` names it in messages.
  void load_string(const std::string& text, const std::string& source,
                   const std::vector<std::string>& overrides, InputErrors& errors);

  // ---- Typed access (std::logic_error on an undeclared key or a type mismatch: a bug).
  double get_real(const std::string& key) const;
  long long get_int(const std::string& key) const;
  bool get_bool(const std::string& key) const;
  const std::string& get_string(const std::string& key) const;  // String and Enum
  std::array<double, 2> get_real2(const std::string& key) const;
  const std::vector<std::string>& get_string_list(const std::string& key) const;
  const std::vector<double>& get_real_list(const std::string& key) const;
  // The loaded items of `[[name]]`, each a registry of the item keys.
  const std::vector<Params>& items(const std::string& name) const;

  // ---- Provenance, for cross-field checks that report like the registry does.
  bool is_set(const std::string& key) const;  // given in the file or by --set
  // False if the value given for `key` was rejected (it then holds its default, so checks
  // that combine keys should skip it rather than report a consequence of the first error).
  bool valid(const std::string& key) const;
  // True if the case file was read and parsed (false: missing or TOML syntax error).
  bool file_ok() const { return file_ok_; }
  // "case.toml:12: initial.y1 = 0.2", "--set: initial.y1 = 0.2" or
  // "case.toml: initial.y1 = 0.14 (default)": the start of a message about `key`.
  std::string where(const std::string& key) const;
  const std::string& source() const { return source_; }
  // A comment written above `key` in to_toml() (e.g. the value derived from a 0 sentinel).
  void annotate(const std::string& key, const std::string& note);

  // ---- Output.
  // Every key with its current value, grouped in [sections], each preceded by its help,
  // unit and allowed values as comments; `header` lines are written first as comments.
  std::string to_toml(const std::string& header = "") const;
  // Writes to_toml(header) to `path`. Returns an error message, empty on success.
  [[nodiscard]] std::string write_toml(const std::string& path,
                                       const std::string& header = "") const;
  // The listing of `granflow check --list`: key, type, unit, default, allowed, help.
  void print_help(std::ostream& os) const;
  const std::vector<ParamSpec>& specs() const { return specs_; }

 private:
  struct Entry {
    ParamValue value;
    bool set = false;      // given by the user
    bool invalid = false;  // given, but rejected
    std::string origin;    // "case.toml:12" or "--set"
    std::string note;      // annotate()
  };
  struct TableArray {
    std::string help;
    std::vector<ParamSpec> item_specs;  // for the help listing
    std::shared_ptr<const Params> schema;
    std::vector<Params> items;
  };
  Params& declare(ParamSpec spec);
  const ParamSpec* find(const std::string& key) const;
  std::size_t index_of(const std::string& key) const;  // logic_error if undeclared
  const ParamValue& value_of(const std::string& key) const;
  bool is_section(const std::string& key) const;
  std::string shown(const std::string& key) const { return prefix_ + key; }
  void reset();
  // The TOML walking lives in Params.cpp so this header does not pull in toml++.
  friend struct ParamsLoader;

  std::vector<ParamSpec> specs_;
  std::map<std::string, std::size_t> index_;
  std::vector<Entry> entries_;
  std::vector<std::string> array_order_;
  std::map<std::string, TableArray> arrays_;
  std::string source_ = "case";  // the file name used in messages
  std::string prefix_;           // "probe[2]." for an item of an array of tables
  std::string item_origin_;      // "case.toml:30" for an item: where its [[...]] header is
  bool file_ok_ = false;
};

// ---- Helpers shared with the case code.
// Optimal-string-alignment edit distance (insertions, deletions, substitutions and
// transpositions of adjacent characters each cost 1).
std::size_t edit_distance(const std::string& a, const std::string& b);
// The candidate closest to `word`, or "" if none is close enough to be a plausible typo.
std::string closest_match(const std::string& word, const std::vector<std::string>& candidates);
// Shortest text that reads back as the same double ("0.1", "1e-05", "-5").
std::string format_number(double v);

}  // namespace gf
