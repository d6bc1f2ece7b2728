#include "io/Json.hpp"

#include <cmath>
#include <cstdio>
#include <type_traits>

#include "io/Csv.hpp"
#include "io/IoError.hpp"

namespace gf::io {

namespace {

void append_escaped(std::string& out, const std::string& s) {
  out += '"';
  for (const char ch : s) {
    const auto c = static_cast<unsigned char>(ch);
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\b': out += "\\b"; break;
      case '\f': out += "\\f"; break;
      case '\n': out += "\\n"; break;
      case '\r': out += "\\r"; break;
      case '\t': out += "\\t"; break;
      default:
        if (c < 0x20) {  // other control characters must be \u escaped
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          out += buf;
        } else {
          out += ch;
        }
    }
  }
  out += '"';
}

}  // namespace

JsonObject::JsonObject(const JsonObject& o) { *this = o; }

JsonObject& JsonObject::operator=(const JsonObject& o) {
  if (this == &o) return *this;
  std::vector<Entry> copy;
  copy.reserve(o.entries_.size());
  for (const Entry& e : o.entries_) {
    if (const auto* sub = std::get_if<std::unique_ptr<JsonObject>>(&e.value))
      copy.push_back({e.key, std::make_unique<JsonObject>(**sub)});
    else
      std::visit(
          [&](const auto& v) {
            using T = std::decay_t<decltype(v)>;
            if constexpr (!std::is_same_v<T, std::unique_ptr<JsonObject>>)
              copy.push_back({e.key, v});
          },
          e.value);
  }
  entries_ = std::move(copy);
  return *this;
}

JsonObject::Value* JsonObject::find(const std::string& key) {
  for (Entry& e : entries_)
    if (e.key == key) return &e.value;
  return nullptr;
}

bool JsonObject::contains(const std::string& key) const {
  for (const Entry& e : entries_)
    if (e.key == key) return true;
  return false;
}

JsonObject& JsonObject::put(const std::string& key, Value v) {
  if (Value* old = find(key)) *old = std::move(v);
  else entries_.push_back({key, std::move(v)});
  return *this;
}

JsonObject& JsonObject::set(const std::string& key, double v) { return put(key, v); }
JsonObject& JsonObject::set(const std::string& key, long long v) { return put(key, v); }
JsonObject& JsonObject::set(const std::string& key, bool v) { return put(key, v); }
JsonObject& JsonObject::set(const std::string& key, std::string v) {
  return put(key, std::move(v));
}
JsonObject& JsonObject::set(const std::string& key, JsonObject v) {
  return put(key, std::make_unique<JsonObject>(std::move(v)));
}

JsonObject& JsonObject::object(const std::string& key) {
  Value* v = find(key);
  if (!v || !std::holds_alternative<std::unique_ptr<JsonObject>>(*v)) {
    put(key, std::make_unique<JsonObject>());
    v = find(key);
  }
  return *std::get<std::unique_ptr<JsonObject>>(*v);
}

void JsonObject::print(std::string& out, int indent) const {
  if (entries_.empty()) {
    out += "{}";
    return;
  }
  const std::string pad(indent + 2, ' ');
  out += "{\n";
  for (std::size_t k = 0; k < entries_.size(); ++k) {
    const Entry& e = entries_[k];
    out += pad;
    append_escaped(out, e.key);
    out += ": ";
    std::visit(
        [&](const auto& v) {
          using T = std::decay_t<decltype(v)>;
          if constexpr (std::is_same_v<T, double>)
            out += std::isfinite(v) ? format_number(v) : "null";
          else if constexpr (std::is_same_v<T, long long>)
            out += std::to_string(v);
          else if constexpr (std::is_same_v<T, bool>)
            out += v ? "true" : "false";
          else if constexpr (std::is_same_v<T, std::string>)
            append_escaped(out, v);
          else
            v->print(out, indent + 2);
        },
        e.value);
    out += k + 1 < entries_.size() ? ",\n" : "\n";
  }
  out += std::string(indent, ' ') + "}";
}

std::string JsonObject::str() const {
  std::string out;
  print(out, 0);
  out += '\n';
  return out;
}

void JsonObject::write(const std::string& path) const {
  const std::string err = write_file_atomic(path, str());
  if (!err.empty()) throw IoError(err);
}

void JsonObject::write_root(const std::string& path, MPI_Comm comm) const {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::string err;
  if (rank == 0) err = write_file_atomic(path, str());
  raise_on_all_ranks(comm, err);
}

}  // namespace gf::io
