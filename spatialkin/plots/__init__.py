"""Figures drawn with matplotlib (Agg): the looper job's charts and the design study's plots. The only layer that
imports matplotlib, apart from the bench's own figures."""
