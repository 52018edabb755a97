#!/usr/bin/env python3
"""Reads what pool_trace.cpp and a library built with -DDRAPE_POOL_TRACE wrote (README: "Where two
threads' wall time goes") and prints per step medians (us): wall, pool passes, serial (the caller
outside any pass, the worker idle), each thread's chunk time, the caller's wait for the worker at a
pass's end, the pool's own cost on the caller per pass (claims, publish, done counts); then per pass
site (one ThreadPool::invoke instance) the chunks' time and the wait, and the serial gaps by the pair
of sites around them.
    python3 tests/bench/pool_trace.py PREFIX [LIBDRAPE] [--steps A:B] [--solo SOLO_PREFIX]
PREFIX: $DRAPE_POOL_TRACE of the run; --steps: only the measured steps A..B-1 (Python slice); --solo: a
DRAPE_POOL_SOLO=1 run of the same scene and steps: each site's chunk time, both threads summed, over the
same site's on one core ("inflation"). Near 1 everywhere: the two threads ran at one core's speed, and what
the wall clock lost is in the serial, wait and pool columns. Above 1 at every site alike (the small
coarse passes as much as the large streaming ones): the machine ran both cores slower during that run.
"""
import collections
import glob
import re
import subprocess
import sys

import numpy as np

REC = np.dtype([('fn', '<u8'), ('publish', '<u8'), ('caller_done', '<u8'), ('all_done', '<u8'),
                ('start', '<u8', 2), ('end', '<u8', 2), ('thread', '<u4', 2)])
STEP = np.dtype([('start', '<u8'), ('end', '<u8'), ('it', '<u4'), ('pad', '<u4')])


def load(prefix):
    raw = open(glob.glob(prefix + '.steps.*')[0], 'rb').read()
    per_us = np.frombuffer(raw[:8], '<f8')[0]
    pools = [f for f in glob.glob(prefix + '.*') if '.steps.' not in f]
    return per_us, np.frombuffer(raw[8:], STEP), np.fromfile(pools[0], REC) if pools else None


def load_steps(prefix, first, last):
    per_us, steps, recs = load(prefix)
    return per_us, steps[first:last], recs


def site_chunks(per_us, steps, recs):
    """Chunk time (us, both threads) per pass site over the given steps, and their wall time."""
    site = collections.defaultdict(float)
    for s in steps:
        r = recs[np.searchsorted(recs['publish'], s['start']):np.searchsorted(recs['publish'], s['end'])]
        d = (r['end'] - r['start']).astype(float).sum(axis=1) / per_us
        for fn, t in zip(r['fn'], d):
            site[int(fn)] += t
    return site, float((steps['end'] - steps['start']).sum()) / per_us


def main():
    args = sys.argv[1:]
    first, last, solo = None, None, None
    if '--steps' in args:
        k = args.index('--steps')
        a, b = args[k + 1].split(':')
        first, last = (int(a) if a else None), (int(b) if b else None)
        del args[k:k + 2]
    if '--solo' in args:
        k = args.index('--solo')
        solo = args[k + 1]
        del args[k:k + 2]
    prefix = args[0]
    lib = args[1] if len(args) > 1 else None
    per_us, steps, recs = load_steps(prefix, first, last)
    us = lambda t: t.astype(float) / per_us
    wall = us(steps['end'] - steps['start'])
    print(f'{prefix}: {len(steps)} steps, iterations a step (median) {np.median(steps["it"]):.0f}, '
          f'wall median {np.median(wall):.1f} us')
    if recs is None:
        return
    pub = recs['publish']
    cols = collections.defaultdict(list)
    site = collections.defaultdict(lambda: np.zeros(4))  # passes, caller chunk, worker chunk, wait
    gap = collections.defaultdict(float)
    for s, w in zip(steps, wall):
        r = recs[np.searchsorted(pub, s['start']):np.searchsorted(pub, s['end'])]
        d = us(r['end'] - r['start'])
        pw = us(r['all_done'] - r['publish'])
        wait = us(r['all_done'] - r['caller_done'])
        mine = r['thread'] == 0
        cwork = (d * mine).sum()
        cols['passes'].append(len(r))
        cols['serial'].append(w - pw.sum())
        cols['caller chunks'].append(cwork)
        cols['worker chunks'].append((d * ~mine).sum())
        cols['caller wait'].append(wait.sum())
        cols['pool cost (caller)'].append(us(r['caller_done'] - r['publish']).sum() - cwork)
        cols['passes the caller ran alone'].append(int(mine.all(axis=1).sum()))
        prev, t = 'step start', s['start']
        for k in range(len(r)):
            fn = int(r['fn'][k])
            site[fn] += (1, (d[k] * mine[k]).sum(), (d[k] * ~mine[k]).sum(), wait[k])
            gap[(prev, fn)] += us(np.array(r['publish'][k] - t))
            prev, t = fn, r['all_done'][k]
        gap[(prev, 'step end')] += us(np.array(s['end'] - t))
    for k, v in cols.items():
        print(f'  {k:28s} median {np.median(v):10.1f}  quartiles {np.percentile(v, 25):10.1f} {np.percentile(v, 75):10.1f}')
    names = {}

    def name(fn):
        if not isinstance(fn, int):
            return fn
        if fn not in names:
            names[fn] = hex(fn)
            if lib:
                out = subprocess.run(['addr2line', '-f', '-C', '-e', lib, hex(fn)], capture_output=True, text=True).stdout
                f, line = (out.split('\n') + ['', ''])[:2]
                f = f.replace('drape::', '').replace('(anonymous namespace)::', '')
                while re.search(r'\([^()]*\)', f):  # drop the parameter lists
                    f = re.sub(r'\([^()]*\)', '', f)
                names[fn] = f.replace('void ThreadPool::invoke<', '').replace('ThreadPool::', '')[:90]
        return names[fn]

    n = len(steps)
    print('  per step, by site: passes, caller chunks us, worker chunks us, caller wait us')
    for fn, a in sorted(site.items(), key=lambda x: -x[1][1] - x[1][2]):
        print(f'    {a[0] / n:6.1f} {a[1] / n:9.1f} {a[2] / n:9.1f} {a[3] / n:8.1f}  {name(fn)}')
    print('  serial gaps per step (us), by the sites before and after')
    for (a, b), v in sorted(gap.items(), key=lambda x: -x[1])[:8]:
        print(f'    {v / n:8.2f}  {name(a)} -> {name(b)}')
    if solo:
        two = {fn: a[1] + a[2] for fn, a in site.items()}  # both threads' chunks, as summed above
        one, wall_one = site_chunks(*load_steps(solo, first, last))
        print(f'  against {solo} (one core, same steps): wall {wall_one / wall.sum():.2f}x faster on two threads; '
              f'chunk time summed {sum(two.values()) / sum(one.values()):.2f}x one core\'s')
        print('  per site: chunk us per step, two threads summed / one core, inflation')
        for fn in sorted(one, key=lambda f: -one[f])[:12]:
            print(f'    {two.get(fn, 0.0) / n:9.1f} {one[fn] / n:9.1f} {two.get(fn, 0.0) / one[fn]:6.2f}  {name(fn)}')


if __name__ == '__main__':
    main()
