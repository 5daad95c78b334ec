"""Marching along a component by arc length: the solve_ivp methods of the compiled engine, the branch's segments and
events, start points, singular points, the arc length re-measured, and a trace past a grazed trim edge."""
