"""The JSON Schema `mpile describe --json-schema` exports, against the shipped case files and
against mutants that the reader refuses: a misspelt key, a value outside its range, a choice that
is not one. Usage: check_case_schema.py MPILE CASES_DIR"""
import copy
import json
import pathlib
import subprocess
import sys
import tomllib

import jsonschema

mpile, cases = sys.argv[1], pathlib.Path(sys.argv[2])
schema = json.loads(subprocess.run([mpile, "describe", "--json-schema"], check=True,
                                   capture_output=True, text=True).stdout)
jsonschema.Draft202012Validator.check_schema(schema)
validator = jsonschema.Draft202012Validator(schema)

def merged(base, over):
    """The case as mpile reads it over its base: tables merge key by key (a table naming another
    type replaces the base's), other values replace."""
    if "type" in over and over.get("type") != base.get("type"):
        return over
    out = dict(base)
    for key, value in over.items():
        out[key] = merged(out[key], value) if isinstance(value, dict) and isinstance(
            out.get(key), dict) else value
    return out


def composed(path):
    """A case file with its `base` files (one, or a list merged in order) read under it (the
    schema describes whole cases)."""
    case = tomllib.loads(path.read_text())
    if "base" not in case:
        return case
    names = case.pop("base")
    base = {}
    for name in names if isinstance(names, list) else [names]:
        part = composed(path.parent / name)
        part.pop("base", None)
        base = merged(base, part)
    return merged(base, case)


files = [f for f in sorted(cases.rglob("*.toml"))
         if f.parent.name not in ("element_tests", "sweeps") and f.parent != cases / "base"]
for f in files:
    errors = list(validator.iter_errors(composed(f)))
    if errors:
        sys.exit(f"{f}: {[list(e.path) for e in errors]}: {errors[0].message}")

jacked = tomllib.loads((cases / "monopile" / "base" / "seed_monopile.toml").read_text())
mutants = {
    "misspelt key": lambda c: c["monopile"].update({"fricton": 0.3}),
    "friction below 0": lambda c: c["monopile"].update({"friction": -0.1}),
    "courant number above 2": lambda c: c.update({"solver": {"courant_number": 2.5}}),
    "unknown scheme": lambda c: c.update({"solver": {"scheme": "rk4"}}),
    "unknown material type": lambda c: next(iter(c["materials"].values())).update({"type": "clay"}),
    "hardening soil without e50_ref": lambda c: [m.pop("e50_ref") for m in c["materials"].values()
                                                 if m["type"] == "hardening_soil"],
    "a phase's local damping of 1": lambda c: c.update({"phases": [{"name": "a", "duration": 1.0,
                                                                    "local_damping": 1.0}]}),
}
for name, mutate in mutants.items():
    case = copy.deepcopy(jacked)
    mutate(case)
    if validator.is_valid(case):
        sys.exit(f"the schema accepts a case with a {name}")
print(f"{len(files)} case files valid; {len(mutants)} mutants refused")
