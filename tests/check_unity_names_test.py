#!/usr/bin/env python3
"""tools/check_unity_names.py on small trees made here: distinct names pass; a helper, a struct or
a constant of a comma list defined in two files of one folder fails and is named; names inside raw
string literals, in two different folders, or of member functions do not count.

    tests/check_unity_names_test.py   prints "all ok" at the end
"""

import sys

from tree_check import report, run_on_tree


def check(files: dict[str, str]):
    return run_on_tree("check_unity_names.py", files)


def main() -> int:
    failures = []
    distinct = {
        "tests/a_test.cpp": 'namespace {\nstd::string format_error_of(const std::string& t) {}\n'
                            'const char* text = R"(young = 1\nint run_text(int x) {\n)";\n}\n',
        "tests/b_test.cpp": "namespace {\nconstexpr double disc_young = 1.0, disc_poisson = 0.3;\n"
                            "int run_text(int x) {}\n}\n",
        "engine/a.cpp": "void Grid::clear() {}\nint run_text_engine(int x) {}\n",
        "engine/b.cpp": "void Particles::clear() {}\nconstexpr double young = 2.0;\n",
        "tests/c_test.cpp": "constexpr double young = 3.0;\n",
    }
    result = check(distinct)
    if result.returncode != 0 or "5 files; unity names ok" not in result.stdout:
        failures.append(f"distinct names refused: {result.stdout}{result.stderr}")

    for clash, name in [
        ("std::string error_of(const std::string& path) {}\n", "error_of"),
        ("struct BadInput {\n};\n", "BadInput"),
        ("constexpr double young = 100e6, poisson = 0.25;\n", "poisson"),
    ]:
        files = dict(distinct)
        files["tests/d_test.cpp"] = "namespace {\n" + clash + "}\n"
        files["tests/e_test.cpp"] = "namespace {\n" + clash + "}\n"
        result = check(files)
        expected = f"{name}: defined in tests/d_test.cpp, tests/e_test.cpp"
        if result.returncode != 1 or expected not in result.stdout:
            failures.append(f"{name} clash not named: {result.stdout}{result.stderr}")

    return report(failures)


if __name__ == "__main__":
    sys.exit(main())
