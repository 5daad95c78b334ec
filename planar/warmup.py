"""Compile planar's kernels ahead: the workload of the background warm-up (spatialkin._lib.warm, registered when
planar is imported) and of ``python -m planar.warmup``: the six-link of the warp-knitting machine over a turn and
the Frenet module's laws (crank-slider and crank-rocker) with their driven links."""
import time


def run():
    """Call the workload (each kernel it reaches compiled, or loaded from the cache)."""
    import numpy as np

    import planar
    angles = np.linspace(0.0, 2 * np.pi, 361)
    solution = planar.examples.fnf_sixbar().solve(angles)
    for joint in solution.linkage.moving:
        solution.acceleration(joint)
    s = np.linspace(0.0, 2 * np.pi, 73)
    for law in (planar.CrankSlider(1.0, 0.2, 3.0), planar.CrankRocker(1.0, 3.0)):
        link = planar.DrivenLink(law, omega=1.0)
        link.position(s, 1.5), link.velocity(s, 1.5), link.acceleration(s, 1.5)


def main(echo=print):
    """Compile the workload in the foreground, stamp the cache, report the time. Returns 0."""
    from spatialkin._lib import jit, warm
    warm.stop_background()              # (started at import on a cold cache: this does its work)
    warm.drop_stale("planar.warmup")   # (a kernel module changed since the last warm-up: all of them compile again)
    warm.say_with(lambda line: None)    # (it says what it did when done)
    jit.use(jit.COMPILED)
    t0 = time.perf_counter()
    run()
    warm.write_stamp(__name__ if __name__ != "__main__" else "planar.warmup")
    echo(f"planar warmup: done in {time.perf_counter() - t0:.1f} s; numba's cache: {warm.cache_folder()}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
