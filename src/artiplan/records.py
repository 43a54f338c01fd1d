"""``dataclass``: the standard library's decorator, built without compiling code at import.

On Python < 3.13 ``dataclasses.dataclass`` writes the source of ``__init__``, ``__repr__``,
``__eq__``, ``__hash__``, ``__setattr__`` and ``__delattr__`` and compiles each: ~0.6 ms a frozen
class, which made up half of the start-up of ``artiplan plan`` (about 100 classes on its path).
This decorator gives the same classes: ``dataclasses`` itself collects the fields (so
``dataclasses.fields``, ``replace``, ``asdict`` and ``is_dataclass`` work as ever) and adds
``__match_args__`` and ``__slots__``; ``__init__`` is compiled as the standard library's (the one
method whose speed counts), but only when first used, so a class a run never builds costs no
compile; the other methods are closures that do what the generated ones do (same results,
hashes, reprs and errors; tests/test_records.py compares the two). mypy sees
``dataclasses.dataclass`` itself.

Supported: ``init``, ``repr``, ``eq``, ``frozen``, ``match_args``, ``slots``, fields with
``default``, ``default_factory``, ``repr``, ``hash``, ``compare``, ``metadata``, and
``__post_init__``. Anything else (``order``, ``unsafe_hash``, ``kw_only``, ``init=False`` fields,
``ClassVar``/``InitVar`` pseudo-fields, a dataclass among the bases) is refused with a
``TypeError``: use ``dataclasses.dataclass`` for such a class.
"""

from __future__ import annotations

import _thread
import abc
import dataclasses
import inspect
from collections.abc import Callable
from dataclasses import MISSING, Field, FrozenInstanceError, field
from operator import attrgetter
from typing import TYPE_CHECKING, Any, TypeVar

__all__ = ["dataclass", "field"]

T = TypeVar("T")


class _Factory:
    """The default of a parameter whose field has a ``default_factory`` (shown as the
    standard library shows it)."""

    def __repr__(self) -> str:
        return "<factory>"


_FACTORY = _Factory()
_UNSUPPORTED = ("order", "unsafe_hash", "kw_only", "weakref_slot")


def _dataclass(cls: type[T] | None = None, /, *, init: bool = True, repr: bool = True,
               eq: bool = True, frozen: bool = False, match_args: bool = True,
               slots: bool = False, **unsupported: Any) -> Any:
    """``dataclasses.dataclass`` for the options in the module docstring."""
    if any(unsupported.get(k) for k in _UNSUPPORTED) or set(unsupported) - set(_UNSUPPORTED):
        raise TypeError(f"artiplan.records.dataclass does not support {sorted(unsupported)}: "
                        "use dataclasses.dataclass")

    def wrap(c: type[T]) -> type[T]:
        return _process(c, init, repr, eq, frozen, match_args, slots)

    return wrap if cls is None else wrap(cls)


def _process(cls: type[T], init: bool, repr_: bool, eq: bool, frozen: bool, match_args: bool,
             slots: bool) -> type[T]:
    if any(dataclasses.is_dataclass(b) for b in cls.__mro__[1:]):
        raise TypeError(f"{cls.__name__}: a dataclass base is not supported here: use "
                        "dataclasses.dataclass")
    own = dict(cls.__dict__)
    class_hash = own.get("__hash__", MISSING)
    explicit_hash = not (class_hash is MISSING or (class_hash is None and "__eq__" in own))
    needs_doc = not cls.__doc__
    if needs_doc:
        cls.__doc__ = "?"  # keeps dataclasses from writing one before __init__ exists
    # Fields, __dataclass_fields__, __match_args__, __slots__: the standard library's.
    cls = dataclasses.dataclass(cls, init=False, repr=False, eq=False, match_args=match_args,
                                slots=slots)
    params = cls.__dataclass_params__  # type: ignore[attr-defined]
    params.init, params.repr, params.eq, params.frozen = init, repr_, eq, frozen
    fields = dataclasses.fields(cls)  # type: ignore[arg-type]
    if len(fields) != len(cls.__dataclass_fields__):  # type: ignore[attr-defined]
        raise TypeError(f"{cls.__name__}: ClassVar/InitVar pseudo-fields are not supported "
                        "here: use dataclasses.dataclass")
    if any(f.kw_only is True or not f.init for f in fields):
        raise TypeError(f"{cls.__name__}: kw_only and init=False fields are not supported "
                        "here: use dataclasses.dataclass")
    if init:
        _check_defaults(fields)
        if "__init__" not in own:
            cls.__init__ = _LazyInit(cls, fields, frozen)  # type: ignore[method-assign,assignment]
    if repr_ and "__repr__" not in own:
        _attach(cls, _repr_fn(tuple(f.name for f in fields if f.repr)))
    if eq and "__eq__" not in own:
        _attach(cls, _eq_fn(_key(tuple(f.name for f in fields if f.compare))))
    if frozen:
        for fn in _frozen_fns(cls, tuple(f.name for f in fields)):
            if fn.__name__ in own:
                raise TypeError(f"Cannot overwrite attribute {fn.__name__} in class "
                                f"{cls.__name__}")
            _attach(cls, fn)
        if slots:
            state: dict[str, Callable[..., Any]] = {"__getstate__": _getstate,
                                                    "__setstate__": _setstate}
            for name, method in state.items():
                if name not in own:
                    setattr(cls, name, method)
    if eq and not explicit_hash:
        if frozen:
            hashed = tuple(f.name for f in fields if (f.compare if f.hash is None else f.hash))
            _attach(cls, _hash_fn(_key(hashed)))
        else:
            cls.__hash__ = None  # type: ignore[assignment]
    if needs_doc:
        try:
            text_sig = str(inspect.signature(cls)).replace(" -> None", "")
        except (TypeError, ValueError):
            text_sig = ""
        cls.__doc__ = cls.__name__ + text_sig
    abc.update_abstractmethods(cls)
    return cls


def _attach(cls: type, fn: Callable[..., Any]) -> None:
    fn.__qualname__ = f"{cls.__qualname__}.{fn.__name__}"
    setattr(cls, fn.__name__, fn)


def _check_defaults(fields: tuple[Field[Any], ...]) -> None:
    seen_default = False
    for f in fields:
        if f.default is not MISSING or f.default_factory is not MISSING:
            seen_default = True
        elif seen_default:
            raise TypeError(f"non-default argument {f.name!r} follows default argument")


class _LazyInit:
    """A class's ``__init__`` until it is first used (its first instance, or a read such as
    ``inspect.signature``): compiled then, as the standard library writes it (its speed
    counts), and put in its place. Classes a run never builds cost no compile."""

    __slots__ = ("cls", "fields", "frozen")

    def __init__(self, cls: type, fields: tuple[Field[Any], ...], frozen: bool) -> None:
        self.cls, self.fields, self.frozen = cls, fields, frozen

    def __get__(self, obj: Any, owner: type | None = None) -> Any:
        fn = _init_fn(self.cls, self.fields, self.frozen)
        _attach(self.cls, fn)
        return fn if obj is None else fn.__get__(obj, owner)


def _init_fn(cls: type, fields: tuple[Field[Any], ...], frozen: bool) -> Callable[..., None]:
    self_name = "__dataclass_self__" if any(f.name == "self" for f in fields) else "self"
    ns: dict[str, Any] = {"__name__": cls.__module__, "_FACTORY": _FACTORY,
                          "__dataclass_builtins_object__": object}
    params, body = [self_name], []
    for f in fields:
        value = f.name
        if f.default_factory is not MISSING:
            ns[f"_dflt_{f.name}"] = f.default_factory
            params.append(f"{f.name}=_FACTORY")
            value = f"_dflt_{f.name}() if {f.name} is _FACTORY else {f.name}"
        elif f.default is not MISSING:
            ns[f"_dflt_{f.name}"] = f.default
            params.append(f"{f.name}=_dflt_{f.name}")
        else:
            params.append(f.name)
        body.append(f"__dataclass_builtins_object__.__setattr__({self_name},{f.name!r},{value})"
                    if frozen else f"{self_name}.{f.name}={value}")
    if hasattr(cls, "__post_init__"):
        body.append(f"{self_name}.__post_init__()")
    lines = "\n".join(f"  {b}" for b in body or ["pass"])
    exec(f"def __init__({','.join(params)}):\n{lines}", ns)
    fn: Callable[..., None] = ns["__init__"]
    fn.__annotations__ = {**{f.name: f.type for f in fields}, "return": None}
    return fn


def _key(names: tuple[str, ...]) -> Callable[[Any], tuple[Any, ...]]:
    """The tuple of the named attributes of an object (as ``(self.a, self.b,)``)."""
    if len(names) > 1:
        return attrgetter(*names)
    if not names:
        return lambda obj: ()
    get = attrgetter(names[0])
    return lambda obj: (get(obj),)


def _eq_fn(key: Callable[[Any], tuple[Any, ...]]) -> Callable[[Any, Any], Any]:
    def __eq__(self: Any, other: Any) -> Any:
        if other.__class__ is self.__class__:
            return key(self) == key(other)
        return NotImplemented

    return __eq__


def _hash_fn(key: Callable[[Any], tuple[Any, ...]]) -> Callable[[Any], int]:
    def __hash__(self: Any) -> int:
        return hash(key(self))

    return __hash__


def _repr_fn(names: tuple[str, ...]) -> Callable[[Any], str]:
    running: set[tuple[int, int]] = set()

    def __repr__(self: Any) -> str:
        guard = id(self), _thread.get_ident()
        if guard in running:
            return "..."
        running.add(guard)
        try:
            return (self.__class__.__qualname__ + "("
                    + ", ".join([f"{n}={getattr(self, n)!r}" for n in names]) + ")")
        finally:
            running.discard(guard)

    return __repr__


def _frozen_fns(cls: type, names: tuple[str, ...]) -> tuple[Callable[..., None], ...]:
    def __setattr__(self: Any, name: str, value: Any) -> None:
        if type(self) is cls or name in names:
            raise FrozenInstanceError(f"cannot assign to field {name!r}")
        super(cls, self).__setattr__(name, value)  # type: ignore[arg-type]

    def __delattr__(self: Any, name: str) -> None:
        if type(self) is cls or name in names:
            raise FrozenInstanceError(f"cannot delete field {name!r}")
        super(cls, self).__delattr__(name)  # type: ignore[arg-type]

    return __setattr__, __delattr__


def _getstate(self: Any) -> list[Any]:
    return [getattr(self, f.name) for f in dataclasses.fields(self)]


def _setstate(self: Any, state: list[Any]) -> None:
    for f, value in zip(dataclasses.fields(self), state, strict=False):
        object.__setattr__(self, f.name, value)


if TYPE_CHECKING:
    from dataclasses import dataclass as dataclass
else:
    dataclass = _dataclass
