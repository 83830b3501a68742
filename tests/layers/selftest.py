#!/usr/bin/env python3
"""Self-tests of the layer checks: each one fails a small tree that breaks its rule and passes the
same tree without the break.

Why: a check that never fails is indistinguishable from a check that works. These trees pin what
each rule catches and, as important, what it must not catch (the false positives met on the real
tree: an SVG's 6.2, `CaptureTime time() const`, snprintf, 1'000, braces in strings).

The nm parts compile two or three tiny objects with g++ into temporary archives; they are skipped
where g++, ar or nm is missing.

Usage: selftest.py [-v]
"""

import os
import shutil
import subprocess
import sys
import tempfile
import textwrap
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import cxx_functions  # noqa: E402

HAVE_TOOLCHAIN = all(shutil.which(tool) for tool in ("g++", "ar", "nm"))


def write(root, files):
    for rel, text in files.items():
        path = os.path.join(root, rel)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as f:
            f.write(textwrap.dedent(text))


def run_check(script, *args):
    run = subprocess.run([sys.executable, os.path.join(HERE, script)] + list(args), capture_output=True, text=True)
    return run.returncode, run.stdout + run.stderr


def archive(tmp, name, source):
    """A static library built from one C++ source."""
    src = os.path.join(tmp, name + ".cpp")
    obj = os.path.join(tmp, name + ".o")
    lib = os.path.join(tmp, "lib" + name + ".a")
    with open(src, "w") as f:
        f.write(textwrap.dedent(source))
    subprocess.run(["g++", "-std=c++20", "-O0", "-c", src, "-o", obj], check=True)
    subprocess.run(["ar", "rcs", lib, obj], check=True)
    return lib


class CheckTestCase(unittest.TestCase):
    script = None

    def check(self, files, *args):
        with tempfile.TemporaryDirectory() as root:
            write(root, files)
            return run_check(self.script, "--root", root, *args)

    def assert_passes(self, files, *args):
        code, out = self.check(files, *args)
        self.assertEqual(code, 0, out)

    def assert_fails(self, files, *expected, args=()):
        code, out = self.check(files, *args)
        self.assertEqual(code, 1, out)
        for text in expected:
            self.assertIn(text, out)


class EstimatorPurity(CheckTestCase):
    script = "check_estimator_purity.py"
    CLEAN = """\
        #include <chrono>
        #include <cstdio>
        #include <vector>
        // No steady_clock::now() here, and no <fstream>: time(nullptr) is for drivers.
        struct Sample { long t; };
        struct Filter {
          long time() const { return t_; }   // a member called time is fine
          void take_time(long t) { t_ = t; }
          long t_ = 1'000;
        };
        int label(char* out, int n) { return std::snprintf(out, 8, "%d rand() %s", n, "::now("); }
        """

    def test_clean_tree_passes(self):
        self.assert_passes({"estimator/src/a.cpp": self.CLEAN, "estimator/core/src/b.cpp": self.CLEAN})

    def test_forbidden_headers_fail(self):
        for header in ("fstream", "sys/socket.h", "linux/can.h", "unistd.h", "thread", "ctime", "gps.h"):
            with self.subTest(header=header):
                self.assert_fails({"estimator/core/src/b.cpp": f"#include <{header}>\n" + self.CLEAN},
                                  f"estimator/core/src/b.cpp:1: includes <{header}>")

    def test_clock_reads_fail(self):
        for call in ("std::chrono::steady_clock::now()", "std::chrono::system_clock::now()", "time(nullptr)",
                     "std::time(nullptr)", "clock_gettime(0, &ts)", "std::rand()", "Clock::now()"):
            with self.subTest(call=call):
                self.assert_fails({"estimator/src/a.cpp": self.CLEAN + f"void f() {{ auto x = {call}; }}\n"},
                                  "estimator/src/a.cpp:12: ")

    @unittest.skipUnless(HAVE_TOOLCHAIN, "needs g++, ar and nm")
    def test_archives(self):
        with tempfile.TemporaryDirectory() as tmp:
            pure = archive(tmp, "pure", """\
                #include <cmath>
                #include <cstdio>
                #include <cstring>
                #include <memory>
                int label(char* out, double x) { return std::snprintf(out, 16, "%.3f", std::sqrt(x)); }
                std::unique_ptr<int> boxed(const char* s) { return std::make_unique<int>(std::strlen(s)); }
                """)
            io = archive(tmp, "io", """\
                #include <chrono>
                #include <cstdio>
                #include <ctime>
                long now_ns() { return std::chrono::steady_clock::now().time_since_epoch().count(); }
                long stamp() { timespec ts; clock_gettime(CLOCK_MONOTONIC, &ts); return ts.tv_sec; }
                void save() { std::FILE* f = std::fopen("x", "w"); std::fclose(f); }
                """)
            self.assert_passes({"estimator/src/a.cpp": self.CLEAN}, pure)
            self.assert_fails({"estimator/src/a.cpp": self.CLEAN}, f"{io}: clock_gettime", f"{io}: fopen",
                              f"{io}: std::chrono::_V2::steady_clock::now()",
                              args=(pure, io))


class SimIndependence(CheckTestCase):
    script = "check_sim_independence.py"
    TREE = {
        "estimator/include/roadload/model/longitudinal.hpp": "#pragma once\ndouble drag(double v);\n",
        "estimator/core/include/roadload/can_frame.hpp": "#pragma once\nstruct CanFrame {};\n",
        "sim/include/roadload/sim/plant.hpp": '#pragma once\n#include "roadload/can_frame.hpp"\n',
    }

    def test_core_headers_pass(self):
        self.assert_passes(dict(self.TREE, **{"sim/src/plant.cpp": '#include "roadload/sim/plant.hpp"\n'
                                                                    '#include <vector>\n'}))

    def test_estimator_header_fails(self):
        self.assert_fails(dict(self.TREE, **{"sim/src/plant.cpp": '#include "roadload/sim/plant.hpp"\n'
                                                                   '#include "roadload/model/longitudinal.hpp"\n'}),
                          "sim/src/plant.cpp:2: includes the estimator's roadload/model/longitudinal.hpp")

    def test_commented_include_passes(self):
        self.assert_passes(dict(self.TREE, **{"sim/src/plant.cpp": '// #include "roadload/model/longitudinal.hpp"\n'}))

    @unittest.skipUnless(HAVE_TOOLCHAIN, "needs g++, ar and nm")
    def test_archives(self):
        with tempfile.TemporaryDirectory() as tmp:
            estimator = archive(tmp, "estimator", """\
                namespace roadload::model { double drag(double v) { return 0.5 * v * v; } }
                """)
            own = archive(tmp, "sim_own", """\
                #include <vector>
                namespace roadload::sim { double drag(double v) { return 0.6 * v * v; } }
                double total(const std::vector<double>& v) { return roadload::sim::drag(v.at(0)); }
                """)
            borrowed = archive(tmp, "sim_borrowed", """\
                namespace roadload::model { double drag(double v); }
                double force(double v) { return roadload::model::drag(v); }
                """)
            self.assert_passes(self.TREE, "--estimator-lib", estimator, "--sim-lib", own)
            self.assert_fails(self.TREE, "roadload::model::drag(double)",
                              args=("--estimator-lib", estimator, "--sim-lib", borrowed))


class Constants(CheckTestCase):
    script = "check_constants.py"
    CLEAN = """\
        // Figure 6.2 of the report; version 5.14.2; 15.14 m; 936 wheels; 3.360001
        double char_width = 6.2;
        int x = 24 + 6.2 * n;
        """

    def test_clean_tree_passes(self):
        self.assert_passes({"tools/report.cpp": self.CLEAN,
                            # the numbers may live in tests, docs and config
                            "tests/unit/truck_test.cpp": "double mass = 36152.0;\n",
                            "config/vehicles/mnroad-truck.toml": "mass_kg = 36152\n",
                            "docs/truck.md": "36,152 kg\n"})

    def test_truck_numbers_fail(self):
        cases = {
            "double mass_kg = 36152.0;": "gross mass",
            "// mass (default 36,152 kg)": "gross mass",
            "std::array<double, 3> g{12.80, 9.25, 6.76};": "gear ratios",
            "axle(\"drive1\", 5.14, 7734.0)": "first drive axle position",
            "double cda_prior_m2 = 6.2;": "CdA",
            "\"  --cda M2  CdA's prior (default 6.2 +- 0.6)\"": "CdA",
            "std::string vin = \"1HSGSSJT8CJ536729\";": "VIN",
            "return load > 0 ? moment / load : 9.74;": "centre of gravity",
            "double torque_bias_sigma_nm = 9.74;": "EEC3 torque-rounding sigma",
            "set(ROADLOAD_MASS 36152)": "gross mass",
        }
        for line, what in cases.items():
            with self.subTest(line=line):
                name = "sim/CMakeLists.txt" if line.startswith("set(") else "sim/src/truck.cpp"
                self.assert_fails({name: self.CLEAN + line + "\n"}, f"{name}:4: the MnROAD truck's {what}")

    def test_sigma_is_not_also_the_centre_of_gravity(self):
        code, out = self.check({"estimator/a.hpp": "double torque_bias_sigma_nm = 9.74;\n"})
        self.assertEqual(out.count("belongs in"), 1, out)


class Sizes(CheckTestCase):
    script = "check_sizes.py"

    @staticmethod
    def function(lines, excuse=""):
        body = "".join(f"  x += {i};\n" for i in range(lines - 3))
        return f"{excuse}int f(int x) {{\n{body}  return x;\n}}\n"

    def test_short_files_and_functions_pass(self):
        self.assert_passes({"estimator/src/a.cpp": self.function(80), "tools/run.py": "print()\n" * 400,
                            "docs/long.md": "text\n" * 900, "tests/data/trace.log": "x\n" * 900})

    def test_long_file_fails(self):
        for name in ("tools/run.py", "scripts/build", "cmake/Warnings.cmake", "estimator/src/a.hpp"):
            with self.subTest(name=name):
                text = ("#!/bin/bash\n" if "." not in os.path.basename(name) else "") + "# x\n" * 401
                self.assert_fails({name: text}, f"{name}:1: file is")

    def test_long_function_fails(self):
        self.assert_fails({"estimator/src/a.cpp": "// Sums.\n" + self.function(81)},
                          "estimator/src/a.cpp:2: function 'f' is 81 lines (limit 80)")

    def test_long_function_that_says_why_passes(self):
        excuse = "// The table of every PGN, top to bottom.\n// Long because one table reads better than ten.\n"
        self.assert_passes({"estimator/src/a.cpp": self.function(120, excuse)})

    def test_excuse_must_be_directly_above(self):
        excuse = "// Long because of reasons.\n\n"
        self.assert_fails({"estimator/src/a.cpp": self.function(120, excuse)}, "function 'f' is 120 lines")


@unittest.skipUnless(shutil.which("clang-format-14") or shutil.which("clang-format"), "needs clang-format")
class Format(CheckTestCase):
    script = "check_format.py"

    def style(self):
        with open(os.path.join(os.path.dirname(os.path.dirname(HERE)), ".clang-format")) as f:
            return f.read()

    def test_formatted_file_passes(self):
        self.assert_passes({".clang-format": self.style(), "src/a.cpp": "int f(int x) { return x; }\n",
                            "tests/data/ugly.cpp": "int   g( ) {return 0 ;}\n"})

    def test_unformatted_file_fails(self):
        self.assert_fails({".clang-format": self.style(), "src/a.cpp": "int f(int x)   {\nreturn x;}\n"},
                          "src/a.cpp:1: needs clang-format")


class FunctionDetection(unittest.TestCase):
    """What cxx_functions finds in tricky C++: (name, first line, last line) of every body."""

    def found(self, code):
        return [(f.name, f.start_line, f.end_line) for f in cxx_functions.find_functions(textwrap.dedent(code))]

    def test_tricky_snippets(self):
        code = """\
            #define BODY(x) { return x; }
            namespace a::b {
            template <typename T, typename U = std::vector<int>>
            T tmpl(T x) requires std::integral<T> {
              if constexpr (sizeof(T) > 4) { return x; }
              return x;
            }
            struct X {
             public:
              X(int a, int b)
                  : a_(a),
                    b_{b} {
              }
              bool operator==(const X& o) const noexcept { return a_ == o.a_; }
              int& operator[](std::size_t i) { return a_; }
              auto get() const -> std::pair<int, int> { return {a_, b_}; }
              explicit operator bool() const { return a_; }
             private:
              int a_ = 0;
              int b_{0};
            } x;
            enum class E : std::uint8_t { one, two };
            const auto kTwice = [](int v) {
              return v * 2;
            };
            const int kTable[] = {1, 2, 3};
            void with_default(Config c = {}, int n = 1'000) {
              const char* s = R"x({ "}" )x";
              char q = '{';
            }
            extern "C" {
            int c_func(void) { return 0; }
            }
            TEST(Suite, Name) {
              auto l = [&]() { return 1; };
            }
            Foo::~Foo() {}
            }  // namespace a::b
            """
        self.assertEqual(self.found(code), [
            ("tmpl", 3, 7), ("X", 10, 13), ("operator==", 14, 14), ("operator[]", 15, 15), ("get", 16, 16),
            ("operator bool", 17, 17), ("kTwice", 23, 25), ("with_default", 27, 30), ("c_func", 32, 32),
            ("TEST(Suite, Name)", 34, 36), ("Foo::~Foo", 37, 37)])

    def test_conditional_compilation_reads_one_branch(self):
        code = """\
            #if A
            void f() {
            #else
            void f(int) {
            #endif
            }
            void g() {}
            """
        self.assertEqual(self.found(code), [("f", 2, 6), ("g", 7, 7)])


if __name__ == "__main__":
    unittest.main()
