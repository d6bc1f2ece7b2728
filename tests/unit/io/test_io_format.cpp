// CSV and JSON formatting: exact text, round trip of the numbers, errors.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include "io/Csv.hpp"
#include "io/IoError.hpp"
#include "io/Json.hpp"

namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream f(p, std::ios::binary);
  std::ostringstream s;
  s << f.rdbuf();
  return s.str();
}

// A fresh folder per test, removed afterwards.
class TmpDir : public ::testing::Test {
 protected:
  void SetUp() override {
    dir = fs::temp_directory_path() /
          ("gf_test_io_format_" + std::to_string(::getpid()) + "_" +
           ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir);
  }
  void TearDown() override { fs::remove_all(dir); }
  fs::path dir;
};

using Csv = TmpDir;
using Json = TmpDir;

TEST(Format, SeventeenDigits) {
  EXPECT_EQ(gf::io::format_number(0.1), "0.10000000000000001");
  EXPECT_EQ(gf::io::format_number(1.0), "1");
  EXPECT_EQ(gf::io::format_number(-2.5e-7), "-2.4999999999999999e-07");
  // Every double survives the text round trip.
  for (double x : {1.0 / 3.0, std::nextafter(1.0, 2.0), 6.02214076e23, -1e-300, 123456.789})
    EXPECT_EQ(std::strtod(gf::io::format_number(x).c_str(), nullptr), x);
}

TEST_F(Csv, HeaderRowsAndFlush) {
  const std::string path = (dir / "sub" / "series.csv").string();  // parent is created
  gf::io::CsvWriter w(path, {"t", "ke", "n"}, PETSC_COMM_SELF);
  w.row({0.0, 0.1, 3});
  // Flushed at once: visible before the writer is closed.
  EXPECT_EQ(slurp(path), "t,ke,n\n0,0.10000000000000001,3\n");
  w.row({1.0 / 3.0, std::numeric_limits<double>::quiet_NaN(), -1e300});
  EXPECT_EQ(slurp(path),
            "t,ke,n\n0,0.10000000000000001,3\n"
            "0.33333333333333331,nan,-1.0000000000000001e+300\n");
  EXPECT_THROW(w.row({1.0, 2.0}), std::invalid_argument);
}

TEST_F(Csv, BadColumnsAndPaths) {
  EXPECT_THROW(gf::io::CsvWriter((dir / "a.csv").string(), {"t", "a,b"}, PETSC_COMM_SELF),
               std::invalid_argument);
  EXPECT_THROW(gf::io::CsvWriter((dir / "a.csv").string(), {}, PETSC_COMM_SELF),
               std::invalid_argument);
  // A path below an existing *file* cannot be created.
  fs::create_directories(dir);
  std::ofstream(dir / "file") << "x";
  EXPECT_THROW(gf::io::CsvWriter((dir / "file" / "a.csv").string(), {"t"}, PETSC_COMM_SELF),
               gf::io::IoError);
}

TEST_F(Json, OrderedNestedEscapedNull) {
  gf::io::JsonObject o;
  o.set("title", "dam \"break\"\n\\ 1")  // literal: must be a string, not a bool
      .set("cells", 1024)
      .set("big", 9007199254740993LL)
      .set("dt", 0.1)
      .set("ok", true)
      .set("bad", std::numeric_limits<double>::quiet_NaN())
      .set("inf", -std::numeric_limits<double>::infinity())
      .set("ratio", 2.0f);
  o.object("runout").set("x_front", 0.25).set("steps", std::size_t{7});
  o.object("empty");
  o.set("cells", 2048);  // replaced in place: keeps its position
  o.object("runout").set("stopped", false);
  EXPECT_EQ(o.str(),
            "{\n"
            "  \"title\": \"dam \\\"break\\\"\\n\\\\ 1\",\n"
            "  \"cells\": 2048,\n"
            "  \"big\": 9007199254740993,\n"
            "  \"dt\": 0.10000000000000001,\n"
            "  \"ok\": true,\n"
            "  \"bad\": null,\n"
            "  \"inf\": null,\n"
            "  \"ratio\": 2,\n"
            "  \"runout\": {\n"
            "    \"x_front\": 0.25,\n"
            "    \"steps\": 7,\n"
            "    \"stopped\": false\n"
            "  },\n"
            "  \"empty\": {}\n"
            "}\n");
  EXPECT_EQ(o.size(), 10u);
  EXPECT_TRUE(o.contains("empty"));
}

TEST_F(Json, ControlCharactersAndCopies) {
  gf::io::JsonObject a;
  a.set("s", std::string("a\tb\x01", 5));
  a.object("n").set("k", 1);
  gf::io::JsonObject b = a;  // deep copy
  b.object("n").set("k", 2);
  EXPECT_EQ(a.str(), "{\n  \"s\": \"a\\tb\\u0001\\u0000\",\n  \"n\": {\n    \"k\": 1\n  }\n}\n");
  gf::io::JsonObject c;
  c.set("inner", std::move(b));
  EXPECT_NE(c.str().find("\"k\": 2"), std::string::npos);
}

TEST_F(Json, AtomicWrite) {
  fs::create_directories(dir);
  const std::string path = (dir / "summary.json").string();
  gf::io::JsonObject o;
  o.set("a", 1);
  o.write(path);
  o.set("a", 2);
  o.write_root(path, PETSC_COMM_SELF);  // replaces the file
  EXPECT_EQ(slurp(path), "{\n  \"a\": 2\n}\n");
  EXPECT_FALSE(fs::exists(path + ".tmp"));
  EXPECT_THROW(o.write((dir / "missing" / "x.json").string()), gf::io::IoError);
}

}  // namespace
