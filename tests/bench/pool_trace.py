#!/usr/bin/env python3
"""Reads what pool_trace.cpp and a library built with -DDRAPE_POOL_TRACE wrote (README: "Where two
threads' wall time goes") and prints per step medians (us): wall, pool passes, serial (the caller
outside any pass, the worker idle), each thread's chunk time, the caller's wait for the worker at a
pass's end, the pool's own cost on the caller per pass (claims, publish, done counts); then per pass
site (one ThreadPool::invoke instance) the chunks' time and the wait, and the serial gaps by the pair
of sites around them.
    python3 tests/bench/pool_trace.py PREFIX [LIBDRAPE]   (PREFIX: $DRAPE_POOL_TRACE of the run)
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


def main():
    prefix = sys.argv[1]
    lib = sys.argv[2] if len(sys.argv) > 2 else None
    per_us, steps, recs = load(prefix)
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


if __name__ == '__main__':
    main()
