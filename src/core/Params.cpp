// The typed parameter registry (see Params.hpp). Reading is in three passes so that every
// problem is reported at once and an override can replace a bad value in the file:
//   1. walk the parsed file: remember the node given for each declared key, report unknown
//      keys (with a suggestion) and load the items of arrays of tables;
//   2. apply the --set overrides on top (a later one wins);
//   3. convert and validate the surviving node of each key; report missing required keys.
// File messages are sorted by line, then come the override messages.
#include "core/Params.hpp"

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "core/Error.hpp"

namespace gf {

// ------------------------------------------------------------------------------------------
// Small helpers
// ------------------------------------------------------------------------------------------

void InputErrors::throw_if_any() const {
  if (messages_.empty()) return;
  std::string all;
  for (const auto& m : messages_) {
    if (!all.empty()) all += '\n';
    all += m;
  }
  throw InputError(all);
}

std::string format_number(double v) {
  // Whole numbers as integers ("100000", not the shortest form "1e+05"); anything else in
  // the shortest form that reads back exactly.
  if (v == std::trunc(v) && std::abs(v) < 1e15) return std::to_string(static_cast<long long>(v));
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

namespace {

// A double as a TOML float: "1550" would read back as an integer, so add ".0".
std::string toml_number(double v) {
  std::string s = format_number(v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

// A TOML basic string (double quotes, escapes), also used to show strings in messages.
std::string quote(const std::string& s) {
  std::string out = "\"";
  for (const unsigned char c : s) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (c < 0x20 || c == 0x7f) {
          char b[8];
          std::snprintf(b, sizeof b, "\\u%04X", static_cast<unsigned>(c));
          out += b;
        } else {
          out += static_cast<char>(c);
        }
    }
  }
  return out + "\"";
}

std::string join(const std::vector<std::string>& v, const std::string& sep) {
  std::string out;
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? sep : "") + v[i];
  return out;
}

std::string unit_suffix(const ParamSpec& s) { return s.unit.empty() ? "" : " (" + s.unit + ")"; }

std::string format_value(const ParamValue& v, bool toml) {
  struct Visitor {
    bool toml;
    std::string operator()(double x) const { return toml ? toml_number(x) : format_number(x); }
    std::string operator()(long long x) const { return std::to_string(x); }
    std::string operator()(bool x) const { return x ? "true" : "false"; }
    std::string operator()(const std::string& x) const { return quote(x); }
    std::string operator()(const std::array<double, 2>& x) const {
      return "[" + (*this)(x[0]) + ", " + (*this)(x[1]) + "]";
    }
    std::string operator()(const std::vector<std::string>& x) const {
      std::vector<std::string> q;
      for (const auto& s : x) q.push_back(quote(s));
      return "[" + join(q, ", ") + "]";
    }
    std::string operator()(const std::vector<double>& x) const {
      std::vector<std::string> q;
      for (const double v : x) q.push_back((*this)(v));
      return "[" + join(q, ", ") + "]";
    }
  };
  return std::visit(Visitor{toml}, v);
}

ParamValue zero_of(ParamType t) {
  switch (t) {
    case ParamType::Real:
      return 0.0;
    case ParamType::Integer:
      return 0LL;
    case ParamType::Boolean:
      return false;
    case ParamType::String:
    case ParamType::Enum:
      return std::string();
    case ParamType::Real2:
      return std::array<double, 2>{0.0, 0.0};
    case ParamType::StringList:
      return std::vector<std::string>();
    case ParamType::RealList:
      return std::vector<double>();
  }
  return 0.0;
}

const char* type_name(ParamType t) {
  switch (t) {
    case ParamType::Real:
      return "real";
    case ParamType::Integer:
      return "int";
    case ParamType::Boolean:
      return "bool";
    case ParamType::String:
      return "string";
    case ParamType::Enum:
      return "enum";
    case ParamType::Real2:
      return "real[2]";
    case ParamType::StringList:
      return "string[]";
    case ParamType::RealList:
      return "real[]";
  }
  return "?";
}

// What a value of this type looks like, for "wrong type" messages.
const char* expected_text(ParamType t) {
  switch (t) {
    case ParamType::Real:
      return "a number";
    case ParamType::Integer:
      return "an integer";
    case ParamType::Boolean:
      return "true or false";
    case ParamType::String:
    case ParamType::Enum:
      return "a string";
    case ParamType::Real2:
      return "an array of 2 numbers";
    case ParamType::StringList:
      return "an array of strings";
    case ParamType::RealList:
      return "an array of numbers";
  }
  return "?";
}

std::string allowed_text(const ParamSpec& s) {
  switch (s.type) {
    case ParamType::Real:
    case ParamType::Integer: {
      const std::string r = s.range.describe();
      return r.empty() ? "any" : r;
    }
    case ParamType::Real2:
    case ParamType::RealList: {
      const std::string r = s.range.describe();
      return r.empty() ? "any" : "each " + r;
    }
    case ParamType::Boolean:
      return "true or false";
    case ParamType::String:
      return s.rule_text.empty() ? "any string" : s.rule_text;
    case ParamType::Enum:
      return "one of " + join(s.choices, ", ");
    case ParamType::StringList:
      return "one or more of " + join(s.choices, ", ");
  }
  return "";
}

std::string node_kind(const toml::node& n) {
  if (const auto* a = n.as_array())
    return "an array of " + std::to_string(a->size()) + (a->size() == 1 ? " element" : " elements");
  switch (n.type()) {
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a float";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::table:
      return "a table";
    case toml::node_type::date:
    case toml::node_type::time:
    case toml::node_type::date_time:
      return "a date/time";
    default:
      return "nothing";
  }
}

// A node as the user wrote it, near enough: shortest numbers, quoted strings.
std::string show_node(const toml::node& n) {
  if (const auto* v = n.as_integer()) return std::to_string(v->get());
  // Floats keep their ".0" so "n = 64.0: expected an integer, got a float" makes sense.
  if (const auto* v = n.as_floating_point()) return toml_number(v->get());
  if (const auto* v = n.as_boolean()) return v->get() ? "true" : "false";
  if (const auto* v = n.as_string()) return quote(v->get());
  if (const auto* a = n.as_array()) {
    std::vector<std::string> parts;
    for (const auto& e : *a) parts.push_back(show_node(e));
    return "[" + join(parts, ", ") + "]";
  }
  if (const auto* t = n.as_table()) return t->empty() ? "{}" : "{...}";
  std::ostringstream os;
  n.visit([&](const auto& x) { os << x; });
  return os.str();
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  const auto e = s.find_last_not_of(" \t\r\n");
  return s.substr(b, e - b + 1);
}

// A decimal number as TOML writes one (sign, digits with '_', fraction, exponent): to tell a
// number that failed to parse (out of range) from a word.
bool looks_like_number(const std::string& t) {
  std::size_t i = 0;
  const auto digits = [&] {
    const std::size_t b = i;
    while (i < t.size() && (std::isdigit(static_cast<unsigned char>(t[i])) || t[i] == '_')) ++i;
    return i > b;
  };
  if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
  bool any = digits();
  if (i < t.size() && t[i] == '.') {
    ++i;
    any = digits() || any;
  }
  if (!any) return false;
  if (i < t.size() && (t[i] == 'e' || t[i] == 'E')) {
    ++i;
    if (i < t.size() && (t[i] == '+' || t[i] == '-')) ++i;
    if (!digits()) return false;
  }
  return i == t.size();
}

std::string last_component(const std::string& key) {
  const auto dot = key.rfind('.');
  return dot == std::string::npos ? key : key.substr(dot + 1);
}

// Checks a number against the spec's range; "" if allowed.
std::string check_range(const ParamSpec& s, double x, const char* each = "") {
  if (!std::isfinite(x)) return std::string(each) + "must be a finite number" + unit_suffix(s);
  if (!s.range.contains(x))
    return std::string(each) + "must be " + s.range.describe() + unit_suffix(s);
  return "";
}

// Converts `n` to the spec's type and checks it. On failure returns nullopt and sets `why`
// to what is wrong and what is allowed.
std::optional<ParamValue> convert(const ParamSpec& s, const toml::node& n, std::string& why) {
  const auto wrong_type = [&]() -> std::optional<ParamValue> {
    why = std::string("wrong type: expected ") + expected_text(s.type) + unit_suffix(s) + ", got " +
          node_kind(n);
    return std::nullopt;
  };
  // An array of the right shape with an element of the wrong type (k counted from 1).
  const auto wrong_element = [&](std::size_t k, const toml::node& e) -> std::optional<ParamValue> {
    why = std::string("wrong type: expected ") + expected_text(s.type) + unit_suffix(s) +
          ", but element " + std::to_string(k + 1) + " is " + node_kind(e);
    return std::nullopt;
  };
  switch (s.type) {
    case ParamType::Real: {
      double x;
      if (const auto* i = n.as_integer())
        x = static_cast<double>(i->get());  // "rho = 1550"
      else if (const auto* f = n.as_floating_point())
        x = f->get();
      else
        return wrong_type();
      why = check_range(s, x);
      if (!why.empty()) return std::nullopt;
      return x;
    }
    case ParamType::Integer: {
      const auto* i = n.as_integer();
      if (!i) return wrong_type();  // 64.0 is refused too: a count written as a float is a slip
      const long long x = i->get();
      why = check_range(s, static_cast<double>(x));
      if (!why.empty()) return std::nullopt;
      return x;
    }
    case ParamType::Boolean: {
      const auto* b = n.as_boolean();
      if (!b) return wrong_type();
      return b->get();
    }
    case ParamType::String: {
      const auto* str = n.as_string();
      if (!str) return wrong_type();
      if (s.rule) {
        const std::string r = s.rule(str->get());
        if (!r.empty()) {
          why = r;
          return std::nullopt;
        }
      }
      return str->get();
    }
    case ParamType::Enum: {
      const auto* str = n.as_string();
      if (!str) {
        wrong_type();
        why += "; one of " + join(s.choices, ", ");
        return std::nullopt;
      }
      const std::string& v = str->get();
      if (std::find(s.choices.begin(), s.choices.end(), v) != s.choices.end()) return v;
      why = "must be one of " + join(s.choices, ", ");
      const std::string near = closest_match(v, s.choices);
      if (!near.empty()) why += "; did you mean " + near + "?";
      return std::nullopt;
    }
    case ParamType::Real2: {
      const auto* a = n.as_array();
      if (!a || a->size() != 2) return wrong_type();
      std::array<double, 2> x{};
      for (std::size_t k = 0; k < 2; ++k) {
        const toml::node& e = *a->get(k);
        if (const auto* i = e.as_integer())
          x[k] = static_cast<double>(i->get());
        else if (const auto* f = e.as_floating_point())
          x[k] = f->get();
        else
          return wrong_element(k, e);
        why = check_range(s, x[k], "each component ");
        if (!why.empty()) return std::nullopt;
      }
      return x;
    }
    case ParamType::StringList: {
      const auto* a = n.as_array();
      if (!a) return wrong_type();
      std::vector<std::string> x;
      for (std::size_t k = 0; k < a->size(); ++k) {
        const toml::node& e = *a->get(k);
        const auto* str = e.as_string();
        if (!str) return wrong_element(k, e);
        const std::string& v = str->get();
        if (!s.choices.empty() &&
            std::find(s.choices.begin(), s.choices.end(), v) == s.choices.end()) {
          why = quote(v) + " is not allowed: each must be one of " + join(s.choices, ", ");
          const std::string near = closest_match(v, s.choices);
          if (!near.empty()) why += "; did you mean " + near + "?";
          return std::nullopt;
        }
        if (std::find(x.begin(), x.end(), v) != x.end()) {
          why = quote(v) + " is listed twice";
          return std::nullopt;
        }
        x.push_back(v);
      }
      if (x.empty()) {
        why = "must list at least one of " + join(s.choices, ", ");
        return std::nullopt;
      }
      return x;
    }
    case ParamType::RealList: {
      const auto* a = n.as_array();
      if (!a) return wrong_type();
      std::vector<double> x;
      for (std::size_t k = 0; k < a->size(); ++k) {
        const toml::node& e = *a->get(k);
        double v;
        if (const auto* i = e.as_integer())
          v = static_cast<double>(i->get());
        else if (const auto* f = e.as_floating_point())
          v = f->get();
        else
          return wrong_element(k, e);
        why = check_range(s, v, "each element ");
        if (!why.empty()) return std::nullopt;
        if (std::find(x.begin(), x.end(), v) != x.end()) {
          why = format_number(v) + " is listed twice";
          return std::nullopt;
        }
        x.push_back(v);
      }
      if (x.empty()) {
        why = "must list at least one number";
        return std::nullopt;
      }
      return x;
    }
  }
  return wrong_type();
}

}  // namespace

// ------------------------------------------------------------------------------------------
// Range, edit distance
// ------------------------------------------------------------------------------------------

bool Range::contains(double v) const {
  if (zero_ok && v == 0.0) return true;
  if (lo_open ? !(v > lo) : !(v >= lo)) return false;
  if (hi_open ? !(v < hi) : !(v <= hi)) return false;
  return true;
}

std::string Range::describe() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  std::string s;
  if (has_lo && has_hi)
    s = std::string("in ") + (lo_open ? "(" : "[") + format_number(lo) + ", " + format_number(hi) +
        (hi_open ? ")" : "]");
  else if (has_lo)
    s = std::string(lo_open ? "> " : ">= ") + format_number(lo);
  else if (has_hi)
    s = std::string(hi_open ? "< " : "<= ") + format_number(hi);
  if (zero_ok && !s.empty()) s = "0 or " + s;
  return s;
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  const std::size_t n = a.size(), m = b.size();
  std::vector<std::vector<std::size_t>> d(n + 1, std::vector<std::size_t>(m + 1));
  for (std::size_t i = 0; i <= n; ++i) d[i][0] = i;
  for (std::size_t j = 0; j <= m; ++j) d[0][j] = j;
  for (std::size_t i = 1; i <= n; ++i)
    for (std::size_t j = 1; j <= m; ++j) {
      const std::size_t cost = a[i - 1] == b[j - 1] ? 0 : 1;
      d[i][j] = std::min({d[i - 1][j] + 1, d[i][j - 1] + 1, d[i - 1][j - 1] + cost});
      if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1])
        d[i][j] = std::min(d[i][j], d[i - 2][j - 2] + 1);  // "rhoo" / "etab" style slips
    }
  return d[n][m];
}

std::string closest_match(const std::string& word, const std::vector<std::string>& candidates) {
  // Up to a third of the word may be wrong (at least 2 characters): beyond that a
  // "did you mean" is more confusing than helpful.
  const std::size_t limit = std::max<std::size_t>(2, word.size() / 3);
  std::string best;
  std::size_t best_d = limit + 1;
  for (const auto& c : candidates) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  return best;
}

// ------------------------------------------------------------------------------------------
// Declaration
// ------------------------------------------------------------------------------------------

Params& Params::declare(ParamSpec spec) {
  if (spec.key.empty() || index_.count(spec.key) || arrays_.count(spec.key))
    throw std::logic_error("Params: parameter '" + spec.key + "' declared twice or empty");
  // A default that its own checks would reject is a schema bug: catch it at declaration.
  if (spec.def) {
    bool ok = true;
    if (const auto* x = std::get_if<double>(&*spec.def)) ok = spec.range.contains(*x);
    if (const auto* x = std::get_if<long long>(&*spec.def)) ok = spec.range.contains(double(*x));
    if (const auto* x = std::get_if<std::array<double, 2>>(&*spec.def))
      ok = spec.range.contains((*x)[0]) && spec.range.contains((*x)[1]);
    if (const auto* x = std::get_if<std::vector<double>>(&*spec.def))
      for (const double v : *x) ok = ok && spec.range.contains(v);
    if (spec.type == ParamType::Enum)
      ok = std::find(spec.choices.begin(), spec.choices.end(), std::get<std::string>(*spec.def)) !=
           spec.choices.end();
    if (spec.type == ParamType::String && spec.rule)
      ok = spec.rule(std::get<std::string>(*spec.def)).empty();
    if (!ok) throw std::logic_error("Params: default of '" + spec.key + "' is not allowed");
  }
  index_[spec.key] = specs_.size();
  Entry e;
  e.value = spec.def ? *spec.def : zero_of(spec.type);
  entries_.push_back(std::move(e));
  specs_.push_back(std::move(spec));
  return *this;
}

Params& Params::add_real(const std::string& key, const std::string& unit, std::optional<double> def,
                         Range range, const std::string& help) {
  ParamSpec s{key, ParamType::Real, unit, std::nullopt, range, {}, {}, "", help};
  if (def) s.def = *def;
  return declare(std::move(s));
}

Params& Params::add_int(const std::string& key, const std::string& unit,
                        std::optional<long long> def, Range range, const std::string& help) {
  ParamSpec s{key, ParamType::Integer, unit, std::nullopt, range, {}, {}, "", help};
  if (def) s.def = *def;
  return declare(std::move(s));
}

Params& Params::add_bool(const std::string& key, bool def, const std::string& help) {
  return declare({key, ParamType::Boolean, "", def, {}, {}, {}, "", help});
}

Params& Params::add_string(const std::string& key, std::optional<std::string> def,
                           const std::string& help, StringRule rule, const std::string& rule_text) {
  ParamSpec s{key, ParamType::String, "", std::nullopt, {}, {}, std::move(rule), rule_text, help};
  if (def) s.def = *def;
  return declare(std::move(s));
}

Params& Params::add_enum(const std::string& key, const std::string& def,
                         std::vector<std::string> choices, const std::string& help) {
  return declare({key, ParamType::Enum, "", def, {}, std::move(choices), {}, "", help});
}

Params& Params::add_real2(const std::string& key, const std::string& unit,
                          std::array<double, 2> def, Range range, const std::string& help) {
  return declare({key, ParamType::Real2, unit, def, range, {}, {}, "", help});
}

Params& Params::add_string_list(const std::string& key, std::vector<std::string> def,
                                std::vector<std::string> choices, const std::string& help) {
  return declare({key, ParamType::StringList, "", def, {}, std::move(choices), {}, "", help});
}

Params& Params::add_real_list(const std::string& key, const std::string& unit,
                              std::vector<double> def, Range range, const std::string& help) {
  return declare({key, ParamType::RealList, unit, std::move(def), range, {}, {}, "", help});
}

Params& Params::add_table_array(const std::string& name, Params item, const std::string& help) {
  if (name.empty() || index_.count(name) || arrays_.count(name))
    throw std::logic_error("Params: table array '" + name + "' declared twice or empty");
  TableArray ta;
  ta.help = help;
  ta.item_specs = item.specs_;
  ta.schema = std::make_shared<const Params>(std::move(item));
  arrays_.emplace(name, std::move(ta));
  array_order_.push_back(name);
  return *this;
}

// ------------------------------------------------------------------------------------------
// Lookup
// ------------------------------------------------------------------------------------------

const ParamSpec* Params::find(const std::string& key) const {
  const auto it = index_.find(key);
  return it == index_.end() ? nullptr : &specs_[it->second];
}

std::size_t Params::index_of(const std::string& key) const {
  const auto it = index_.find(key);
  if (it == index_.end()) throw std::logic_error("Params: undeclared parameter '" + key + "'");
  return it->second;
}

const ParamValue& Params::value_of(const std::string& key) const {
  return entries_[index_of(key)].value;
}

bool Params::is_section(const std::string& key) const {
  const std::string p = key + ".";
  for (const auto& s : specs_)
    if (s.key.compare(0, p.size(), p) == 0) return true;
  return false;
}

template <class T>
static const T& get_as(const ParamValue& v, const std::string& key) {
  const T* p = std::get_if<T>(&v);
  if (!p) throw std::logic_error("Params: parameter '" + key + "' read with the wrong type");
  return *p;
}

double Params::get_real(const std::string& key) const { return get_as<double>(value_of(key), key); }
long long Params::get_int(const std::string& key) const {
  return get_as<long long>(value_of(key), key);
}
bool Params::get_bool(const std::string& key) const { return get_as<bool>(value_of(key), key); }
const std::string& Params::get_string(const std::string& key) const {
  return get_as<std::string>(value_of(key), key);
}
std::array<double, 2> Params::get_real2(const std::string& key) const {
  return get_as<std::array<double, 2>>(value_of(key), key);
}
const std::vector<std::string>& Params::get_string_list(const std::string& key) const {
  return get_as<std::vector<std::string>>(value_of(key), key);
}

const std::vector<double>& Params::get_real_list(const std::string& key) const {
  return get_as<std::vector<double>>(value_of(key), key);
}

const std::vector<Params>& Params::items(const std::string& name) const {
  const auto it = arrays_.find(name);
  if (it == arrays_.end()) throw std::logic_error("Params: undeclared table array '" + name + "'");
  return it->second.items;
}

bool Params::is_set(const std::string& key) const { return entries_[index_of(key)].set; }
bool Params::valid(const std::string& key) const { return !entries_[index_of(key)].invalid; }

std::string Params::where(const std::string& key) const {
  const Entry& e = entries_[index_of(key)];
  const std::string v = shown(key) + " = " + format_value(e.value, false);
  if (e.set) return e.origin + ": " + v;
  return (item_origin_.empty() ? source_ : item_origin_) + ": " + v + " (default)";
}

void Params::annotate(const std::string& key, const std::string& note) {
  entries_[index_of(key)].note = note;
}

void Params::reset() {
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    Entry& e = entries_[i];
    e = Entry{};
    e.value = specs_[i].def ? *specs_[i].def : zero_of(specs_[i].type);
  }
  for (auto& [name, ta] : arrays_) ta.items.clear();
  file_ok_ = false;
}

// ------------------------------------------------------------------------------------------
// Loading
// ------------------------------------------------------------------------------------------

struct ParamsLoader {
  struct Candidate {
    const toml::node* node = nullptr;
    std::string origin;  // "case.toml:12" or "--set"
    int line = 0;        // 0 for overrides
    bool quoted = false;  // a quoted dotted key ("grid.n" = 32)
  };
  struct Pending {  // a message about the file, sorted by line before it is reported
    int line;
    std::string text;
  };

  static int line_of(const toml::node& n) { return static_cast<int>(n.source().begin.line); }
  static std::string origin(const std::string& src, int line) {
    return line > 0 ? src + ":" + std::to_string(line) : src;
  }

  // Why `key` is not a parameter, with the most useful hint we can find.
  static std::string unknown_reason(const Params& p, const std::string& key) {
    if (p.is_section(key)) {
      for (const auto& s : p.specs_)
        if (s.key.compare(0, key.size() + 1, key + ".") == 0)
          return "is a section of keys such as " + s.key + ", not a value";
    }
    std::vector<std::string> names;
    for (const auto& s : p.specs_) names.push_back(s.key);
    for (const auto& a : p.array_order_) names.push_back(a);
    const std::string near = closest_match(key, names);
    if (!near.empty()) return "unknown key; did you mean " + p.shown(near) + "?";
    // A key put in the wrong section: suggest the keys with the same last component.
    std::vector<std::string> same;
    for (const auto& n : names)
      if (last_component(n) == last_component(key)) same.push_back(p.shown(n));
    if (!same.empty()) return "unknown key; did you mean " + join(same, " or ") + "?";
    return "unknown key (granflow check --list shows every key)";
  }

  static void walk(Params& p, const toml::table& t, const std::string& prefix,
                   const std::string& src, std::map<std::string, Candidate>& cand,
                   std::vector<Pending>& pend) {
    for (auto&& [k, node] : t) {
      const std::string key =
          prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
      // Implicit tables (from [a.b] or dotted keys) have no source; the key always has.
      int line = line_of(node);
      if (line == 0) line = static_cast<int>(k.source().begin.line);
      if (p.find(key)) {
        // The same key twice: TOML itself refuses a repeated key within a table, but a quoted
        // root key "grid.n" = 32 and [grid] n = 16 are two different keys to TOML and the same
        // parameter here. Which one was meant is not ours to guess: an error, the first kept.
        const bool quoted = std::string(k.str()).find('.') != std::string::npos;
        if (const auto it = cand.find(key); it != cand.end()) {
          pend.push_back({line, origin(src, line) + ": " + p.shown(key) + " = " +
                                    show_node(node) + ": given twice (also at " +
                                    it->second.origin + ", = " + show_node(*it->second.node) +
                                    ")" +
                                    (quoted || it->second.quoted
                                         ? ": a quoted key \"" + key +
                                               "\" is the same parameter as " +
                                               last_component(key) + " in its [section]"
                                         : "") +
                                    "; keep one"});
          continue;
        }
        cand[key] = {&node, origin(src, line), line, quoted};
        continue;
      }
      if (p.arrays_.count(key)) {
        load_array(p, key, node, src, line, pend);
        continue;
      }
      // A known section, or an unknown one whose keys we report one by one (each with its
      // own suggestion: [phase.granuler] rho -> phase.granular.rho).
      if (const auto* sub = node.as_table(); sub && (p.is_section(key) || !sub->empty())) {
        walk(p, *sub, key, src, cand, pend);
        continue;
      }
      pend.push_back({line, origin(src, line) + ": " + p.shown(key) + " = " + show_node(node) +
                                ": " + unknown_reason(p, key)});
    }
  }

  static void load_array(Params& p, const std::string& name, const toml::node& node,
                         const std::string& src, int line, std::vector<Pending>& pend) {
    Params::TableArray& ta = p.arrays_.at(name);
    const auto* arr = node.as_array();
    if (!arr || (!arr->empty() && !arr->is_array_of_tables())) {
      pend.push_back({line, origin(src, line) + ": " + p.shown(name) + " = " + show_node(node) +
                                ": wrong type: expected an array of tables [[" + name + "]], got " +
                                node_kind(node)});
      return;
    }
    for (std::size_t i = 0; i < arr->size(); ++i) {
      const toml::table& t = *arr->get(i)->as_table();
      Params item = *ta.schema;
      item.reset();
      item.source_ = src;
      item.prefix_ = p.prefix_ + name + "[" + std::to_string(i + 1) + "].";
      const int item_line = line_of(t) > 0 ? line_of(t) : line;
      item.item_origin_ = origin(src, item_line);
      item.file_ok_ = true;
      InputErrors none;  // items take no overrides
      apply(item, &t, src, {}, pend, none);
      ta.items.push_back(std::move(item));
    }
  }

  // Reads "key=value" into a node owned by `owned`; reports what cannot be applied.
  static void add_override(const Params& p, const std::string& o,
                           std::map<std::string, Candidate>& cand,
                           std::vector<std::unique_ptr<toml::table>>& owned, InputErrors& late) {
    const auto eq = o.find('=');
    const std::string key = trim(o.substr(0, eq));
    if (eq == std::string::npos || key.empty()) {
      late.add("--set " + o + ": expected key=value, e.g. --set grid.n=128");
      return;
    }
    const std::string text = trim(o.substr(eq + 1));
    for (const auto& name : p.array_order_)
      if (key == name || key.rfind(name + "[", 0) == 0 || key.rfind(name + ".", 0) == 0) {
        late.add("--set: " + key + " = " + text + ": [[" + name +
                 "]] entries can only be given in the case file");
        return;
      }
    const ParamSpec* spec = p.find(key);
    if (!spec) {
      late.add("--set: " + key + " = " + text + ": " + unknown_reason(p, key));
      return;
    }
    // The value is a TOML value ("1e-4", "[0, -9.81]", "\"x\"", "true"); a bare word (or
    // anything that is not valid TOML) is a string, so --set initial.shape=circle works.
    auto t = std::make_unique<toml::table>();
    bool parsed = false;
    try {
      *t = toml::parse(std::string_view("v = " + text), std::string_view("--set"));
      parsed = t->size() == 1 && t->contains("v");
    } catch (const toml::parse_error&) {
    }
    const bool wants_string = spec->type == ParamType::String || spec->type == ParamType::Enum;
    // A number beyond the range of a double (1e999) is not valid TOML either; it must not then
    // be read as a string ("got a string"): say what is wrong with it.
    if (!parsed && !wants_string && looks_like_number(text)) {
      late.add("--set: " + key + " = " + text + ": out of range: " +
               (spec->type == ParamType::Integer
                    ? std::string("beyond the 64-bit integers (+-9.2e18)")
                    : std::string("not representable as a double (magnitude above 1.8e308 or "
                                  "a non-zero value below 4.9e-324)")));
      return;
    }
    if (!parsed || (wants_string && !t->get("v")->is_string())) {
      t = std::make_unique<toml::table>();
      t->insert("v", text);
    }
    cand[key] = {t->get("v"), "--set", 0};
    owned.push_back(std::move(t));
  }

  static void apply(Params& p, const toml::table* file, const std::string& src,
                    const std::vector<std::string>& overrides, std::vector<Pending>& pend,
                    InputErrors& late) {
    std::map<std::string, Candidate> cand;
    if (file) walk(p, *file, "", src, cand, pend);
    std::vector<std::unique_ptr<toml::table>> owned;  // keeps override nodes alive
    for (const auto& o : overrides) add_override(p, o, cand, owned, late);

    for (const auto& [key, c] : cand) {
      const std::size_t i = p.index_.at(key);
      Params::Entry& e = p.entries_[i];
      e.set = true;
      e.origin = c.origin;
      std::string why;
      if (auto v = convert(p.specs_[i], *c.node, why)) {
        e.value = std::move(*v);
        continue;
      }
      e.invalid = true;
      std::string msg = c.origin + ": " + p.shown(key) + " = " + show_node(*c.node) + ": " + why;
      if (c.line > 0 || c.origin != "--set")
        pend.push_back({c.line, std::move(msg)});
      else
        late.add(std::move(msg));
    }

    const std::string here = p.item_origin_.empty() ? src : p.item_origin_;
    int here_line = 0;
    if (const auto colon = here.rfind(':'); colon != std::string::npos)
      here_line = std::atoi(here.c_str() + colon + 1);
    for (std::size_t i = 0; i < p.specs_.size(); ++i)
      if (!p.specs_[i].def && !p.entries_[i].set) {
        p.entries_[i].invalid = true;
        pend.push_back({here_line, here + ": " + p.shown(p.specs_[i].key) +
                                       ": missing: this key is required" +
                                       unit_suffix(p.specs_[i]) + "; " + p.specs_[i].help});
      }
  }

  static void run(Params& p, const std::optional<std::string>& text, const std::string& src,
                  const std::vector<std::string>& overrides, InputErrors& errors) {
    p.reset();
    p.source_ = src;
    std::optional<toml::table> file;
    if (text) {
      try {
        file = toml::parse(std::string_view(*text), std::string_view(src));
      } catch (const toml::parse_error& e) {
        const auto& b = e.source().begin;
        errors.add(src + ":" + std::to_string(b.line) + ":" + std::to_string(b.column) +
                   ": TOML syntax error: " + std::string(e.description()));
      }
    }
    p.file_ok_ = file.has_value();
    std::vector<Pending> pend;
    InputErrors late;
    apply(p, file ? &*file : nullptr, src, overrides, pend, late);
    std::stable_sort(pend.begin(), pend.end(),
                     [](const Pending& a, const Pending& b) { return a.line < b.line; });
    for (auto& m : pend) errors.add(std::move(m.text));
    for (const auto& m : late.messages()) errors.add(m);
  }
};

void Params::load(const std::string& path, const std::vector<std::string>& overrides,
                  InputErrors& errors) {
  std::optional<std::string> text;
  // A folder opens as a file on Linux and reads as nothing: that would be an empty case (all
  // defaults), run without a word. A read error likewise must not leave a partial text.
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    errors.add(path + ": is a folder, not a case file (give the path of a .toml file)");
  } else if (std::FILE* f = std::fopen(path.c_str(), "rb"); !f) {
    errors.add(path + ": cannot open the case file (" + std::strerror(errno) + ")");
  } else {
    std::string s;
    char buf[1 << 14];
    std::size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) s.append(buf, n);
    const int err = std::ferror(f) ? errno : 0;
    std::fclose(f);
    if (err)
      errors.add(path + ": cannot read the case file (" + std::strerror(err) + ")");
    else
      text = std::move(s);
  }
  // Overrides are still checked without a file, so one run reports every problem.
  ParamsLoader::run(*this, text, path, overrides, errors);
}

void Params::load(const std::string& path, const std::vector<std::string>& overrides) {
  InputErrors errors;
  load(path, overrides, errors);
  errors.throw_if_any();
}

void Params::load_string(const std::string& text, const std::string& source,
                         const std::vector<std::string>& overrides, InputErrors& errors) {
  ParamsLoader::run(*this, text, source, overrides, errors);
}

// ------------------------------------------------------------------------------------------
// Output
// ------------------------------------------------------------------------------------------

namespace {

// Each line of `text` after `lead` ("# " for TOML comments, spaces for the help listing),
// word-wrapped so that lines stay within 96 columns.
void comment_lines(std::ostream& os, const std::string& text, const std::string& lead = "# ") {
  constexpr std::size_t kWidth = 96;
  std::istringstream is(text);
  std::string para;
  while (std::getline(is, para)) {
    std::istringstream words(para);
    std::string word, line;
    while (words >> word) {
      if (!line.empty() && lead.size() + line.size() + 1 + word.size() > kWidth) {
        os << lead << line << "\n";
        line.clear();
      }
      line += (line.empty() ? "" : " ") + word;
    }
    os << lead << line << "\n";
  }
}

// "default: 0.5", or "required" for a key without a default.
std::string default_text(const ParamSpec& s) {
  return s.def ? "default: " + format_value(*s.def, false) : "required";
}

void write_entry(std::ostream& os, const ParamSpec& s, const std::string& leaf, const ParamValue& v,
                 const std::string& note) {
  comment_lines(os, s.help);
  os << "# " << (s.unit.empty() ? "" : "unit: " + s.unit + " | ") << "allowed: " << allowed_text(s)
     << " | " << default_text(s) << "\n";
  if (!note.empty()) comment_lines(os, note);
  os << leaf << " = " << format_value(v, true) << "\n";
}

}  // namespace

std::string Params::to_toml(const std::string& header) const {
  std::ostringstream os;
  if (!header.empty()) comment_lines(os, header);
  // Group keys by section (all but the last component), in order of first declaration;
  // top-level keys go first because TOML puts everything after a [header] in that table.
  std::vector<std::string> sections{""};
  std::map<std::string, std::vector<std::size_t>> members;
  for (std::size_t i = 0; i < specs_.size(); ++i) {
    const auto dot = specs_[i].key.rfind('.');
    const std::string sec = dot == std::string::npos ? "" : specs_[i].key.substr(0, dot);
    if (!members.count(sec) && !sec.empty()) sections.push_back(sec);
    members[sec].push_back(i);
  }
  for (const auto& sec : sections) {
    if (!members.count(sec)) continue;
    if (!sec.empty())
      os << "\n[" << sec << "]\n";
    else if (!header.empty())
      os << "\n";
    for (const std::size_t i : members[sec])
      write_entry(os, specs_[i], last_component(specs_[i].key), entries_[i].value,
                  entries_[i].note);
  }
  for (const auto& name : array_order_) {
    const TableArray& ta = arrays_.at(name);
    os << "\n";
    comment_lines(os, "[[" + name + "]]: " + ta.help);
    if (ta.items.empty()) {
      os << "# (none given; each [[" << name << "]] takes these keys)\n";
      for (const auto& s : ta.item_specs)
        os << "#   " << s.key << ": " << s.help << " (" << (s.unit.empty() ? "" : s.unit + "; ")
           << allowed_text(s) << "; " << default_text(s) << ")\n";
    }
    for (const Params& item : ta.items) {
      os << "[[" << name << "]]\n";
      for (std::size_t i = 0; i < item.specs_.size(); ++i)
        write_entry(os, item.specs_[i], item.specs_[i].key, item.entries_[i].value,
                    item.entries_[i].note);
    }
  }
  return os.str();
}

std::string Params::write_toml(const std::string& path, const std::string& header) const {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  if (!out) return path + ": cannot write (" + std::strerror(errno) + ")";
  out << to_toml(header);
  out.close();
  if (!out) return path + ": write failed (" + std::strerror(errno) + ")";
  return "";
}

void Params::print_help(std::ostream& os) const {
  const auto line = [&](const ParamSpec& s, const std::string& shown_key) {
    os << shown_key << "  (" << type_name(s.type) << (s.unit.empty() ? "" : ", " + s.unit) << ")  "
       << default_text(s) << "; allowed: " << allowed_text(s) << "\n";
    comment_lines(os, s.help, "    ");
  };
  for (const auto& s : specs_) line(s, s.key);
  for (const auto& name : array_order_) {
    const TableArray& ta = arrays_.at(name);
    os << "[[" << name << "]]  (array of tables)  " << ta.help << "\n";
    for (const auto& s : ta.item_specs) line(s, name + "[]." + s.key);
  }
}

}  // namespace gf
