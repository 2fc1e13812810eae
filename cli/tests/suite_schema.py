#!/usr/bin/env python3
"""The suite schema (bim/schema/suite.schema.json) and `isg sweep` agree, and what `isg generate`
writes is valid for the plan and scenario schemas.

Every committed suite (eval/suites) is valid for the schema and read by `isg sweep` (as a Slurm
dry run, which checks the suite and writes the script but runs nothing). Each structural mutation
below is rejected by both. Every family's generated plan and scenario validate. Run by CTest with
Debian's python3 and python3-jsonschema.
"""
import argparse
import copy
import json
import pathlib
import subprocess
import sys
import tempfile

import jsonschema

PLAN_ID = "https://isgraphs-testbed.invalid/schema/plan.schema.json"

MUTATIONS = [
    ("no worlds", lambda s: s.pop("worlds")),
    ("empty worlds", lambda s: s.__setitem__("worlds", [])),
    ("a number as a world", lambda s: s["worlds"].append(3)),
    ("an unknown family", lambda s: s["worlds"].append({"generate": {"family": "castle"}})),
    ("a control character in a world", lambda s: s["worlds"].append("builtin:d1\x7f")),
    ("a generator without family", lambda s: s["worlds"].append({"generate": {"seed": 1}})),
    ("a fractional room count",
     lambda s: s["worlds"].append({"generate": {"family": "hall", "rooms": 2.5}})),
    ("a negative seed", lambda s: s.__setitem__("seeds", [-1])),
    ("a seed twice", lambda s: s.__setitem__("seeds", [1, 1])),
    ("a method twice", lambda s: s.__setitem__("methods", ["odometry", "odometry"])),
    ("no methods", lambda s: s.__setitem__("methods", [])),
    ("a zero duration", lambda s: s.setdefault("run", {}).__setitem__("duration", 0)),
    ("65 threads", lambda s: s.setdefault("run", {}).__setitem__("threads", 65)),
    ("a wrong version", lambda s: s.__setitem__("version", 2)),
    ("zero CPUs per task", lambda s: s.setdefault("slurm", {}).__setitem__("cpus_per_task", 0)),
    ("arrays of no task", lambda s: s.setdefault("slurm", {}).__setitem__("max_array_size", 0)),
    ("arrays of 2.5 tasks",
     lambda s: s.setdefault("slurm", {}).__setitem__("max_array_size", 2.5)),
]


def accepted_by_isg(isg, suite, work):
    path = work / "suite.json"
    path.write_text(json.dumps(suite))
    out = work / "sweep"
    subprocess.run(["rm", "-rf", str(out)], check=True)
    r = subprocess.run([isg, "sweep", str(path), "-o", str(out), "--backend", "slurm", "--dry-run"],
                       capture_output=True, text=True)
    if r.returncode not in (0, 1):
        raise SystemExit(f"isg sweep exited {r.returncode}: {r.stderr}")
    return r.returncode == 0, r.stderr


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--isg", required=True)
    parser.add_argument("--root", required=True)
    args = parser.parse_args()
    root = pathlib.Path(args.root)
    schema_dir = root / "bim" / "schema"
    suite_schema = json.loads((schema_dir / "suite.schema.json").read_text())
    jsonschema.Draft202012Validator.check_schema(suite_schema)
    suite_validator = jsonschema.Draft202012Validator(suite_schema)
    plan = json.loads((schema_dir / "plan.schema.json").read_text())
    scenario = json.loads((schema_dir / "scenario.schema.json").read_text())
    resolver = jsonschema.RefResolver.from_schema(scenario, store={PLAN_ID: plan})
    plan_validator = jsonschema.Draft202012Validator(plan)
    scenario_validator = jsonschema.Draft202012Validator(scenario, resolver=resolver)
    failures = []
    with tempfile.TemporaryDirectory() as tmp:
        work = pathlib.Path(tmp)
        suites = sorted((root / "eval" / "suites").glob("*.json"))
        if not suites:
            failures.append("no suites in eval/suites")
        for path in suites:
            suite = json.loads(path.read_text())
            for e in suite_validator.iter_errors(suite):
                failures.append(f"{path.name}: schema: {e.message}")
            # Relative world files would resolve against the temporary folder: committed suites
            # use built-ins and generators only.
            ok, err = accepted_by_isg(args.isg, suite, work)
            if not ok:
                failures.append(f"{path.name}: isg sweep: {err}")
        base = {"format": "isg.suite", "version": 1, "worlds": ["builtin:d2"], "seeds": [1],
                "methods": ["odometry"]}
        for name, mutate in MUTATIONS:
            suite = copy.deepcopy(base)
            mutate(suite)
            schema_ok = suite_validator.is_valid(suite)
            isg_ok, _ = accepted_by_isg(args.isg, suite, work)
            if schema_ok or isg_ok:
                failures.append(f"{name}: schema {'accepts' if schema_ok else 'rejects'}, "
                                f"isg sweep {'accepts' if isg_ok else 'rejects'}; both must reject")
        generated = work / "generated"
        r = subprocess.run([args.isg, "generate", "all", "-o", str(generated), "--count", "2",
                            "--closed-doors", "0.3", "--missing-walls", "0.2", "--extra-walls",
                            "0.2", "--no-verify", "-q"], capture_output=True, text=True)
        if r.returncode != 0:
            failures.append(f"isg generate: {r.stderr}")
        files = sorted(generated.glob("*.json"))
        for path in files:
            doc = json.loads(path.read_text())
            validator = scenario_validator if path.name.endswith(".asbuilt.json") else plan_validator
            for e in validator.iter_errors(doc):
                failures.append(f"{path.name}: schema: {e.message}")
    for f in failures:
        print("FAIL:", f)
    print(f"{len(suites)} suites, {len(MUTATIONS)} mutations, {len(files)} generated files checked")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
