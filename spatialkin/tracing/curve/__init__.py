"""What a traced curve is to the user: its record and Curve, its dense output, statuses and messages, the curves
of tangency in closed form, B-splines, and the cut to the CAD-face trims."""
