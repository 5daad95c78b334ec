"""The package version (one place: pyproject.toml reads it, spatialkin.__version__ is it)."""
__version__ = "0.2.0"
