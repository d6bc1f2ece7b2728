#pragma once
// A small ordered JSON object writer for summary.json and similar run reports.
//
// Keys keep their insertion order (setting an existing key replaces its value in place), so
// a report reads in the order the code fills it and diffs cleanly between runs. Numbers are
// written with 17 significant digits (exact round trip, as in the CSV files); NaN and
// infinities, which JSON cannot represent, are written as null. Strings are escaped per
// RFC 8259 and otherwise passed through as UTF-8.
//
//   io::JsonObject s;
//   s.set("cells", 1024).set("t_end", 0.5).set("converged", true);
//   s.object("runout").set("x_front", 0.31);
//   s.write_root(dir + "/summary.json", grid.comm());
#include <petscsys.h>

#include <concepts>
#include <memory>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace gf::io {

class JsonObject {
 public:
  JsonObject() = default;
  JsonObject(const JsonObject& o);
  JsonObject& operator=(const JsonObject& o);
  JsonObject(JsonObject&&) noexcept = default;
  JsonObject& operator=(JsonObject&&) noexcept = default;

  JsonObject& set(const std::string& key, double v);
  JsonObject& set(const std::string& key, long long v);
  JsonObject& set(const std::string& key, bool v);
  JsonObject& set(const std::string& key, std::string v);
  // Without this overload a string literal would convert to bool.
  JsonObject& set(const std::string& key, const char* v) { return set(key, std::string(v)); }
  JsonObject& set(const std::string& key, JsonObject v);
  // Other integer and floating types (int, size_t, float...): without these, set(key, 3)
  // would be ambiguous between the double and long long overloads.
  template <std::integral T>
    requires(!std::same_as<T, bool>)
  JsonObject& set(const std::string& key, T v) {
    return set(key, static_cast<long long>(v));
  }
  template <std::floating_point T>
  JsonObject& set(const std::string& key, T v) {
    return set(key, static_cast<double>(v));
  }

  // The nested object under `key`, created empty (at the end) if absent; replaces a
  // non-object value. The reference stays valid until `key` is set again or this object dies.
  JsonObject& object(const std::string& key);

  bool contains(const std::string& key) const;
  std::size_t size() const { return entries_.size(); }

  // Pretty-printed text, two-space indent, ending in a newline.
  std::string str() const;

  // Writes str() to `path` atomically (tmp file, then rename). Not collective: call it on
  // one rank. Throws IoError.
  void write(const std::string& path) const;
  // Collective on `comm`: rank 0 writes, every rank throws IoError if that failed.
  void write_root(const std::string& path, MPI_Comm comm = PETSC_COMM_WORLD) const;

 private:
  using Value = std::variant<double, long long, bool, std::string, std::unique_ptr<JsonObject>>;
  struct Entry {
    std::string key;
    Value value;
  };
  Value* find(const std::string& key);
  JsonObject& put(const std::string& key, Value v);
  void print(std::string& out, int indent) const;

  std::vector<Entry> entries_;
};

}  // namespace gf::io
