#!/usr/bin/env python3
"""The JSON Schemas in bim/schema and the parser behind `isg check` must agree.

Every reference plan and scenario is valid for both. Each structural mutation below is rejected
by both (the schema cannot express semantic rules, so those are only checked by the C++ tests).
Unknown fields are accepted by both. Run by CTest with Debian's python3 and python3-jsonschema.
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


def validators(schema_dir):
    plan = json.loads((schema_dir / "plan.schema.json").read_text())
    scenario = json.loads((schema_dir / "scenario.schema.json").read_text())
    jsonschema.Draft202012Validator.check_schema(plan)
    jsonschema.Draft202012Validator.check_schema(scenario)
    # Resolve the scenario's reference to the plan schema locally: nothing is fetched.
    resolver = jsonschema.RefResolver.from_schema(scenario, store={PLAN_ID: plan})
    return (jsonschema.Draft202012Validator(plan),
            jsonschema.Draft202012Validator(scenario, resolver=resolver))


def walls(doc):
    return doc["levels"][0]["walls"]


def doors(doc):
    return doc["levels"][0]["doors"]


def rooms(doc):
    return doc["levels"][0]["rooms"]


def setter(path, value):
    def mutate(doc):
        node = doc
        for key in path[:-1]:
            node = node[key]
        node[path[-1]] = value
    return mutate


def deleter(path):
    def mutate(doc):
        node = doc
        for key in path[:-1]:
            node = node[key]
        del node[path[-1]]
    return mutate


PLAN_MUTATIONS = {
    "wrong format": setter(["format"], "isg.blueprint"),
    "version 2": setter(["version"], 2),
    "no levels": setter(["levels"], []),
    "missing thickness": deleter(["levels", 0, "walls", 0, "thickness"]),
    "thickness as a string": setter(["levels", 0, "walls", 0, "thickness"], "0.3"),
    "zero thickness": setter(["levels", 0, "walls", 0, "thickness"], 0),
    "three-number point": setter(["levels", 0, "walls", 0, "end"], [1, 2, 3]),
    "zero level height": setter(["levels", 0, "height"], 0),
    "negative base": setter(["levels", 0, "walls", 0, "base"], -0.1),
    "door without wall": deleter(["levels", 0, "doors", 0, "wall"]),
    "door width zero": setter(["levels", 0, "doors", 0, "width"], 0),
    "door with three rooms": setter(["levels", 0, "doors", 0, "rooms"], ["R1", "R2", "outside"]),
    "two-vertex outline": setter(["levels", 0, "rooms", 0, "outline"], [[0, 0], [1, 0]]),
    "room called outside": setter(["levels", 0, "rooms", 0, "id"], "outside"),
    "empty id": setter(["levels", 0, "walls", 0, "id"], ""),
    "window without sill": deleter(["levels", 0, "windows", 0, "sill"]),
    "window below its wall's base": setter(["levels", 0, "windows", 0, "sill"], -0.1),
    "window height zero": setter(["levels", 0, "windows", 0, "height"], 0),
    "window height as a string": setter(["levels", 0, "windows", 0, "height"], "1.2"),
}

SCENARIO_MUTATIONS = {
    "wrong format": setter(["format"], "isg.scene"),
    "no plan": deleter(["plan"]),
    "negative seed": setter(["seed"], -1),
    "fractional seed": setter(["seed"], 1.5),
    "start with room and pose": setter(["robot", "start"], {"room": "R1", "pose": [1, 1, 0]}),
    "unknown route": setter(["robot", "route"], "spiral"),
    "zero speed": setter(["robot", "speed"], 0),
    "gait at 50 Hz": setter(["robot", "gait"], {"frequency_hz": 50}),
    "lidar rate 40": setter(["lidar", "rate_hz"], 40),
    "dropout 1": setter(["lidar", "dropout"], 1.0),
    "mount of three": setter(["lidar", "mount"], [0, 0, 0.25]),
    "negative odometry noise": setter(["odometry", "translation_noise"], -0.1),
    "imu at 5 Hz": setter(["imu", "rate_hz"], 5),
    "imu mount of three": setter(["imu", "mount"], [0, 0, 0.1]),
    "negative gyroscope noise": setter(["imu", "gyroscope_noise_density"], -1e-4),
    "clutter sphere": setter(["as_built", "clutter", 0, "shape"], "sphere"),
    "clutter zero size": setter(["as_built", "clutter", 0, "size"], [1, 0, 1]),
    "extra wall without thickness": deleter(["as_built", "extra_walls", 0, "thickness"]),
    "door closed twice": setter(["as_built", "closed_doors"], ["D1", "D1"]),
}


def isg_accepts(isg, doc, name, plan_doc=None):
    with tempfile.TemporaryDirectory() as tmp:
        tmp = pathlib.Path(tmp)
        if plan_doc is not None:
            (tmp / "plan.json").write_text(json.dumps(plan_doc))
        (tmp / name).write_text(json.dumps(doc))
        result = subprocess.run([isg, "check", name], cwd=tmp, capture_output=True, text=True)
        if result.returncode not in (0, 1):
            raise SystemExit(f"isg check exited {result.returncode}: {result.stderr}")
        return result.returncode == 0, result.stderr.strip()


def main():
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--isg", required=True)
    parser.add_argument("--root", required=True, type=pathlib.Path)
    args = parser.parse_args()
    args.isg = str(pathlib.Path(args.isg).resolve())
    plan_v, scenario_v = validators(args.root / "bim" / "schema")
    failures = []
    checked = 0

    plans_dir = args.root / "worlds" / "plans"
    for path in sorted(plans_dir.glob("*.json")):
        doc = json.loads(path.read_text())
        validator = scenario_v if doc.get("format") == "isg.scenario" else plan_v
        errors = list(validator.iter_errors(doc))
        if errors:
            failures.append(f"{path.name}: schema rejects a reference file: {errors[0].message}")
        checked += 1

    base_plan = json.loads((plans_dir / "d1.json").read_text())
    base_scenario = json.loads((plans_dir / "d1.asbuilt.json").read_text())
    base_scenario["plan"] = "plan.json"
    base_scenario["robot"] = {"level": "L0", "start": {"room": "R1"}, "route": "tour", "speed": 0.5}
    base_scenario["lidar"] = {"rate_hz": 10, "dropout": 0.0, "mount": [0, 0, 0.25, 0, 0, 0]}
    base_scenario["odometry"] = {"rate_hz": 50, "translation_noise": 0.02}
    base_scenario["imu"] = {"rate_hz": 400, "mount": [0.1, 0, 0.05, 0, 0, 0], "gravity": 9.80665}
    base_scenario["as_built"]["extra_walls"] = [{"start": [1, 1], "end": [1, 2], "thickness": 0.1}]
    base_plan["levels"][0]["walls"][0]["colour"] = "grey"  # unknown fields: fine for both
    base_plan["levels"][0]["windows"] = [
        {"id": "WIN1", "wall": "W1", "offset": 3.0, "width": 1.2, "sill": 0.9, "height": 1.2}]

    for label, validator, base, name, mutations in (
        ("plan", plan_v, base_plan, "plan.json", PLAN_MUTATIONS),
        ("scenario", scenario_v, base_scenario, "scenario.json", SCENARIO_MUTATIONS),
    ):
        plan_doc = None if name == "plan.json" else base_plan
        ok, err = isg_accepts(args.isg, base, name, plan_doc)
        if not ok or list(validator.iter_errors(base)):
            failures.append(f"base {label} is not valid for both: {err}")
        for what, mutate in mutations.items():
            doc = copy.deepcopy(base)
            mutate(doc)
            schema_rejects = bool(list(validator.iter_errors(doc)))
            parser_accepts, err = isg_accepts(args.isg, doc, name, plan_doc)
            checked += 1
            if not schema_rejects:
                failures.append(f"{label} / {what}: the schema accepts it, the parser says: {err}")
            if parser_accepts:
                failures.append(f"{label} / {what}: the parser accepts it, the schema rejects it")

    for failure in failures:
        print("MISMATCH:", failure)
    print(f"{checked - len(failures)} passed, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
