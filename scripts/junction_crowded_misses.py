#!/usr/bin/env python3
"""Classifies the crowded "segments end near" misses of benchmark_junctions --miss_dir.

Reads <miss_dir>/notjoined.csv (one row per pair of segments on two long edges of a missed vertex)
and, for each crowded missed vertex, takes its most probable pair whose eq. (6) point lies within
3 px of the vertex and says what the detector did with the pair's two segments. Usage: scripts/junction_crowded_misses.py <miss_dir>/notjoined.csv [--all] [--list]
(--all: isolated misses too; --list: the vertices of each class).
"""
import collections
import csv
import sys


def classify(rows):
    located = [r for r in rows if 0 <= float(r['location_error_px']) <= 3]
    if not located:
        return 'no pair of its segments meets within 3 px of the vertex', None
    passing = [r for r in located if r['passes'] == '1']
    if not passing:
        return 'its pairs within 3 px fail the pair test', max(located, key=lambda r: float(r['probability']))
    best = max(passing, key=lambda r: float(r['probability']))
    a, b = best['seg_a'], best['seg_b']
    ja, jb = best['taken_a_by'], best['taken_b_by']
    if ja == '-' and jb == '-':
        return 'pair passes, neither segment in a junction', best
    if ja == jb:
        return 'pair passes, both segments in one junction (shared with another true vertex)', best
    ja_segs, jb_segs = ja.split('|'), jb.split('|')
    for s, j_s, t, j_t in ((a, ja_segs, b, jb_segs), (b, jb_segs, a, ja_segs)):
        others = [x for x in j_s if x != s]
        bars = [x for x in set(j_t) if j_t.count(x) == 2]
        if j_s != ['-'] and any(x in bars for x in others) and j_t.count(t) == 1:
            return ('pair passes; one end-point in a corner W with x, the other the stem of a T '
                    'on x (two vertices on one line)'), best
    if ja == '-' or jb == '-':
        return 'pair passes, one segment in no junction, the other in a junction elsewhere', best
    return 'pair passes, the segments in two other junctions', best


def main():
    if len(sys.argv) < 2:
        sys.exit('usage: junction_crowded_misses.py <miss_dir>/notjoined.csv [--all] [--list]')
    by_vertex = collections.defaultdict(list)
    with open(sys.argv[1]) as f:
        for row in csv.DictReader(f):
            by_vertex[int(row['id'])].append(row)
    counts, members = collections.Counter(), collections.defaultdict(list)
    for vertex, rows in sorted(by_vertex.items()):
        if rows[0]['crowded'] != '1' and '--all' not in sys.argv:
            continue
        kind, best = classify(rows)
        counts[kind] += 1
        members[kind].append((vertex, rows[0]['tag'], rows[0]['frame'], best))
    for kind, n in counts.most_common():
        print(f'{n:5d}  {kind}')
        if '--list' in sys.argv:
            for vertex, tag, frame, best in members[kind]:
                extra = '' if best is None else (f" p={best['probability']} a={best['seg_a']} in {best['taken_a_by']}"
                                                 f" ({best['taken_a_px']} px) b={best['seg_b']} in {best['taken_b_by']}"
                                                 f" ({best['taken_b_px']} px)")
                print(f'         {vertex} {tag} frame {frame}{extra}')


if __name__ == '__main__':
    main()
