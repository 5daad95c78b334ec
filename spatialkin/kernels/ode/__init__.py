"""Kernels of spatialkin.ode: the compiled Runge–Kutta engine (rk), Dormand–Prince 5(4) and 8(5,3) with scipy's steps."""
