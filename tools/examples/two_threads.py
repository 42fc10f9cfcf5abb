#!/usr/bin/env python3
"""A benchmark, not a test: two renders in two Python threads against one alone, each on one
render thread. Scene.render releases the GIL, so on two free cores the pair takes about the time
of one (a ratio near 1; near 2 if the renders ran one after the other). The same work on the
renderer's own two threads shows what the machine's free cores allow: on a busy machine both
ratios rise together.

    PYTHONPATH=build/python /usr/bin/python3 tools/examples/two_threads.py
"""
import argparse
import pathlib
import threading
import time

import glint

ROOT = pathlib.Path(__file__).resolve().parents[2]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--scene", default=str(ROOT / "scenes" / "soft_shadows.json"))
    ap.add_argument("--spp", type=int, default=16)
    ap.add_argument("--repeats", type=int, default=3)
    a = ap.parse_args()
    scene = glint.load_scene(a.scene)
    settings = dict(width=200, height=120, spp=a.spp, threads=1)
    scene.render(**settings)  # warm: the first render maps the libraries' pages

    def one():
        t = time.perf_counter()
        scene.render(**settings)
        return time.perf_counter() - t

    def two():
        t = time.perf_counter()
        threads = [threading.Thread(target=scene.render, kwargs=settings) for _ in range(2)]
        for th in threads:
            th.start()
        for th in threads:
            th.join()
        return time.perf_counter() - t

    def own_threads():  # the same work as the pair, on the renderer's own two threads
        t = time.perf_counter()
        scene.render(**dict(settings, spp=2 * a.spp, threads=2))
        return time.perf_counter() - t

    # The best of a few runs of each: the least disturbed by other work on the machine.
    alone = min(one() for _ in range(a.repeats))
    pair = min(two() for _ in range(a.repeats))
    native = min(own_threads() for _ in range(a.repeats))
    print(f"one render on one thread:           {alone:.3f} s")
    print(f"two renders in two Python threads:  {pair:.3f} s  ({pair / alone:.2f}x one; "
          f"1 = fully parallel, 2 = serialised)")
    print(f"the same work on the renderer's own 2 threads: {native:.3f} s  ({native / alone:.2f}x "
          f"one: what this machine's free cores allow)")

if __name__ == "__main__":
    main()
