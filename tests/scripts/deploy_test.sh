#!/usr/bin/env bash
# deploy/slurm and deploy/k8s without a cluster (docs/cluster.md; `make cluster-check` runs the
# Slurm ones on a real one-node Slurm): the commands each writes for a shard and for the merge,
# against a stand-in glarecam that prints its arguments; the refusals (not an array task, an
# array other than 0..SHARDS-1, a missing shard); the manifests: an Indexed Job whose SHARDS is
# its completions, and the shell they run.
set -euo pipefail
root="$(cd "$(dirname "$0")/../.." && pwd)"
fail() { echo "FAIL: $*" >&2; exit 1; }
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
printf '#!/bin/sh\necho "glarecam $*"\n' > "$tmp/glarecam"
chmod +x "$tmp/glarecam"
export GLARECAM="$tmp/glarecam"

array="$root/deploy/slurm/hazard-array.sbatch"
out=$(env SLURM_ARRAY_TASK_ID=2 SLURM_ARRAY_TASK_COUNT=4 SLURM_ARRAY_TASK_MIN=0 \
      SLURM_ARRAY_TASK_MAX=3 bash "$array" city.geojson p.json 2027 4 /o 2>/dev/null)
[[ $out == "glarecam hazard city.geojson --profile p.json --year 2027 --screen --shard 2/4 --threads 1 --no-progress --out /o/shard-2" ]] \
  || fail "shard command: $out"
out=$(env SLURM_ARRAY_TASK_ID=0 SLURM_ARRAY_TASK_COUNT=3 SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_MAX=2 \
      SLURM_CPUS_PER_TASK=4 SCENE=s.geojson PROFILE=p.json YEAR=2030 OUT=/x MAX_DISTANCE=800 \
      bash "$array" 2>/dev/null)
[[ $out == "glarecam hazard s.geojson --profile p.json --year 2030 --screen --shard 0/3 --threads 4 --no-progress --out /x/shard-0 --max-distance 800" ]] \
  || fail "shard command from the environment: $out"
set +e
env -u SLURM_ARRAY_TASK_ID bash "$array" a b 2027 4 /o >/dev/null 2>&1
[[ $? -eq 2 ]] || fail "outside an array task: not exit 2"
env SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_MAX=4 bash "$array" a b 2027 4 /o \
  >/dev/null 2>&1
[[ $? -eq 2 ]] || fail "array 1-4 for 4 shards: not exit 2"
env SLURM_ARRAY_TASK_ID=1 bash "$array" a b 2027 0 /o >/dev/null 2>&1
[[ $? -eq 2 ]] || fail "SHARDS 0: not exit 2"
env SLURM_ARRAY_TASK_ID=2 SLURM_ARRAY_TASK_COUNT=2 SLURM_ARRAY_TASK_MIN=1 SLURM_ARRAY_TASK_MAX=2 \
  bash "$array" a b 2027 "" /o >/dev/null 2>&1
[[ $? -eq 2 ]] || fail "SHARDS from the count of an array 1-2: not exit 2"
set -e
# EXTRA_ARGS: further options, split at blanks, after the others; never --shard, --out, ...
out=$(env SLURM_ARRAY_TASK_ID=1 SLURM_ARRAY_TASK_COUNT=2 SLURM_ARRAY_TASK_MIN=0 SLURM_ARRAY_TASK_MAX=1 \
      EXTRA_ARGS=' --step-s 300  --criteria lai,ch ' bash "$array" a b 2027 2 /o 2>/dev/null)
[[ $out == "glarecam hazard a --profile b --year 2027 --screen --shard 1/2 --threads 1 --no-progress --out /o/shard-1 --step-s 300 --criteria lai,ch" ]] \
  || fail "EXTRA_ARGS: $out"
out=$(cd "$tmp" && touch x1 x2 && env SLURM_ARRAY_TASK_ID=0 EXTRA_ARGS='--models x*' \
      bash "$array" a b 2027 1 /o 2>/dev/null)
[[ $out == *" --models x*" ]] || fail "EXTRA_ARGS globbed: $out"
for bad in '--out /elsewhere' '--shard 0/1' '--threads=8' '--no-progress'; do
  set +e
  env SLURM_ARRAY_TASK_ID=0 EXTRA_ARGS="$bad" bash "$array" a b 2027 1 /o >/dev/null 2>&1
  status=$?
  set -e
  [[ $status -eq 2 ]] || fail "EXTRA_ARGS '$bad': exit $status, not 2"
done
# A rerun of one shard (--array=5) with SHARDS given.
out=$(env SLURM_ARRAY_TASK_ID=5 SLURM_ARRAY_TASK_COUNT=1 SLURM_ARRAY_TASK_MIN=5 SLURM_ARRAY_TASK_MAX=5 \
      bash "$array" a b 2027 8 /o 2>/dev/null)
[[ $out == *"--shard 5/8 "* ]] || fail "a rerun of shard 5: $out"

merge="$root/deploy/slurm/merge.sbatch"
mkdir -p "$tmp/o/shard-0" "$tmp/o/shard-1"
echo '{}' > "$tmp/o/shard-0/shard.json"
echo '{}' > "$tmp/o/shard-1/shard.json"
out=$(env -u SCENE -u MERGED bash "$merge" 2 "$tmp/o" 2>/dev/null)
[[ $out == "glarecam hazard merge $tmp/o/shard-0 $tmp/o/shard-1 --out $tmp/o/merged" ]] || fail "merge: $out"
out=$(env SCENE=/in/city.geojson MERGED=/m bash "$merge" 2 "$tmp/o" 2>/dev/null)
[[ $out == "glarecam hazard merge $tmp/o/shard-0 $tmp/o/shard-1 --out /m --scene /in/city.geojson" ]] \
  || fail "merge with SCENE and MERGED: $out"
set +e
bash "$merge" 3 "$tmp/o" >/dev/null 2>&1
[[ $? -eq 2 ]] || fail "merge with a shard missing: not exit 2"
set -e

# The manifests: parsed, and the shell they run, as Kubernetes hands it over ($$ is $).
if python3 -c 'import yaml' 2>/dev/null; then
  python3 - "$root/deploy/k8s" "$tmp" <<'PY'
import os, subprocess, sys, yaml
k8s, tmp = sys.argv[1], sys.argv[2]
def load(name):
    with open(os.path.join(k8s, name)) as f:
        return yaml.safe_load(f)
pvc, shards, merge = load("pvc.yaml"), load("hazard-shards-job.yaml"), load("merge-job.yaml")
assert pvc["kind"] == "PersistentVolumeClaim" and "ReadWriteMany" in pvc["spec"]["accessModes"]
for job in (shards, merge):
    assert job["apiVersion"] == "batch/v1" and job["kind"] == "Job", job["metadata"]["name"]
    pod = job["spec"]["template"]["spec"]
    assert pod["restartPolicy"] == "Never"
    assert pod["volumes"][0]["persistentVolumeClaim"]["claimName"] == pvc["metadata"]["name"]
spec = shards["spec"]
assert spec["completionMode"] == "Indexed", spec
env = {e["name"]: e["value"] for e in spec["template"]["spec"]["containers"][0]["env"]}
assert int(env["SHARDS"]) == spec["completions"], "SHARDS is not completions"
merge_env = {e["name"]: e["value"] for e in merge["spec"]["template"]["spec"]["containers"][0]["env"]}
assert merge_env["SHARDS"] == env["SHARDS"] and merge_env["OUT"] == env["OUT"], "merge's SHARDS/OUT"
def shell(job, extra):
    container = job["spec"]["template"]["spec"]["containers"][0]
    script = container["args"][0].replace("$$", "$")
    run_env = dict(os.environ, PATH=tmp + ":" + os.environ["PATH"], **extra)
    return subprocess.run(container["command"] + [script], env=run_env, capture_output=True, text=True)
got = shell(shards, dict(env, JOB_COMPLETION_INDEX="5")).stdout.strip()
want = (f"glarecam hazard {env['SCENE']} --profile {env['PROFILE']} --year {env['YEAR']} --screen "
        f"--shard 5/{env['SHARDS']} --threads {env['THREADS']} --no-progress --out {env['OUT']}/shard-5")
assert got == want, got
got = shell(shards, dict(env, JOB_COMPLETION_INDEX="0", EXTRA_ARGS="--step-s 300 --models *")).stdout.strip()
assert got == want.replace("--shard 5/", "--shard 0/").replace(
    "--no-progress --out", "--no-progress --step-s 300 --models * --out").replace("shard-5", "shard-0"), got
got = shell(merge, {"SHARDS": "2", "OUT": os.path.join(tmp, "o")}).stdout.strip()
assert got == f"glarecam hazard merge {tmp}/o/shard-0 {tmp}/o/shard-1 --out {tmp}/o/merged", got
assert shell(merge, {"SHARDS": "3", "OUT": os.path.join(tmp, "o")}).returncode == 2
PY
  echo "deploy: slurm scripts and k8s manifests as documented"
else
  echo "deploy: slurm scripts as documented (no python3-yaml: manifests not parsed)"
fi
