#!/usr/bin/python3
"""tools/fuzz_cases.py --first: a run from mutant N checks exactly the mutants a whole run of the
same seed checks from N on (so a long run cut short can be finished), on the shipped case files."""
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, os.path.join(ROOT, "tools"))
import fuzz_cases  # noqa: E402

cases = []
for name in ("jacked_quick.toml", "gdp_quick.toml"):
    with open(os.path.join(ROOT, "cases", "monopile", name), encoding="utf-8") as f:
        cases.append((name, "monopile", f.read()))
whole = list(fuzz_cases.draw_mutants(cases, 7, 200))
tail = list(fuzz_cases.draw_mutants(cases, 7, 200, first=150))
assert [i for i, _ in whole] == list(range(200)), "a whole run numbers its mutants 0 to 199"
assert tail == whole[150:], "a run from 150 must check the whole run's mutants 150 to 199"
assert len({m[2] for _, m in whole}) > 150, "the mutants must differ from one another"
print("ok")
