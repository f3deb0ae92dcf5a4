"""A cached property without a lock.

``functools.cached_property`` takes a lock on every read until Python 3.12 (its value shadows
it only after the first read, but the first read of each property of each new object pays the
lock): making a new problem's constants (case, shear stress, slip constants, ...) spent more
time in it than in the arithmetic (``docs/performance.md``). :class:`cached` computes the value
on first read and stores it in the instance's ``__dict__`` under the property's name, where it
shadows the descriptor from then on, as ``functools.cached_property`` does; two threads reading
a new object at once may both compute it (the values are pure functions of the object).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any, Generic, TypeVar, overload

T = TypeVar("T")


class cached(Generic[T]):  # noqa: N801  (a decorator, named like functools.cached_property)
    """Decorator: a property computed once per instance (module docstring)."""

    def __init__(self, func: Callable[[Any], T]) -> None:
        self.func = func
        self.name = func.__name__
        self.__doc__ = func.__doc__

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name

    @overload
    def __get__(self, obj: None, owner: type | None = None) -> cached[T]: ...

    @overload
    def __get__(self, obj: object, owner: type | None = None) -> T: ...

    def __get__(self, obj: object | None, owner: type | None = None) -> T | cached[T]:
        if obj is None:
            return self
        value = self.func(obj)
        obj.__dict__[self.name] = value
        return value
