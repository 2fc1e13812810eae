"""What the oracle scripts (rosbag_oracle.py, mcap_oracle.py, camera_bag_oracle.py) share: checks
that are counted rather than stopping at the first, running isg, and reading an MCAP file with
npm's readers."""
import json
import pathlib
import subprocess
import sys

failures = []


def check(condition, what):
    """Records a failed check and says it; the script goes on to the others."""
    if not condition:
        failures.append(what)
        print("FAIL:", what)


def run(cmd):
    """Runs a command; its stdout, or the script ends with its stderr."""
    result = subprocess.run(cmd, capture_output=True, text=True)
    if result.returncode != 0:
        sys.exit(f"{' '.join(cmd)} failed ({result.returncode}): {result.stderr}")
    return result.stdout


def verdict():
    """The exit code: 1 with the count of failed checks, else 0."""
    if failures:
        print(f"{len(failures)} check(s) failed")
        return 1
    print("every check passed")
    return 0


def read_mcap_with_npm(mcap, oracles):
    """An MCAP file as mcap_oracle.js reads it with npm's readers (its JSON document), or the
    script ends with their error."""
    script = pathlib.Path(__file__).with_name("mcap_oracle.js")
    done = subprocess.run(["node", str(script), str(mcap), oracles], capture_output=True,
                          text=True)
    if done.returncode != 0:
        sys.exit(f"the npm readers could not read {mcap}:\n{done.stderr}")
    return json.loads(done.stdout)
