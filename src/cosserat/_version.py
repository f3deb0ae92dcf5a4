"""The package version, in one place (read by pyproject.toml and the command line)."""

__version__ = "0.2.0.dev0"
