#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Per-stage time of elan binaries side by side (bench/results/amd-epyc/dispatch.md): each runs
`elan run scenes/X.json --steps 200 --threads 1` on jolt_pyramid, pile4k and pile10k, ROUNDS
rounds alternating the order; prints the medians of each stage's profile_ms (summed over the
200 steps, ms). Usage: stage_profile.py ROUNDS ELAN... (from the root)."""
import json, subprocess, sys, statistics
rounds, exes = int(sys.argv[1]), sys.argv[2:]
scenes = ['jolt_pyramid', 'pile4k', 'pile10k']
keys = ['bounds', 'pairs', 'collide', 'islands', 'color', 'prepare', 'solve', 'finalize', 'total']
res = {}
for r in range(rounds):
    for s in scenes:
        for exe in (exes if r % 2 == 0 else list(reversed(exes))):
            out = subprocess.run([exe, 'run', f'scenes/{s}.json', '--steps', '200', '--threads', '1'],
                                 capture_output=True, text=True, check=True).stdout
            res.setdefault((s, exe), []).append(json.loads(out)['profile_ms'])
print('| scene | binary | ' + ' | '.join(keys) + ' |')
print('| --- | --- | ' + ' | '.join('---' for _ in keys) + ' |')
for s in scenes:
    for exe in exes:
        cells = ' | '.join(f"{statistics.median(p[k] for p in res[(s, exe)]):.0f}" for k in keys)
        print(f'| {s} | {exe} | {cells} |', flush=True)
