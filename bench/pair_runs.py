#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Paired `elan run` of two elan binaries A and B (bench/results/amd-epyc/dispatch.md): each round
runs A and B back to back per scene and thread count, alternating which goes first; prints the
medians of ms_per_step and their ratio. Usage: pair_runs.py A_ELAN B_ELAN ROUNDS (from the root)."""
import json, subprocess, sys, statistics
a, b, rounds = sys.argv[1], sys.argv[2], int(sys.argv[3])
scenes = ['jolt_pyramid', 'pile4k', 'pile10k']
res = {}
for r in range(rounds):
    for s in scenes:
        for t in (1, 2):
            order = [('A', a), ('B', b)] if r % 2 == 0 else [('B', b), ('A', a)]
            for tag, exe in order:
                out = subprocess.run([exe, 'run', f'scenes/{s}.json', '--steps', '300', '--threads', str(t)],
                                     capture_output=True, text=True, check=True).stdout
                d = json.loads(out)
                res.setdefault((s, t, tag), []).append(d['ms_per_step'])
                res[(s, t, tag + 'simd')] = d.get('simd', '-')
print('| scene | threads | portable (path) ms/step | native ms/step | portable / native |')
print('| --- | --- | --- | --- | --- |')
for s in scenes:
    for t in (1, 2):
        pa, pb = statistics.median(res[(s, t, 'A')]), statistics.median(res[(s, t, 'B')])
        print(f"| {s} | {t} | {pa:.2f} ({res[(s,t,'Asimd')]}) | {pb:.2f} | {pa/pb:.2f} |", flush=True)
