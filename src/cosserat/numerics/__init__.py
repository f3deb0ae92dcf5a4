"""Compiled numerical kernels (numba): the Radau IIA integrator and the models' shooting kernels."""
