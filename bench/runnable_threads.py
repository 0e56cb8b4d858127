#!/usr/bin/env python3
"""How much of a run keeps the cores busy, measurable on a loaded machine: samples every 5 ms
how many of the command's threads are runnable (state R in /proc/PID/task/*/stat: running or
waiting for a core) and prints the share of samples with 0, 1 and 2 or more. Wall times on a
shared machine follow the other jobs; this share follows the program's own schedule (a phase
where one thread works while the others wait shows as "1" however loaded the machine is).
Child processes (gnuplot) are not counted.
  bench/runnable_threads.py COMMAND [ARGS...]
e.g. bench/runnable_threads.py build/apps/sysid pipeline datasets/virtual -o /tmp/report
"""
import collections
import os
import subprocess
import sys
import time


def runnable(pid):
    n = 0
    for tid in os.listdir("/proc/%d/task" % pid):
        try:
            stat = open("/proc/%d/task/%s/stat" % (pid, tid)).read()
        except OSError:
            continue  # the thread ended between the listing and the read
        if stat[stat.rindex(")") + 2] == "R":
            n += 1
    return n


def main():
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    proc = subprocess.Popen(sys.argv[1:], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    counts = collections.Counter()
    t0 = time.time()
    while proc.poll() is None:
        try:
            counts[min(runnable(proc.pid), 2)] += 1
        except OSError:
            break  # the process ended
        time.sleep(0.005)
    wall = time.time() - t0
    total = max(sum(counts.values()), 1)
    print("%s: %.1f s wall, %d samples: runnable threads 0: %.1f %%, 1: %.1f %%, >= 2: %.1f %%"
          % (os.path.basename(sys.argv[1]), wall, total, 100.0 * counts[0] / total,
             100.0 * counts[1] / total, 100.0 * counts[2] / total))
    sys.exit(proc.returncode)


if __name__ == "__main__":
    main()
