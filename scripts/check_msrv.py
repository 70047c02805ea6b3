#!/usr/bin/env python3
"""Checks that the kernel's declared rust-version is at least every
rust-version its locked dependencies declare (normal dependencies, as built
for a Cortex-M0+), i.e. that no dependency needs a newer compiler than the
kernel says it needs. Exits 1 and names the offender otherwise."""
import json
import subprocess
import sys


def version(v):
    return tuple(int(x) for x in v.split("."))


meta = json.loads(
    subprocess.check_output(
        ["cargo", "metadata", "--format-version", "1", "--locked",
         "--filter-platform", "thumbv6m-none-eabi"]
    )
)
packages = {p["id"]: p for p in meta["packages"]}
nodes = {n["id"]: n for n in meta["resolve"]["nodes"]}
kernel = next(p for p in meta["packages"] if p["name"] == "fixshade")
declared = version(kernel["rust_version"])

seen, todo, worst = set(), [kernel["id"]], []
while todo:
    pid = todo.pop()
    if pid in seen:
        continue
    seen.add(pid)
    for dep in nodes[pid]["deps"]:
        if any(k["kind"] is None for k in dep["dep_kinds"]):
            todo.append(dep["pkg"])
for pid in seen - {kernel["id"]}:
    p = packages[pid]
    if p.get("rust_version"):
        worst.append((version(p["rust_version"]), p["name"], p["version"]))
worst.sort(reverse=True)
print(f"fixshade declares rust-version {kernel['rust_version']}; "
      f"its {len(seen) - 1} locked dependencies need at most "
      + (".".join(map(str, worst[0][0])) + f" ({worst[0][1]} {worst[0][2]})" if worst else "nothing"))
bad = [w for w in worst if w[0] > declared]
if bad:
    for v, n, ver in bad:
        print(f"  {n} {ver} needs {'.'.join(map(str, v))}", file=sys.stderr)
    sys.exit(1)
