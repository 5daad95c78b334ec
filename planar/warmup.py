"""Compile planar's kernels ahead: the workload of the background warm-up (spatialkin._lib.warm, registered when
planar is imported) and of ``python -m planar.warmup``: the six-link of the warp-knitting machine over a turn and
the Frenet module's laws (crank-slider and crank-rocker) with their driven links."""


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
    """Compile the workload in the foreground, stamp the cache, report the time (``spatialkin warmup`` compiles it
    too, beside spatialkin's). Returns 0."""
    from spatialkin._lib import warm
    warm.say_with(lambda line: None)    # (it says what it did when done)
    seconds = warm.compile_ahead(["planar.warmup"])
    echo(f"planar warmup: done in {sum(seconds.values()):.1f} s; numba's cache: {warm.cache_folder()}")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
