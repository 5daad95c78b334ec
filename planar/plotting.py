"""The matplotlib figure both families draw on (kept apart from the kinematics; matplotlib imported only
when a picture is asked for)."""


def new_figure(size=(6.0, 6.0), columns=1):
    """(Figure, axes) outside pyplot's state: no backend switch, nothing accumulates, and Jupyter shows the
    Figure when a cell returns it. size in inches; columns > 1 gives an array of axes side by side."""
    from matplotlib.figure import Figure
    fig = Figure(figsize=size)
    return fig, fig.subplots(1, columns)
